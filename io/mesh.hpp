// Triangle meshes in the common surface-mesh formats: OBJ, PLY (ASCII and binary) and STL (ASCII
// and binary), read through CGAL's polygon-soup readers (CGAL::IO::read_OBJ / read_PLY / read_STL,
// the stream forms behind CGAL::IO::read_polygon_soup), so the bytes parsed are the bytes the
// certifier hashes. CGAL is included in mesh.cpp only.
//
// A mesh is a set of points in R^3 and triangles on them. Vertices with identical coordinates
// (equal as numbers: 0 and -0 are one vertex) are merged (STL repeats every vertex in each facet; CGAL's STL reader merges them too), so the
// triangles share vertices and form a simplicial complex. Faces that are not triangles are
// refused: a quad is not a simplex, and a certifier must not invent a triangulation of it.
//
// Written: PLY (ASCII, double coordinates, shortest round-trip decimals) by format_ply.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "io/complex.hpp"
#include "io/points.hpp"

namespace delcert::io {

enum class MeshFormat { obj, ply, stl };

const char* to_string(MeshFormat format);

struct Mesh {
  PointSet points;            // dimension 3
  Complex triangles;          // on points.size() vertices, every simplex of size 3
  std::size_t merged_vertices = 0;  // vertex copies merged into an earlier identical vertex
  // The file as written, before any merging (for messages in the user's terms, io/mesh_feedback.hpp): its vertices
  // in file order (STL, which has no vertex list: every facet corner, 3 per facet, corner k of facet f at 3f + k),
  // the line of each in an ASCII file (0 where unknown), its triangles on them, and the vertex of `points` each
  // became. The same bytes as `points` and `triangles`, so file_to_vertex[file_faces[f][k]] is triangles' f-th.
  std::vector<std::array<double, 3>> file_vertices;
  std::vector<long> file_vertex_lines;
  std::vector<std::array<std::size_t, 3>> file_faces;
  std::vector<int> file_to_vertex;
};

// The mesh format of a file, from its content (a first line "ply", a first word "solid") or,
// failing that, its extension (.obj, .ply, .stl, any case). nullopt: not recognisably one of them.
// Files tagged "OFF", "nOFF", "delcert-..." are never taken for a mesh format here.
std::optional<MeshFormat> detect_mesh_format(std::string_view text, const std::string& name);

// Throws InputError naming `name` (and the line, for the ASCII formats, where it is known): the
// reader failed, no triangles, a face that is not a triangle, an index out of range, a degenerate
// triangle (a vertex repeated after merging), a non-finite coordinate.
Mesh parse_mesh(const std::string& text, const std::string& name, MeshFormat format);

// ASCII PLY of a triangle mesh in R^3 (throws std::invalid_argument otherwise, as format_off).
std::string format_ply(const PointSet& points, const Complex& triangles);

// A surface mesh to `path`, as OFF or PLY by its extension (.off or .ply, any case): atomic.
// Throws InputError naming `path` for another extension.
enum class MeshOutputFormat { off, ply };
MeshOutputFormat mesh_output_format(const std::string& path, const std::string& option);
std::string format_mesh(const PointSet& points, const Complex& triangles, MeshOutputFormat format);

}  // namespace delcert::io
