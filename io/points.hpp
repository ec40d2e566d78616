// Point sets: #points by dimension, stored row-major as doubles.
//
// Formats read (detected from the first line):
//   delcert-points v1     our format: a line "DIM COUNT", then COUNT lines of DIM numbers;
//                         blank lines and lines starting with '#' are ignored.
//   OFF                   an OFF file in R^3 (faces, if any, are ignored here).
//   nOFF                  GUDHI's n-dimensional OFF: "nOFF", the dimension, "NV NF NE", coordinates.
//   OBJ, PLY, STL         the vertices of a surface mesh (io/mesh.hpp; detected by content or extension).
// Written: delcert-points v1 (default), OFF or nOFF, always with the shortest decimal text that
// reads back to the same double, so every format round-trips bit for bit.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace delcert::io {

// The largest ambient dimension N a spec may declare. Every fixed-size scratch array over
// coordinates (core's neighbour search and star projection) and the complex reader's limit of
// N + 1 vertices per simplex follow from it.
inline constexpr int kMaxAmbientDimension = 64;

struct PointSet {
  int dimension = 0;
  std::vector<double> coordinates;  // #points by dimension, row-major

  std::size_t size() const { return dimension ? coordinates.size() / dimension : 0; }
  std::span<const double> point(std::size_t i) const {
    return {coordinates.data() + i * dimension, static_cast<std::size_t>(dimension)};
  }
  void push_back(std::span<const double> p) { coordinates.insert(coordinates.end(), p.begin(), p.end()); }
};

struct PointReadOptions {
  int expected_dimension = 0;     // 0: any; otherwise a mismatch is an error
  bool reject_duplicates = true;  // two bit-identical points are an error
};

// A points file as read: the points and, for messages about a point, the line it is on.
struct PointsFile {
  PointSet points;
  std::vector<long> lines;  // lines[i]: the 1-based line of point i in the file
};

// Throws InputError("file:line: ...") on anything malformed: unknown tag or version, bad counts,
// malformed/NaN/infinite numbers, wrong dimension, duplicate points.
PointSet read_points(const std::string& path, const PointReadOptions& options = {});
PointSet parse_points(const std::string& text, const std::string& name, const PointReadOptions& options = {});
PointsFile parse_points_file(const std::string& text, const std::string& name, const PointReadOptions& options = {});

enum class PointFormat { delcert, off, noff };

// OFF needs dimension 3 (throws std::invalid_argument otherwise); nOFF takes any dimension.
std::string format_points(const PointSet& points, PointFormat format = PointFormat::delcert);
void write_points(const std::string& path, const PointSet& points, PointFormat format = PointFormat::delcert);  // atomic

// The coordinate lines alone (one point per line), as used by every format above.
std::string format_coordinate_lines(const PointSet& points);

// Shortest round-trip decimal text of a double.
std::string format_double(double x);

}  // namespace delcert::io
