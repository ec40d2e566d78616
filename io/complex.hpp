// Simplicial complexes given by their maximal simplices, as 0-based vertex indices.
//
// Formats read (ComplexFormat; detected when not given, docs/formats.md "Detection"):
//   delcert-complex v1   a line "NUM_VERTICES NUM_SIMPLICES", then one simplex per line;
//                        blank lines and '#' comments are ignored.
//   OFF                  a surface mesh in R^3: its faces must be triangles ("3 a b c").
//   OBJ, PLY, STL        surface meshes in R^3 through CGAL's polygon-soup readers (io/mesh.hpp).
//   gudhi                no header: one simplex per line as vertex indices (GUDHI's simplex-tree
//                        exports), optionally followed by a filtration value ("0 1 2 0.35", from
//                        Python) or as GUDHI's C++ operator<< writes it ("2 2 1 0 0.35": the
//                        dimension, the vertices decreasing, the value); values are ignored; faces
//                        of listed simplices may be listed too and are dropped, the maximal
//                        simplices are kept.
// Written: delcert-complex v1, simplices in the order stored.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/points.hpp"

namespace delcert::io {

// At most this many vertices in one simplex: a simplex of an m-manifold sample in R^N has at most
// N + 1 <= 65 affinely independent vertices (the spec reader allows ambient dimension <= kMaxAmbientDimension = 64).
// Longer lines are refused by the reader (exit 2, with file and line), so no consumer ever
// meets a simplex whose 2^n faces could not be enumerated or whose n overflows `1u << n`.
inline constexpr std::size_t kMaxSimplexVertices = kMaxAmbientDimension + 1;

struct Complex {
  std::size_t num_vertices = 0;
  std::vector<std::vector<int>> simplices;  // #simplices, each a list of distinct vertex indices
};

enum class ComplexFormat { automatic, delcert, off, obj, ply, stl, gudhi };

// "auto", "delcert", "off", "obj", "ply", "stl", "gudhi" (the --complex-format values); nullopt otherwise.
std::optional<ComplexFormat> complex_format_from_name(const std::string& name);
const char* to_string(ComplexFormat format);
inline constexpr const char* kComplexFormatNames = "auto, delcert, off, obj, ply, stl, gudhi";

struct ComplexReadOptions {
  ComplexFormat format = ComplexFormat::automatic;
  // The number of vertices, for the headerless gudhi format (the size of the point set): every
  // index must be below it. 0: one more than the largest index.
  std::size_t num_vertices = 0;
};

struct ComplexFile {
  ComplexFormat format = ComplexFormat::automatic;  // the format read (never automatic)
  std::string note;  // what the reader changed, for the user: merged vertices, dropped faces; or empty
  Complex complex;
  std::optional<PointSet> embedded_points;  // the vertices, when the file carries them (OFF, OBJ, PLY, STL)
  // Lines in the file, for messages: of the header line that gives the vertex count, and of
  // each embedded point (empty without embedded points). 0 where unknown (OBJ, PLY, STL, gudhi).
  long counts_line = 0;
  std::vector<long> embedded_point_lines;
};

// Throws InputError("file:line: ...") on malformed counts, out-of-range or repeated indices,
// non-triangular OFF faces, the same simplex listed twice, unknown tags or versions, and (without
// a format) a file whose format cannot be told: the message lists the --complex-format values.
ComplexFile read_complex(const std::string& path, const ComplexReadOptions& options = {});
ComplexFile parse_complex(const std::string& text, const std::string& name, const ComplexReadOptions& options = {});

std::string format_complex(const Complex& complex);
void write_complex(const std::string& path, const Complex& complex);  // atomic

// A surface mesh as OFF: points in R^3 and triangles (throws std::invalid_argument otherwise).
std::string format_off(const PointSet& points, const Complex& triangles);
void write_off(const std::string& path, const PointSet& points, const Complex& triangles);  // atomic

}  // namespace delcert::io
