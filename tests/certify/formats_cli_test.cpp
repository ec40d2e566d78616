// delcert-certify on the formats users already have (issue 13 §3), through the binary: OBJ, PLY
// and STL meshes and GUDHI simplex lists give the same verdict as the native files, ambiguous and
// malformed files are refused with exit status 2, "file:line" and no certificate, and
// --residual-tolerance replaces the spec's tolerance and is recorded in the certificate.
// Fixtures: fixtures/meshes/ (fixtures/meshes/make_meshes.py).
#include <filesystem>

#include "support.hpp"

namespace delcert::certify::test {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }
const std::string kSphere = " --manifold builtin:sphere-2 --threads 2";

TEST(FormatsCli, EveryMeshFormatCertifiesTheOctahedron) {
  TempDir dir("formats");
  for (const std::string f : {"octahedron.obj", "octahedron.ply", "octahedron-binary.ply", "octahedron.stl",
                              "octahedron-binary.stl"}) {
    const std::string mesh = fixture("meshes/" + f), out = dir.file(f + ".json");
    // The mesh is both the points and the complex (as an OFF can be); --kind as the native test.
    RunResult r = run(binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh) +
                          " --kind tangential --out " + q(out),
                      dir);
    EXPECT_EQ(r.exit_code, 0) << f << "\n" << r.out << r.err;
    EXPECT_EQ(last_line(r.out), "verdict: CERTIFIED") << f;
    auto j = nlohmann::json::parse(read_text(out));
    const std::string ext = f.substr(f.rfind('.') + 1);
    EXPECT_EQ(j["inputs"]["complex"]["read"]["format"], ext) << f;
    EXPECT_EQ(j["inputs"]["complex"]["simplices"], 8) << f;
  }
  // The native files, for comparison.
  RunResult r = run(binary() + kSphere + " --points " + q(fixture("points/octahedron.off")) + " --complex " +
                        q(fixture("certify/octahedron.complex")),
                    dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST(FormatsCli, GudhiListsAreDetectedOrNamed) {
  TempDir dir("formats-gudhi");
  const std::string pts = " --points " + q(fixture("points/octahedron.off"));
  for (const std::string f : {"octahedron.gudhi", "octahedron-triangles.gudhi", "octahedron-filtered.gudhi",
                              "octahedron-simplex-tree.gudhi"}) {
    RunResult r = run(binary() + kSphere + pts + " --complex " + q(fixture("meshes/" + f)), dir);
    EXPECT_EQ(r.exit_code, 0) << f << "\n" << r.out << r.err;
    r = run(binary() + kSphere + pts + " --complex-format gudhi --complex " + q(fixture("meshes/" + f)), dir);
    EXPECT_EQ(r.exit_code, 0) << f << "\n" << r.out << r.err;
  }
  // Ambiguous: the message says which --complex-format values to choose; no certificate.
  const std::string amb = fixture("meshes/ambiguous.txt"), out = dir.file("cert.json");
  RunResult r = run(binary() + kSphere + pts + " --complex " + q(amb) + " --out " + q(out), dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(amb + ":1: cannot tell the complex format"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--complex-format gudhi"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // An unknown value of --complex-format is a usage error.
  r = run(binary() + kSphere + pts + " --complex-format xyz --complex " + q(amb), dir);
  EXPECT_EQ(r.exit_code, 2);
}

// The points and the complex are read on two threads; the first error is still the points' when
// both files are bad (or the complex is missing), and the complex's when only it is bad.
TEST(FormatsCli, ThePointsErrorComesFirstOnAnyThreadCount) {
  TempDir dir("formats-order");
  const std::string bad_points = dir.file("bad.points"), bad_complex = dir.file("bad.complex");
  write_text(bad_points, "delcert-points v1\n3 2\n0 0 1\n0 0 x\n");
  write_text(bad_complex, "delcert-complex v1\n2 3\n0 1 x\n");
  for (const std::string threads : {"1", "2"}) {
    const std::string base = binary() + " --manifold builtin:sphere-2 --threads " + threads;
    for (const std::string& complex : {bad_complex, dir.file("missing.complex")}) {
      RunResult r = run(base + " --points " + q(bad_points) + " --complex " + q(complex), dir);
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find(bad_points + ":4:"), std::string::npos) << threads << "\n" << r.err;
      EXPECT_EQ(r.err.find(complex), std::string::npos) << threads << "\n" << r.err;
    }
    RunResult r = run(base + " --points " + q(fixture("points/octahedron.off")) + " --complex " + q(bad_complex), dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(bad_complex + ":3:"), std::string::npos) << threads << "\n" << r.err;
  }
}

TEST(FormatsCli, MalformedMeshesAreRefusedWithFileAndLine) {
  TempDir dir("formats-bad");
  const struct {
    const char* file;
    const char* where;  // "FILE:LINE: ..." suffix after the path
  } cases[] = {{"bad-quad.obj", ":14: face 6 has 4 vertices"},
               {"bad-out-of-range.ply", ":23: face 7: vertex index 9 out of range"},
               {"bad-degenerate.stl", ":51: face 7 is degenerate"},
               {"bad-huge-count.ply", ":3: the PLY header announces 4000000000"}};
  for (const auto& c : cases) {
    const std::string path = fixture(std::string("meshes/") + c.file), out = dir.file("cert.json");
    RunResult r = run(binary() + kSphere + " --points " + q(fixture("points/octahedron.off")) + " --complex " + q(path) +
                          " --out " + q(out),
                      dir);
    EXPECT_EQ(r.exit_code, 2) << c.file << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(path + c.where), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.file;
    EXPECT_EQ(r.out.find("verdict"), std::string::npos) << r.out;
  }
  // Filtration values on some lines of a GUDHI list only.
  const std::string g = fixture("meshes/bad-filtration.gudhi");
  RunResult r = run(binary() + kSphere + " --points " + q(fixture("points/octahedron.off")) +
                        " --complex-format gudhi --complex " + q(g),
                    dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(g + ":1: this line does not end in a filtration value"), std::string::npos) << r.err;
}

// The octahedron scaled by 1 + 1e-7: |F(p)| = 2.0000001e-7 at every vertex, above the default 1e-9.
TEST(FormatsCli, ResidualToleranceOverridesTheSpecAndIsRecorded) {
  TempDir dir("formats-tol");
  const std::string mesh = fixture("meshes/octahedron-off-sphere.obj");
  const std::string base = binary() + kSphere + " --points " + q(mesh) + " --complex " + q(mesh);
  // Claimed tangential: T_p M is needed, so points off M are refused...
  RunResult r = run(base + " --kind tangential", dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--residual-tolerance"), std::string::npos) << r.err;
  // ... unless the tolerance admits them.
  const std::string out = dir.file("tol.json");
  r = run(base + " --kind tangential --residual-tolerance 1e-6 --out " + q(out), dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  auto j = nlohmann::json::parse(read_text(out));
  EXPECT_EQ(j["inputs"]["residual_tolerance"]["value"], "0.000001");
  EXPECT_EQ(j["inputs"]["residual_tolerance"]["source"], "--residual-tolerance");
  EXPECT_EQ(j["checks"][0]["details"]["residual_tolerance"], "0.000001");
  EXPECT_EQ(j["checks"][0]["details"]["off_manifold_points"], 0);
  // A mesher's output (restricted, the default for meshes) is accepted either way; the certificate
  // says which points are off M by the tolerance used.
  const std::string spec_out = dir.file("spec.json");
  r = run(base + " --out " + q(spec_out), dir);
  EXPECT_NE(r.exit_code, 2) << r.out << r.err;
  j = nlohmann::json::parse(read_text(spec_out));
  EXPECT_EQ(j["inputs"]["residual_tolerance"]["source"], "the manifold spec");
  EXPECT_EQ(j["inputs"]["residual_tolerance"]["value"], "0.000000001");
  EXPECT_EQ(j["checks"][0]["details"]["off_manifold_points"], 6);
  r = run(base + " --residual-tolerance 1/1000000 --out " + q(spec_out), dir);
  j = nlohmann::json::parse(read_text(spec_out));
  EXPECT_EQ(j["checks"][0]["details"]["off_manifold_points"], 0);
  // Refused values: exit 2, no certificate.
  for (const std::string bad : {"0", "-1e-6", "abc", "inf", "nan"}) {
    const std::string o = dir.file("bad.json");
    r = run(base + " --residual-tolerance=" + bad + " --out " + q(o), dir);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("--residual-tolerance: '" + bad + "'"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(o)) << bad;
  }
}

}  // namespace
}  // namespace delcert::certify::test
