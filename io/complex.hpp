// Simplicial complexes given by their maximal simplices, as 0-based vertex indices.
//
// Formats read (detected from the first line):
//   delcert-complex v1   a line "NUM_VERTICES NUM_SIMPLICES", then one simplex per line;
//                        blank lines and '#' comments are ignored.
//   OFF                  a surface mesh in R^3: its faces must be triangles ("3 a b c").
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

struct ComplexFile {
  Complex complex;
  std::optional<PointSet> embedded_points;  // the vertices, when the file carries them (OFF)
  // Lines in the file, for messages: of the header line that gives the vertex count, and of
  // each embedded point (empty without embedded points).
  long counts_line = 0;
  std::vector<long> embedded_point_lines;
};

// Throws InputError("file:line: ...") on malformed counts, out-of-range or repeated indices,
// non-triangular OFF faces, the same simplex listed twice, unknown tags or versions.
ComplexFile read_complex(const std::string& path);
ComplexFile parse_complex(const std::string& text, const std::string& name);

std::string format_complex(const Complex& complex);
void write_complex(const std::string& path, const Complex& complex);  // atomic

// A surface mesh as OFF: points in R^3 and triangles (throws std::invalid_argument otherwise).
std::string format_off(const PointSet& points, const Complex& triangles);
void write_off(const std::string& path, const PointSet& points, const Complex& triangles);  // atomic

}  // namespace delcert::io
