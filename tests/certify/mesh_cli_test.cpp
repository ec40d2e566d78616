// A surface mesher's user's first hour (issue 41), through the binary: a REFUTED mesh names its non-Delaunay edges
// in the file's own numbering (OBJ from 1; STL by facet corner, with how the corners were merged) and the flip that
// fixes each; --fix-out writes Del_RM(P) in the input's format, which then certifies; it writes nothing when
// Del_RM(P) is not certified, and is refused before any work where it cannot be written; a mesh off M says so first,
// with the largest certified distance. Fixtures: fixtures/certify/cgal-mesh-sphere.off (CGAL's mesher, frozen),
// with one edge flipped here.
#include <algorithm>
#include <array>
#include <filesystem>
#include <set>

#include "io/complex.hpp"
#include "support.hpp"

namespace delcert::certify::test {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }
const std::string kSphere = " --manifold builtin:sphere-2 --threads 2";

// CGAL's sphere mesh (exactly Del_RM of its vertices: check 12 certifies it) with the edge a-b of its face 0
// flipped to c-d (c opposite a-b in face 0, d in the other face at a-b).
struct Flipped {
  io::PointSet points;
  std::vector<std::vector<int>> original, faces;
  int a = 0, b = 0, c = 0, d = 0;
};

Flipped flip_first_edge() {
  const io::ComplexFile f = io::read_complex(fixture("certify/cgal-mesh-sphere.off"));
  Flipped r;
  r.points = *f.embedded_points, r.original = r.faces = f.complex.simplices;
  r.a = r.faces[0][0], r.b = r.faces[0][1], r.c = r.faces[0][2];
  for (std::size_t j = 1; j < r.faces.size(); ++j) {
    const auto& t = r.faces[j];
    if (std::count(t.begin(), t.end(), r.a) && std::count(t.begin(), t.end(), r.b)) {
      for (int v : t)
        if (v != r.a && v != r.b) r.d = v;
      r.faces[0] = {r.a, r.d, r.c}, r.faces[j] = {r.d, r.b, r.c};
      break;
    }
  }
  return r;
}

std::string coordinates(const io::PointSet& P, int v, const char* sep = " ") {
  return io::format_double(P.point(v)[0]) + sep + io::format_double(P.point(v)[1]) + sep + io::format_double(P.point(v)[2]);
}

std::string obj(const io::PointSet& P, const std::vector<std::vector<int>>& faces, double scale = 1) {
  std::string s;
  for (std::size_t v = 0; v < P.size(); ++v)
    s += "v " + io::format_double(scale * P.point(v)[0]) + " " + io::format_double(scale * P.point(v)[1]) + " " +
         io::format_double(scale * P.point(v)[2]) + "\n";
  for (const auto& t : faces) s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return s;
}

std::string stl(const io::PointSet& P, const std::vector<std::vector<int>>& faces) {  // every corner repeated
  std::string s = "solid flipped\n";
  for (const auto& t : faces) {
    s += "facet normal 0 0 0\nouter loop\n";
    for (int v : t) s += "vertex " + coordinates(P, v) + "\n";
    s += "endloop\nendfacet\n";
  }
  return s + "endsolid flipped\n";
}

std::set<std::vector<int>> sorted_set(std::vector<std::vector<int>> t) {
  for (auto& s : t) std::sort(s.begin(), s.end());
  return {t.begin(), t.end()};
}

std::string edge_text(int u, int v) {  // OBJ numbering, smaller first
  return std::to_string(std::min(u, v) + 1) + "-" + std::to_string(std::max(u, v) + 1);
}

// The certifier on a mesh file with --out and --fix-out (the mesh, fixed mesh and certificate paths given).
RunResult certify_with_fix_out(const TempDir& dir, const std::string& mesh, const std::string& fixed, const std::string& out) {
  return run(binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh) + " --out " + q(out) + " --fix-out " +
                 q(fixed),
             dir);
}

TEST(MeshCli, ARefutedObjNamesTheFlippedEdgeAndItsFlipAndFixOutCertifies) {
  TempDir dir("mesh-cli-obj");
  const Flipped F = flip_first_edge();
  const std::string mesh = dir.file("flipped.obj"), fixed = dir.file("fixed.obj"), out = dir.file("cert.json");
  write_text(mesh, obj(F.points, F.faces));
  RunResult r = certify_with_fix_out(dir, mesh, fixed, out);
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(last_line(r.out), "verdict: REFUTED");
  // The edge the flip made, in the OBJ's numbering and with its coordinates; its flip is the edge it replaced.
  const std::string line = "  edge " + edge_text(F.c, F.d) + "  (" +
                           coordinates(F.points, std::min(F.c, F.d), ", ") + ") - (" + coordinates(F.points, std::max(F.c, F.d), ", ") +
                           "); flip it to " + edge_text(F.a, F.b) + ": both new triangles are in Del_RM(P)\n";
  EXPECT_NE(r.out.find(line), std::string::npos) << line << r.out;
  EXPECT_NE(r.out.find("mesh 1 edge(s) of the mesh not in Del_RM(P) (not Delaunay):"), std::string::npos) << r.out;
  // Check 12 says what it certified and what failed.
  EXPECT_NE(r.out.find("Del_RM of the points: 438 m-simplices certified (all of them); the given complex is not it: 2 "
                       "simplices of Del_RM missing from it, 2 of its simplices not in Del_RM"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fix-out            " + fixed + ": Del_RM(P), 438 triangles, as OBJ"), std::string::npos) << r.out;
  const auto cert = nlohmann::json::parse(read_text(out));
  const auto& fb = cert["inputs"]["complex"]["mesh_feedback"];
  ASSERT_EQ(fb["non_delaunay_edges_total"], 1) << fb.dump(1);
  EXPECT_EQ(fb["non_delaunay_edges"][0]["edge"][0]["file_index"], std::min(F.c, F.d) + 1);
  EXPECT_EQ(fb["non_delaunay_edges"][0]["edge"][1]["file_index"], std::max(F.c, F.d) + 1);
  EXPECT_EQ(fb["non_delaunay_edges"][0]["flip"]["to"][0]["file_index"], std::min(F.a, F.b) + 1);
  EXPECT_EQ(fb["non_delaunay_edges"][0]["flip"]["to"][1]["file_index"], std::max(F.a, F.b) + 1);
  // The fixed mesh: the same vertices at the same indices, exactly CGAL's (Delaunay) triangles; it certifies.
  const io::ComplexFile back = io::read_complex(fixed);
  EXPECT_EQ(back.embedded_points->coordinates, F.points.coordinates);
  EXPECT_EQ(sorted_set(back.complex.simplices), sorted_set(F.original));
  r = run(binary() + kSphere + " --points " + q(fixed) + " --complex " + q(fixed) + " --out " + q(out), dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(last_line(r.out), "verdict: CERTIFIED");
  EXPECT_NE(r.out.find("Del_RM of the points: 438 m-simplices certified (all of them), exactly the given complex's"),
            std::string::npos) << r.out;
  EXPECT_FALSE(nlohmann::json::parse(read_text(out))["inputs"]["complex"].contains("mesh_feedback"));  // nothing to say
  // Byte-identical reruns (no times), --fix-out included.
  const std::string again = dir.file("again.obj");
  run(binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh) + " --fix-out " + q(again), dir);
  EXPECT_EQ(read_text(again), read_text(fixed));
}

TEST(MeshCli, AnStlNamesVerticesByFacetCornerAndSaysHowTheyWereMerged) {
  TempDir dir("mesh-cli-stl");
  const Flipped F = flip_first_edge();
  const std::string mesh = dir.file("flipped.stl"), fixed = dir.file("fixed.stl"), out = dir.file("cert.json");
  write_text(mesh, stl(F.points, F.faces));
  RunResult r = certify_with_fix_out(dir, mesh, fixed, out);
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("mesh STL: 1314 corner entries (3 per facet) merged into 221 vertices by exact coordinates"),
            std::string::npos) << r.out;
  const auto fb = nlohmann::json::parse(read_text(out))["inputs"]["complex"]["mesh_feedback"];
  ASSERT_EQ(fb["non_delaunay_edges_total"], 1) << fb.dump(1);
  // Each end of the edge is named by a corner of the file that holds c or d: facet 0 is (a, d, c).
  const auto& e = fb["non_delaunay_edges"][0]["edge"];
  std::set<std::pair<int, int>> corners = {{e[0]["facet"], e[0]["corner"]}, {e[1]["facet"], e[1]["corner"]}};
  EXPECT_EQ(corners, (std::set<std::pair<int, int>>{{0, 1}, {0, 2}})) << e.dump();
  for (int k : {0, 1}) {
    const int corner = e[k]["corner"];
    const int v = F.faces[0][corner];
    EXPECT_EQ(e[k]["coordinates"], nlohmann::json({io::format_double(F.points.point(v)[0]), io::format_double(F.points.point(v)[1]),
                                                   io::format_double(F.points.point(v)[2])}));
  }
  // The line of each corner in the ASCII file: facet f's corner k is on line 4 + 7f + k.
  EXPECT_EQ(e[0]["line"], 4 + e[0]["corner"].get<int>());
  // The fixed STL certifies, as its own points.
  r = run(binary() + kSphere + " --points " + q(fixed) + " --complex " + q(fixed), dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST(MeshCli, AMeshOffMSaysSoFirstWithTheLargestCertifiedDistance) {
  TempDir dir("mesh-cli-off-m");
  const Flipped F = flip_first_edge();
  const std::string mesh = dir.file("sphere-1.1.obj"), out = dir.file("cert.json");
  write_text(mesh, obj(F.points, F.original, 1.1));
  RunResult r = run(binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh), dir);
  // Del_RM of points scaled about the sphere's centre is theirs on M (the bisectors pass through the centre): the
  // verdict is CERTIFIED, and check 1's line, the first, opens with the points' distance to M.
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string first = r.out.substr(0, r.out.find('\n'));
  EXPECT_NE(first.find("CERTIFIED  [claimed]     the points are not on M: 221 of 221 point(s) off M beyond the residual "
                       "tolerance 0.000000001"), std::string::npos) << first;
  const auto at = first.find("every point is within ");
  ASSERT_NE(at, std::string::npos) << first;
  const double d = std::stod(first.substr(at + 22));
  EXPECT_GE(d, 0.1 - 1e-6);  // about |1.1 p| - 1 = 0.1 (p within 8e-6 of M)
  EXPECT_LE(d, 0.1 + 1e-4);
  EXPECT_NE(first.find(" of M (certified upper bound; the largest: point "), std::string::npos) << first;
  // Claimed tangential, the points are refused at once (exit 2), with the same facts and what to do; nothing written.
  r = run(binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh) + " --kind tangential --out " + q(out), dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(r.err.find("delcert-certify: " + mesh + ": the points are not on M: 221 of 221 point(s) off M"), 0u) << r.err;
  EXPECT_NE(r.err.find("--kind restricted"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(MeshCli, FixOutWritesNothingWhereDelRMIsNotCertifiedAndIsRefusedWhereItCannotBe) {
  TempDir dir("mesh-cli-fix-out");
  // The coarse ellipsoid: Del_RM(P) not known completely (mesher_test.cpp): UNDECIDED, and no mesh written.
  const std::string coarse = fixture("certify/cgal-mesh-ellipsoid-coarse.off"), fixed = dir.file("fixed.off");
  RunResult r = run(binary() + " --manifold " + q(fixture("specs/ellipsoid.json")) + " --threads 2 --points " + q(coarse) +
                        " --complex " + q(coarse) + " --fix-out " + q(fixed), dir);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("fix-out            not written: Del_RM(P) is not certified complete and pure (check 12: "),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the given complex is not proven to be it: "), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(fixed));
  // Refused before any work (exit 2, nothing written): another format's extension, a complex that is no mesh.
  const std::string oct = fixture("meshes/octahedron.obj"), out = dir.file("cert.json");
  r = run(binary() + kSphere + " --points " + q(oct) + " --complex " + q(oct) + " --out " + q(out) + " --fix-out " +
              q(dir.file("fixed.off")), dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("(OBJ here): name the file .obj"), std::string::npos) << r.err;
  r = run(binary() + kSphere + " --points " + q(fixture("points/octahedron.off")) + " --complex " +
              q(fixture("certify/octahedron.complex")) + " --out " + q(out) + " --fix-out " + q(dir.file("fixed.obj")), dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("is not a mesh (OFF, OBJ, PLY or STL)"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir.file("fixed.obj")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("fixed.off")));
  EXPECT_NE(run(binary() + " --help", dir).out.find("--fix-out"), std::string::npos);
}

}  // namespace
}  // namespace delcert::certify::test
