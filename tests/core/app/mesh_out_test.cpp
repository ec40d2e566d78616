// `delcert tangential --mesh-out` and `delcert refine --mesh-out` (issue 13 §3): the complex of a
// surface in R^3 as OFF or PLY, written atomically, read back by delcert-certify with the same
// verdict as the native files; refused (exit 2, nothing written) for another extension or another
// m, N.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/complex.hpp"
#include "io/points.hpp"
#include "tests/test_support.hpp"

namespace delcert::app {
namespace {

using test::binary;
using test::run;

std::string q(const std::string& s) { return "'" + s + "'"; }

std::string last_line(std::string t) {
  while (!t.empty() && t.back() == '\n') t.pop_back();
  auto p = t.find_last_of('\n');
  return p == std::string::npos ? t : t.substr(p + 1);
}

// The verdict line of delcert-certify and its exit status.
std::pair<int, std::string> certify(const std::string& args) {
  auto r = run(binary("delcert-certify") + " --manifold builtin:sphere-2 --threads 2 " + args);
  return {r.status, last_line(r.output)};
}

TEST(MeshOut, TangentialOffAndPlyRoundTripThroughTheCertifier) {
  test::TempDir dir("mesh-out-t");
  const std::string pts = dir.file("pts.txt");
  auto r = run(binary("delcert") + " sample --manifold builtin:sphere-2 --eps 0.5 --seed 3 --out " + q(pts));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const std::string mesh : {"m.off", "m.ply"}) {
    const std::string out = dir.file("c-" + mesh + ".txt"), m = dir.file(mesh);
    r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --threads 2 --points " + q(pts) + " --out " +
            q(out) + " --mesh-out " + q(m));
    ASSERT_EQ(r.status, 0) << r.output;
    // The mesh is the complex on the same points, bit for bit.
    const io::ComplexFile native = io::read_complex(out), back = io::read_complex(m);
    ASSERT_TRUE(back.embedded_points.has_value());
    EXPECT_EQ(back.embedded_points->coordinates, io::read_points(pts).coordinates);
    EXPECT_EQ(back.complex.simplices, native.complex.simplices);
    const auto want = certify("--points " + q(pts) + " --complex " + q(out));
    EXPECT_EQ(want.second, "verdict: CERTIFIED");
    EXPECT_EQ(certify("--points " + q(pts) + " --complex " + q(m) + " --kind tangential"), want) << mesh;
    EXPECT_EQ(certify("--points " + q(m) + " --complex " + q(m) + " --kind tangential"), want) << mesh;
  }
}

TEST(MeshOut, RefineWritesTheMeshOfItsOutput) {
  test::TempDir dir("mesh-out-r");
  const std::string out = dir.file("out"), m = dir.file("refined.off");
  auto r = run(binary("delcert") + " refine --manifold builtin:sphere-2 --eps 0.5 --threads 2 --out " + q(out) +
               " --mesh-out " + q(m));
  ASSERT_EQ(r.status, 0) << r.output;
  const io::ComplexFile native = io::read_complex(out + "/complex.txt"), back = io::read_complex(m);
  EXPECT_EQ(back.complex.simplices, native.complex.simplices);
  EXPECT_EQ(back.embedded_points->coordinates, io::read_points(out + "/points.txt").coordinates);
  const std::string claims = " --claims " + q(out + "/claims.json");
  const auto want = certify("--points " + q(out + "/points.txt") + " --complex " + q(out + "/complex.txt") + claims);
  EXPECT_EQ(want.second, "verdict: CERTIFIED");
  EXPECT_EQ(certify("--points " + q(m) + " --complex " + q(m) + " --kind tangential" + claims), want);
}

TEST(MeshOut, RefusedBeforeAnyWork) {
  test::TempDir dir("mesh-out-bad");
  const std::string pts = dir.file("pts.txt"), out = dir.file("c.txt");
  ASSERT_EQ(run(binary("delcert") + " sample --manifold builtin:sphere-3 --eps 0.9 --out " + q(pts)).status, 0);
  // Not a surface in R^3.
  auto r = run(binary("delcert") + " tangential --manifold builtin:sphere-3 --points " + q(pts) + " --out " + q(out) +
               " --mesh-out " + q(dir.file("m.off")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("m = 3, N = 4"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir.file("m.off")));
  r = run(binary("delcert") + " refine --manifold builtin:sphere-3 --eps 0.9 --out " + q(dir.file("o")) + " --mesh-out " +
          q(dir.file("m.ply")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o")));
  // An extension that names no written format; the mesh path equal to --out.
  r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(test::fixture("points/octahedron.off")) +
          " --out " + q(out) + " --mesh-out " + q(dir.file("m.stl")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("must end in .off or .ply"), std::string::npos) << r.output;
  r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(test::fixture("points/octahedron.off")) +
          " --out " + q(dir.file("same.off")) + " --mesh-out " + q(dir.file("same.off")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir.file("same.off")));
}

}  // namespace
}  // namespace delcert::app
