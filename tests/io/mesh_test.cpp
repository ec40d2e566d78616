// Surface meshes (io/mesh.hpp) and the headerless GUDHI simplex lists of io/complex.hpp: the same
// octahedron in every format reads to the same complex; detection; malformed files refused with
// file and line. Fixtures: fixtures/meshes/ (written by fixtures/meshes/make_meshes.py).
#include "io/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "tests/io/expect_input_error.hpp"
#include "tests/test_support.hpp"

namespace delcert::io {
namespace {

using test::fixture;

std::vector<std::vector<int>> sorted_simplices(const Complex& c) {
  auto s = c.simplices;
  for (auto& t : s) std::sort(t.begin(), t.end());
  std::sort(s.begin(), s.end());
  return s;
}

TEST(Mesh, EveryFormatReadsTheSameOctahedron) {
  const ComplexFile off = read_complex(fixture("complexes/octahedron.off"));
  ASSERT_TRUE(off.embedded_points.has_value());
  const struct {
    const char* file;
    ComplexFormat format;
    std::size_t merged;
  } cases[] = {{"octahedron.obj", ComplexFormat::obj, 0},          {"octahedron.ply", ComplexFormat::ply, 0},
               {"octahedron-binary.ply", ComplexFormat::ply, 0},   {"octahedron.stl", ComplexFormat::stl, 0},
               {"octahedron-binary.stl", ComplexFormat::stl, 0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const ComplexFile f = read_complex(fixture(std::string("meshes/") + c.file));
    EXPECT_EQ(f.format, c.format);
    ASSERT_TRUE(f.embedded_points.has_value());
    EXPECT_EQ(f.complex.num_vertices, 6u);
    EXPECT_EQ(f.embedded_point_lines.size(), 6u);
    // OBJ and PLY keep the vertex order, so the complex is the OFF's exactly.
    if (c.format != ComplexFormat::stl) {
      EXPECT_EQ(f.embedded_points->coordinates, off.embedded_points->coordinates);
      EXPECT_EQ(f.complex.simplices, off.complex.simplices);
    } else {
      // STL has no vertex list: vertices are numbered by first appearance. Same mesh up to that.
      std::vector<int> to_off(6);
      for (std::size_t i = 0; i < 6; ++i)
        for (std::size_t j = 0; j < 6; ++j)
          if (std::equal(f.embedded_points->point(i).begin(), f.embedded_points->point(i).end(),
                         off.embedded_points->point(j).begin()))
            to_off[i] = static_cast<int>(j);
      Complex renamed = f.complex;
      for (auto& t : renamed.simplices)
        for (int& v : t) v = to_off[v];
      EXPECT_EQ(sorted_simplices(renamed), sorted_simplices(off.complex));
    }
    // The points reader takes the mesh's vertices, in the complex reader's order.
    const PointSet p = read_points(fixture(std::string("meshes/") + c.file), PointReadOptions{3, true});
    EXPECT_EQ(p.coordinates, f.embedded_points->coordinates);
  }
}

// STL repeats every vertex in each of its facets; the reader merges identical coordinates.
TEST(Mesh, StlVerticesAreShared) {
  const std::string text = read_file(fixture("meshes/octahedron.stl"));
  std::size_t corners = 0;
  for (std::size_t at = text.find("vertex "); at != std::string::npos; at = text.find("vertex ", at + 1)) ++corners;
  EXPECT_EQ(corners, 24u);
  const Mesh m = parse_mesh(text, "oct.stl", MeshFormat::stl);
  EXPECT_EQ(m.points.size(), 6u);
  EXPECT_EQ(m.triangles.simplices.size(), 8u);
  const ComplexFile f = parse_complex(text, "oct.stl");
  EXPECT_EQ(m.merged_vertices, 18u);  // 24 corners, 6 vertices
  EXPECT_EQ(f.note, "18 vertex copies with identical coordinates merged (6 distinct vertices)");
  EXPECT_EQ(parse_complex(read_file(fixture("meshes/octahedron-binary.stl")), "b.stl").note, f.note);
}

TEST(Mesh, DetectionByContentThenExtension) {
  EXPECT_EQ(detect_mesh_format("ply\nformat ascii 1.0\n", "x.txt"), MeshFormat::ply);
  EXPECT_EQ(detect_mesh_format("solid a\nendsolid a\n", "x"), MeshFormat::stl);
  EXPECT_EQ(detect_mesh_format("v 0 0 0\n", "dir.v2/mesh.OBJ"), MeshFormat::obj);
  EXPECT_EQ(detect_mesh_format(std::string(84, '\0'), "part.stl"), MeshFormat::stl);
  EXPECT_FALSE(detect_mesh_format("OFF\n0 0 0\n", "mesh.obj").has_value());  // a tag wins over the extension
  EXPECT_FALSE(detect_mesh_format("0 1 2\n", "dir.obj/list").has_value());
}

TEST(Mesh, PlyAndOffOutputsReadBackBitForBit) {
  const ComplexFile off = read_complex(fixture("complexes/octahedron.off"));
  PointSet pts = *off.embedded_points;
  pts.coordinates[0] = 0.1 + 0.2;  // a double whose shortest decimal has 17 digits
  for (MeshOutputFormat f : {MeshOutputFormat::off, MeshOutputFormat::ply}) {
    const std::string text = format_mesh(pts, off.complex, f);
    const ComplexFile back = parse_complex(text, f == MeshOutputFormat::off ? "m.off" : "m.ply");
    ASSERT_TRUE(back.embedded_points.has_value());
    EXPECT_EQ(back.embedded_points->coordinates, pts.coordinates);
    EXPECT_EQ(back.complex.simplices, off.complex.simplices);
  }
  EXPECT_EQ(mesh_output_format("a/b.PLY", "--mesh-out"), MeshOutputFormat::ply);
  EXPECT_THROW(mesh_output_format("a/b.stl", "--mesh-out"), InputError);
}

TEST(Gudhi, ListWithFacesKeepsTheMaximalSimplices) {
  const ComplexFile g = read_complex(fixture("meshes/octahedron.gudhi"));
  EXPECT_EQ(g.format, ComplexFormat::gudhi);
  EXPECT_EQ(g.complex.num_vertices, 6u);
  const ComplexFile off = read_complex(fixture("complexes/octahedron.off"));
  EXPECT_EQ(sorted_simplices(g.complex), sorted_simplices(off.complex));
  EXPECT_NE(g.note.find("18 faces of other listed simplices dropped"), std::string::npos) << g.note;
  // A pure list of triangles is detected too; the vertex count comes from the caller when given.
  const ComplexFile t = parse_complex(read_file(fixture("meshes/octahedron-triangles.gudhi")), "t", {ComplexFormat::automatic, 10});
  EXPECT_EQ(t.format, ComplexFormat::gudhi);
  EXPECT_EQ(t.complex.num_vertices, 10u);
  EXPECT_EQ(t.complex.simplices, off.complex.simplices);
  EXPECT_TRUE(t.note.empty());
  // Mixed maximal dimensions are kept as they are (the certifier refutes the wrong dimension).
  const ComplexFile mixed = parse_complex("0 1 2\n2 3\n0 1\n", "m", {ComplexFormat::gudhi, 0});
  EXPECT_EQ(mixed.complex.simplices, (std::vector<std::vector<int>>{{0, 1, 2}, {2, 3}}));
}

TEST(Gudhi, AmbiguousFilesNameTheFormatsToChoose) {
  test::expect_input_error([](const std::string& p) { read_complex(p); }, fixture("meshes/ambiguous.txt"), 1,
                           "cannot tell the complex format");
  try {
    read_complex(fixture("meshes/ambiguous.txt"));
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--complex-format gudhi"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(kComplexFormatNames), std::string::npos) << e.what();
  }
  // Naming the format resolves it: the count line is then a simplex ("6 8" is out of range for 6 points).
  test::expect_input_error([](const std::string& p) { read_complex(p, {ComplexFormat::gudhi, 6}); },
                           fixture("meshes/ambiguous.txt"), 1, "vertex index 6 out of range");
  EXPECT_EQ(read_complex(fixture("meshes/ambiguous.txt"), {ComplexFormat::gudhi, 9}).complex.simplices.size(), 9u);
  // Filtration values on some lines only: the line without one is named.
  test::expect_input_error([](const std::string& p) { read_complex(p); }, fixture("meshes/bad-filtration.gudhi"), 1,
                           "this line does not end in a filtration value, but line 2 does ('0.25')");
}

// GUDHI's two exports of a filtered simplex tree (issue 41; fixtures checked against GUDHI 3.7.1):
// Python's `print(*s, f)` over get_filtration() and C++'s `std::cout << simplex_tree`
// ("dimension, vertices in decreasing order, value"). Both are detected, the values ignored and
// the faces dropped: the octahedron of the OFF file.
TEST(Gudhi, FiltrationValuesAreReadAndIgnored) {
  const ComplexFile off = read_complex(fixture("complexes/octahedron.off"));
  for (const char* name : {"meshes/octahedron-filtered.gudhi", "meshes/octahedron-simplex-tree.gudhi"})
    for (ComplexFormat format : {ComplexFormat::automatic, ComplexFormat::gudhi}) {
      const ComplexFile g = read_complex(fixture(name), {format, 6});
      EXPECT_EQ(g.format, ComplexFormat::gudhi) << name;
      EXPECT_EQ(g.complex.num_vertices, 6u) << name;
      EXPECT_EQ(sorted_simplices(g.complex), sorted_simplices(off.complex)) << name;
      EXPECT_NE(g.note.find("26 simplices read, filtration values ignored, 18 faces of other listed simplices dropped"),
                std::string::npos)
          << g.note;
    }
  EXPECT_NE(read_complex(fixture("meshes/octahedron-simplex-tree.gudhi")).note.find("GUDHI simplex tree"), std::string::npos);
  // One simplex with its value, in either layout; "inf" and exponents are values too.
  EXPECT_EQ(parse_complex("0 1 2 0.35\n", "f").complex.simplices, (std::vector<std::vector<int>>{{0, 1, 2}}));
  EXPECT_EQ(parse_complex("0 1 2 inf\n1 2 3 1e-05\n", "f").complex.simplices,
            (std::vector<std::vector<int>>{{0, 1, 2}, {1, 2, 3}}));
  EXPECT_EQ(parse_complex("0 0 0\n0 1 0\n1 1 0 0.5\n", "t").complex.simplices, (std::vector<std::vector<int>>{{0, 1}}));
  // The simplex-tree layout is told by its structure (its values may be integers: C++ prints 0 as
  // "0"): every line "k v_k .. v_0 f", decreasing vertices, every facet listed. Lines of integers
  // that are not so are a plain list (here "0 1 2" is a face of "1 2 0 3": one tetrahedron).
  EXPECT_EQ(parse_complex("0 1 2\n1 2 0 3\n", "p").complex.simplices, (std::vector<std::vector<int>>{{1, 2, 0, 3}}));
}

struct BadGudhi {
  const char* text;
  long line;
  const char* message;
};

class GudhiBadFiltration : public ::testing::TestWithParam<BadGudhi> {};

TEST_P(GudhiBadFiltration, IsRefusedWithTheLine) {
  for (ComplexFormat format : {ComplexFormat::automatic, ComplexFormat::gudhi}) {
    try {
      parse_complex(GetParam().text, "list.txt", {format, 0});
      ADD_FAILURE() << "read: " << GetParam().text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), GetParam().line) << e.what();
      EXPECT_NE(std::string(e.what()).find(GetParam().message), std::string::npos) << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, GudhiBadFiltration,
    ::testing::Values(
        // A value on one line only.
        BadGudhi{"0 1 2 0.5\n0 2 3\n", 2, "this line does not end in a filtration value, but line 1 does ('0.5')"},
        // A value that is not a number, NaN, or not at the end.
        BadGudhi{"0 1 2 0.5\n0 2 3 nan\n", 2, "does not end in a filtration value"},
        BadGudhi{"0 1 0.5 2\n", 1, "expected a vertex index (a non-negative integer), found '0.5'"},
        // A value without a simplex.
        BadGudhi{"0 1 0.5\n0.25\n", 2, "a filtration value without a simplex"},
        // Simplex-tree lines whose facets are not listed are not a simplex tree: then "1 1 0 0.5"
        // is the simplex {1, 1, 0} and its repeated vertex is refused.
        BadGudhi{"1 1 0 0.5\n", 1, "vertex 1 repeated in a simplex"}));

struct BadMesh {
  const char* file;
  ComplexFormat format;
  long line;
  const char* message_part;
};

class MalformedMesh : public ::testing::TestWithParam<BadMesh> {};

TEST_P(MalformedMesh, ReportsFileLineAndProblem) {
  const BadMesh& c = GetParam();
  test::expect_input_error([&](const std::string& p) { read_complex(p, {c.format, 0}); },
                           fixture(std::string("meshes/") + c.file), c.line, c.message_part);
}

INSTANTIATE_TEST_SUITE_P(
    Refused, MalformedMesh,
    ::testing::Values(BadMesh{"bad-quad.obj", ComplexFormat::automatic, 14, "face 6 has 4 vertices; only triangles"},
                      BadMesh{"bad-out-of-range.ply", ComplexFormat::automatic, 23, "vertex index 9 out of range"},
                      BadMesh{"bad-degenerate.stl", ComplexFormat::automatic, 51, "face 7 is degenerate"},
                      BadMesh{"bad-huge-count.ply", ComplexFormat::automatic, 3, "announces 4000000000 vertex elements"},
                      BadMesh{"bad-filtration.gudhi", ComplexFormat::gudhi, 1, "does not end in a filtration value, but line 2 does"},
                      BadMesh{"octahedron.obj", ComplexFormat::off, 2, "--complex-format off: expected the first line 'OFF'"},
                      BadMesh{"octahedron.gudhi", ComplexFormat::delcert, 1, "expected the first line 'delcert-complex v1'"},
                      BadMesh{"octahedron.gudhi", ComplexFormat::stl, 0, "not a readable STL file"}));

TEST(Mesh, ReaderFailuresAndEmptyMeshes) {
  test::expect_input_error([](const std::string& p) { parse_complex("v 0 0 0\nv 1 nope 0\n", p); }, "m.obj", 0,
                           "not a readable OBJ file");
  test::expect_input_error(
      [](const std::string& p) {
        parse_complex("ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\n"
                      "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n", p);
      },
      "m.ply", 0, "has no faces");
  test::expect_input_error([](const std::string& p) { parse_complex("ply\nformat ascii 1.0\n", p); }, "m", 0,
                           "without 'end_header'");
  test::expect_input_error(
      [](const std::string& p) { parse_complex("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 2 1\n", p); }, "m.obj", 0,
      "simplex 1 listed twice");
}

// CGAL's PLY reader trusts the header (undefined behaviour on the first two, found by fuzzing;
// gigabytes asked for by the third): io/mesh.cpp checks it first.
TEST(Mesh, PlyHeadersAreCheckedBeforeCgalReadsThem) {
  const std::string tail = "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
  test::expect_input_error([](const std::string& p) {
    parse_complex("ply\nformat ascii 1.0\nproperty double x\nelement vertex 0\nend_header\n", p);
  }, "m.ply", 3, "a property before any element");
  test::expect_input_error([&](const std::string& p) {
    parse_complex("ply\nformat ascii 1.0\nelement vertex 0\nproperty double x\nproperty uint16 y\nproperty double z\n" + tail, p);
  }, "m.ply", 9, "vertex coordinate y is of type 'uint16'");
  test::expect_input_error([](const std::string& p) {
    parse_complex("ply\nformat ascii 1.0\nelement vertex 0\nproperty double x\nproperty double y\nproperty double z\n"
                  "element face 0\nproperty list int int vertex_indices\nend_header\n", p);
  }, "m.ply", 8, "list length type 'int'");
  test::expect_input_error([&](const std::string& p) {
    parse_complex("ply\nformat ascii 1.0\nelement vertex 0\nproperty double x\nproperty double y\n" + tail, p);
  }, "m.ply", 8, "no property z");
  test::expect_input_error([&](const std::string& p) {
    parse_complex("ply\nformat ascii 1.0\nelement vertex 0\nproperty double x\nproperty double y\nproperty double z\n"
                  "element vertex 0\nproperty uint32 x\n" + tail, p);
  }, "m.ply", 7, "a second element 'vertex'");
  test::expect_input_error([&](const std::string& p) { parse_complex("ply\nformat text 1.0\n" + tail, p); }, "m.ply", 2,
                           "the second line must be 'format");
}

}  // namespace
}  // namespace delcert::io
