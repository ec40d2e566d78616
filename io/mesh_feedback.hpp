// What a surface mesher's user needs next to a verdict (issue 41): the edges of their mesh that are not edges of the
// restricted Delaunay complex Del_RM(P), named as their file names the vertices (before any merging of identical
// coordinates), with the flip that fixes each where there is one; and Del_RM(P) written back as a mesh in the
// format of their file, to replace it.
//
// Presentation only, outside the trust boundary (docs/design.md §5): delcert-certify calls it after the
// certificate is finished, with check 12's Del_RM(P) (certified complete and pure) and the bytes of the mesh file
// the certificate hashed. Nothing here decides or changes a verdict; what it derives (an edge not in Del_RM(P), a
// flip) is read off the certified triangles by set operations on vertex indices, no geometry.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/complex.hpp"

namespace delcert::io {

// A surface mesh file (OFF, OBJ, PLY, STL) as its user wrote it, and the certifier's vertex each of its vertices
// became (identical coordinates merged, in order of first appearance: the numbering of the certificate).
struct MeshSource {
  ComplexFormat format = ComplexFormat::off;  // off, obj, ply or stl
  std::string path;
  std::vector<std::array<double, 3>> vertices;  // in file order; STL: every facet corner (corner k of facet f: 3f + k)
  std::vector<long> vertex_lines;               // the line of each in an ASCII file, else 0
  std::vector<std::array<std::size_t, 3>> faces;  // the triangles, on file vertices, as written
  std::vector<int> to_vertex;                   // file vertex -> certified vertex
  std::vector<std::size_t> first_copy;          // certified vertex -> its first file vertex
};

// The mesh format of the complex file `text` (named `path`), as the complex reader would take it: `given` when it
// is one of off, obj, ply, stl; automatic: the tag OFF on the first line, else io/mesh.hpp's detection. nullopt
// when it is not a mesh format (delcert-complex, gudhi, or not recognisable).
std::optional<ComplexFormat> mesh_format_of(const std::string& text, const std::string& path, ComplexFormat given);

// Throws InputError as the complex reader does on the same bytes.
MeshSource parse_mesh_source(const std::string& text, const std::string& path, ComplexFormat format);

// How the file's vertices became the certifier's, for the user ("STL: 1236 corner entries merged into 412 vertices
// by exact coordinates"); the numbering the messages use ("OBJ numbers vertices from 1, as its f lines do").
std::string merge_note(const MeshSource& source);
std::string numbering_note(const MeshSource& source);

// A file vertex as the user finds it in the file: "vertex 13 (line 14)", "facet 4 corner 2 (line 31)".
std::string vertex_name(const MeshSource& source, std::size_t file_vertex);

struct MeshFeedback {
  nlohmann::json json;             // the certificate's "mesh_feedback" (docs/certificate.md)
  std::vector<std::string> lines;  // for stdout, without the trailing newline
};

// The edges of the given mesh that are not edges of `del_rm` (Del_RM(P)'s triangles in the certifier's vertex
// indices, certified complete and pure by check 12, so that an edge in none of them is not in Del_RM(P)), in the
// file's numbering with their coordinates. An edge in exactly two triangles (a, b, c) and (a, b, d) of the mesh has
// a flip when c-d is an edge of Del_RM(P) (and not already one of the mesh): the flip replaces a-b by c-d. Then the
// triangles of the mesh not in Del_RM(P) and those of Del_RM(P) not in the mesh. At most `shown` of each printed;
// the JSON holds at most 1000 of each and the totals.
MeshFeedback non_delaunay_edges(const MeshSource& source, const std::vector<std::vector<int>>& del_rm,
                                std::size_t shown = 20);

// `del_rm` (as above) as a mesh file in the source's format: OFF, OBJ or ASCII PLY with every vertex of the file
// in file order (the file's indices stay valid, duplicates included), ASCII STL with each facet's corners. The
// triangles the mesh and Del_RM(P) share come first, in file order and orientation; the others after them, each
// oriented consistently with a neighbour already written where it has one (across a shared edge), else in
// increasing vertex order. Reading the file back gives the points of the source in the same numbering and exactly
// Del_RM(P)'s triangles (STL: in order of first appearance of the corners).
std::string format_fixed_mesh(const MeshSource& source, const std::vector<std::vector<int>>& del_rm);

// The file-name extension of a mesh format, lower case: "off", "obj", "ply", "stl".
const char* mesh_extension(ComplexFormat format);

// delcert-certify --fix-out FILE, before any work: the manifold is a surface (m = 2), --complex is a mesh (OFF,
// OBJ, PLY, STL, by --complex-format or detected), FILE ends in that format's extension (any case) and is a
// writable output that is none of the inputs nor `other_outputs` (io::check_output_path). Throws InputError
// (exit 2) saying which and what to do.
void check_fix_out(const std::string& fix_out, const std::string& manifold, const std::string& complex,
                   const std::string& complex_format, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& other_outputs);

// What delcert-certify adds for a given surface mesh after the certificate is finished: nothing unless the
// certificate's `inputs` name a complex read as OFF, OBJ, PLY or STL, of a surface (m = 2). The file is read again
// and must hash (`sha256`) to the certificate's inputs.complex.sha256 (else InputError: it changed during the run).
// `del_rm`: check 12's Del_RM(P) when certified complete and pure, else empty, `why_not` then check 12's reason. The
// edges are listed for a complex claimed restricted (`restricted`) that is not Del_RM(P). With `fix_out` (its path,
// or empty) `fixed_mesh` (format_fixed_mesh) is made when Del_RM(P) is certified, and the last line says what
// --fix-out did.
struct MeshReport {
  nlohmann::json json;                    // the certificate's inputs.complex.mesh_feedback, or null
  std::vector<std::string> lines;         // stdout, after the checks
  std::optional<std::string> fixed_mesh;  // --fix-out's content
};
MeshReport report_mesh(const nlohmann::json& inputs, bool restricted, const std::vector<std::vector<int>>& del_rm,
                       const std::string& why_not, const std::string& fix_out,
                       const std::function<std::string(std::string_view)>& sha256);

}  // namespace delcert::io
