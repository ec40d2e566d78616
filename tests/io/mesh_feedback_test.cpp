// io/mesh_feedback.hpp: a mesh's edges that are not in Del_RM(P), in the numbering of the user's file (OBJ from 1,
// STL by facet corner, duplicates by their first copy), the flip that fixes each, and Del_RM(P) written back in the
// file's format and numbering. The functions are combinatorial (vertex indices, no geometry), so a made-up
// "Del_RM(P)" tests them: the octahedron of fixtures/meshes/ with one edge flipped.
#include "io/mesh_feedback.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "tests/test_support.hpp"

namespace delcert::io {
namespace {

using test::fixture;
using Triangles = std::vector<std::vector<int>>;

std::set<std::vector<int>> as_set(Triangles t) {
  for (auto& s : t) std::sort(s.begin(), s.end());
  return {t.begin(), t.end()};
}

// The octahedron of octahedron.obj (0-based: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z) with its edge 0-2 (OBJ's 1-3,
// in the triangles 0-2-4 and 2-0-5) flipped to 4-5 (OBJ's 5-6).
Triangles flipped_octahedron() {
  return {{1, 2, 4}, {1, 3, 4}, {3, 0, 4}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}, {0, 4, 5}, {2, 4, 5}};
}

MeshSource source(const std::string& file) {
  const std::string text = read_file(file);
  const auto format = mesh_format_of(text, file, ComplexFormat::automatic);
  EXPECT_TRUE(format.has_value()) << file;
  return parse_mesh_source(text, file, *format);
}

// Every directed edge at most once: the triangles are oriented consistently.
bool consistently_oriented(const Triangles& t) {
  std::set<std::pair<int, int>> seen;
  for (const auto& s : t)
    for (int k = 0; k < 3; ++k)
      if (!seen.insert({s[k], s[(k + 1) % 3]}).second) return false;
  return true;
}

TEST(MeshFeedback, TheNonDelaunayEdgeIsNamedInTheFilesNumberingWithItsFlip) {
  const MeshSource src = source(fixture("meshes/octahedron.obj"));
  ASSERT_EQ(src.vertices.size(), 6u);
  const MeshFeedback fb = non_delaunay_edges(src, flipped_octahedron());
  ASSERT_EQ(fb.json["non_delaunay_edges_total"], 1);
  const auto& e = fb.json["non_delaunay_edges"][0];
  // OBJ numbers vertices from 1: the edge is 1-3, with the lines of its v entries and its exact coordinates.
  EXPECT_EQ(e["edge"][0]["file_index"], 1);
  EXPECT_EQ(e["edge"][1]["file_index"], 3);
  EXPECT_EQ(e["edge"][0]["line"], 2);  // line 1 is the comment
  EXPECT_EQ(e["edge"][1]["coordinates"], nlohmann::json({"0", "1", "0"}));
  EXPECT_EQ(e["in_triangles"], 2);
  EXPECT_EQ(e["flip"]["to"][0]["file_index"], 5);
  EXPECT_EQ(e["flip"]["to"][1]["file_index"], 6);
  EXPECT_EQ(e["flip"]["new_triangles_in_Del_RM"], true);
  EXPECT_EQ(fb.json["triangles_not_in_Del_RM_total"], 2);
  EXPECT_EQ(fb.json["Del_RM_triangles_missing_total"], 2);
  EXPECT_TRUE(fb.json["merged"].is_null());
  // The printed line says the same.
  bool printed = false;
  for (const auto& l : fb.lines)
    printed = printed || (l.find("edge 1-3  (1, 0, 0) - (0, 1, 0); flip it to 5-6: both new triangles are in Del_RM(P)") !=
                          std::string::npos);
  EXPECT_TRUE(printed) << fb.json.dump(1);
}

TEST(MeshFeedback, NoFlipWhenTheOtherDiagonalIsNotInDelRM) {
  const MeshSource src = source(fixture("meshes/octahedron.obj"));
  // "Del_RM" without the edge 0-2 and without 4-5: the two triangles at 0-2 replaced by a different pair is not
  // a complex of the octahedron, but the function reads only the sets: edge 1-3 is not in it, 5-6 neither.
  const Triangles rm = {{1, 2, 4}, {1, 3, 4}, {3, 0, 4}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const MeshFeedback fb = non_delaunay_edges(src, rm);
  ASSERT_EQ(fb.json["non_delaunay_edges_total"], 1);
  EXPECT_TRUE(fb.json["non_delaunay_edges"][0]["flip"].is_null());
  EXPECT_NE(fb.json["non_delaunay_edges"][0]["advice"].get<std::string>().find("not in Del_RM(P) either"), std::string::npos);
}

TEST(MeshFeedback, StlVerticesAreNamedByTheirFirstFacetCorner) {
  const MeshSource src = source(fixture("meshes/octahedron.stl"));
  EXPECT_EQ(src.vertices.size(), 24u);  // 8 facets, 3 corners each
  EXPECT_EQ(src.first_copy.size(), 6u);
  EXPECT_EQ(merge_note(src), "STL: 24 corner entries (3 per facet) merged into 6 vertices by exact coordinates");
  // The certifier's vertex v is the v-th distinct corner in file order; the feedback names it by that corner.
  const MeshFeedback fb = non_delaunay_edges(src, [&] {
    // The same flip, in this file's certified numbering: map the OBJ's vertices by coordinates.
    const MeshSource obj = source(fixture("meshes/octahedron.obj"));
    std::map<std::array<double, 3>, int> of;
    for (std::size_t v = 0; v < src.first_copy.size(); ++v) of[src.vertices[src.first_copy[v]]] = static_cast<int>(v);
    Triangles t = flipped_octahedron();
    for (auto& s : t)
      for (int& v : s) v = of.at(obj.vertices[v]);
    return t;
  }());
  ASSERT_EQ(fb.json["non_delaunay_edges_total"], 1);
  const auto& e = fb.json["non_delaunay_edges"][0]["edge"];
  // +x and +y: corners 0 and 1 of facet 0 (the STL lists facet 1-3-5 first), on the file's lines 4 and 5.
  EXPECT_EQ(e[0]["facet"], 0);
  EXPECT_EQ(e[0]["corner"], 0);
  EXPECT_EQ(e[1]["facet"], 0);
  EXPECT_EQ(e[1]["corner"], 1);
  EXPECT_EQ(e[0]["coordinates"], nlohmann::json({"1", "0", "0"}));
  EXPECT_TRUE(fb.json["merged"].is_string());
  bool printed = false;
  for (const auto& l : fb.lines) printed = printed || l.find("edge facet 0 corner 0 (line 4) - facet 0 corner 1 (line 5)") != std::string::npos;
  EXPECT_TRUE(printed) << fb.json.dump(1);
}

TEST(MeshFeedback, DuplicatedObjVerticesKeepTheirFileIndices) {
  test::TempDir dir("mesh-feedback-dup");
  // The octahedron with +x written twice (vertex 7 is a copy of vertex 1) and used by the last face.
  std::string text = read_file(fixture("meshes/octahedron.obj"));
  text.insert(text.find("f "), "v 1.0 0.0 0.0\n");
  text.replace(text.rfind("f 1 4 6"), 7, "f 7 4 6");
  const std::string file = dir.file("dup.obj");
  write_file_atomically(file, text);
  const MeshSource src = source(file);
  ASSERT_EQ(src.vertices.size(), 7u);
  EXPECT_EQ(src.to_vertex[6], 0);
  EXPECT_EQ(src.first_copy[0], 0u);
  EXPECT_NE(merge_note(src).find("OBJ: 7 vertices merged into 6 by exact coordinates"), std::string::npos);
  // Written back: all 7 vertices at their indices, the kept face still on vertex 7.
  const std::string fixed = format_fixed_mesh(src, flipped_octahedron());
  const std::string out = dir.file("fixed.obj");
  write_file_atomically(out, fixed);
  EXPECT_NE(fixed.find("f 7 4 6\n"), std::string::npos) << fixed;
  const ComplexFile back = read_complex(out);
  EXPECT_EQ(back.embedded_points->size(), 6u);  // merged again, identically
  EXPECT_EQ(as_set(back.complex.simplices), as_set(flipped_octahedron()));
}

// Triangles as sets of their corners' coordinates: comparable across numberings (STL renumbers by first corner).
std::set<std::set<std::vector<double>>> geometric(const ComplexFile& f) {
  std::set<std::set<std::vector<double>>> out;
  for (const auto& t : f.complex.simplices) {
    std::set<std::vector<double>> c;
    for (int v : t) c.insert({f.embedded_points->point(v).begin(), f.embedded_points->point(v).end()});
    out.insert(c);
  }
  return out;
}

TEST(MeshFeedback, TheFixedMeshReadsBackAsDelRMInTheSameFormatAndNumbering) {
  test::TempDir dir("mesh-feedback-fixed");
  const MeshSource obj = source(fixture("meshes/octahedron.obj"));
  const std::string ref_file = dir.file("reference.obj");  // the flipped octahedron, as the reference
  write_file_atomically(ref_file, format_fixed_mesh(obj, flipped_octahedron()));
  const auto reference = geometric(read_complex(ref_file));
  for (const std::string f : {"octahedron.obj", "octahedron.ply", "octahedron-binary.ply", "octahedron.stl",
                              "octahedron-binary.stl"}) {
    SCOPED_TRACE(f);
    const MeshSource src = source(fixture("meshes/" + f));
    const ComplexFile in = read_complex(fixture("meshes/" + f));
    ASSERT_TRUE(consistently_oriented(in.complex.simplices));
    // Del_RM in this file's numbering (PLY and STL number the octahedron's vertices their own way).
    std::map<std::array<double, 3>, int> of;
    for (std::size_t v = 0; v < src.first_copy.size(); ++v) of[src.vertices[src.first_copy[v]]] = static_cast<int>(v);
    Triangles rm = flipped_octahedron();
    for (auto& s : rm)
      for (int& v : s) v = of.at(obj.vertices[v]);
    const std::string out = dir.file("fixed-" + f);
    write_file_atomically(out, format_fixed_mesh(src, rm));
    const ComplexFile back = read_complex(out);
    EXPECT_EQ(back.format, src.format);
    EXPECT_EQ(geometric(back), reference);
    EXPECT_TRUE(consistently_oriented(back.complex.simplices));
    if (src.format == ComplexFormat::stl) continue;  // (no vertex list: renumbered by first corner)
    EXPECT_EQ(back.embedded_points->coordinates, in.embedded_points->coordinates);  // same points, same numbering
    EXPECT_EQ(as_set(back.complex.simplices), as_set(rm));
    // The six triangles the mesh keeps come first, as written (orientation included).
    Triangles kept;
    for (const auto& t : in.complex.simplices)
      if (as_set(rm).count(*as_set({t}).begin())) kept.push_back(t);
    ASSERT_EQ(kept.size(), 6u);
    EXPECT_TRUE(std::equal(kept.begin(), kept.end(), back.complex.simplices.begin()));
  }
}

void expect_refused(const std::function<void()>& f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "not refused: " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(MeshFeedback, FixOutIsRefusedBeforeAnyWorkWhereItCannotBeWritten) {
  test::TempDir dir("mesh-feedback-usage");
  const std::string obj = fixture("meshes/octahedron.obj"), sphere = "builtin:sphere-2";
  const std::vector<std::string> inputs = {sphere, obj};
  check_fix_out(dir.file("fixed.OBJ"), sphere, obj, "auto", inputs, {});  // any case
  expect_refused([&] { check_fix_out(dir.file("fixed.ply"), sphere, obj, "auto", inputs, {}); },
                     "name the file .obj");
  expect_refused([&] { check_fix_out(dir.file("fixed.obj"), sphere, "", "auto", inputs, {}); }, "no --complex");
  expect_refused([&] { check_fix_out(dir.file("fixed.obj"), "builtin:sphere-3", obj, "auto", inputs, {}); },
                     "a surface in R^3");
  const std::string native = fixture("certify/octahedron.complex");
  expect_refused([&] { check_fix_out(dir.file("fixed.obj"), sphere, native, "auto", {sphere, native}, {}); },
                     "is not a mesh");
  expect_refused([&] { check_fix_out(obj, sphere, obj, "auto", inputs, {}); }, "--fix-out");  // an input
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace delcert::io
