// The producer's output rules, through the built binary: nothing is written unless every output
// is, and no output may be (the same file as) an input -- compared by file identity, not spelling.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/test_support.hpp"

namespace delcert::app {
namespace {

using test::binary;
using test::fixture;
using test::run;

std::string q(const std::string& s) { return "'" + s + "'"; }

// Copies the octahedron (6 points on the unit sphere) into `dir` and returns its path.
std::string octahedron_copy(const test::TempDir& dir) {
  const std::string p = dir.file("oct.off");
  test::write_text(p, test::slurp(fixture("points/octahedron.off")));
  return p;
}

TEST(Outputs, TangentialWritesNothingWhenTheStatsPathIsBad) {
  test::TempDir dir("out-stats");
  const std::string pts = octahedron_copy(dir);
  auto r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(pts) + " --out " +
               q(dir.file("complex.txt")) + " --stats " + q(dir.file("missing/stats.json")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("complex.txt")));
  // With a good stats path both are written.
  r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(pts) + " --out " +
          q(dir.file("complex.txt")) + " --stats " + q(dir.file("stats.json")));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("complex.txt")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("stats.json")));
}

TEST(Outputs, TangentialRefusesToOverwriteAnInput) {
  test::TempDir dir("out-same-t");
  const std::string pts = octahedron_copy(dir);
  const std::string before = test::slurp(pts);
  const std::string other_spelling = (dir.path() / "." / "oct.off").string();
  for (const std::string& opts : {" --out " + q(other_spelling), " --out " + q(dir.file("c.txt")) + " --stats " + q(pts),
                                  " --out " + q(dir.file("c.txt")) + " --stats " + q(dir.file("c.txt"))}) {
    auto r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(pts) + opts);
    EXPECT_EQ(r.status, 2) << opts << "\n" << r.output;
    EXPECT_EQ(test::slurp(pts), before) << opts;
    EXPECT_FALSE(std::filesystem::exists(dir.file("c.txt"))) << opts;
  }
  // A symbolic link to the input is the same file.
  std::filesystem::create_symlink(pts, dir.file("link.off"));
  auto r = run(binary("delcert") + " tangential --manifold builtin:sphere-2 --points " + q(pts) + " --out " +
               q(dir.file("link.off")));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("is the input file"), std::string::npos) << r.output;
  EXPECT_EQ(test::slurp(pts), before);
}

TEST(Outputs, SampleRefusesToOverwriteTheSpec) {
  test::TempDir dir("out-same-s");
  const std::string spec = dir.file("sphere.json");
  test::write_text(spec, test::slurp(fixture("manifolds/sphere-2.json")));
  const std::string before = test::slurp(spec);
  auto r = run(binary("delcert") + " sample --manifold " + q(spec) + " --eps 0.5 --out " + q((dir.path() / "." / "sphere.json").string()));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("is the input file"), std::string::npos) << r.output;
  EXPECT_EQ(test::slurp(spec), before);
}

TEST(Outputs, RefineRefusesToOverwriteAnInputAndChecksItsDirectory) {
  test::TempDir dir("out-same-r");
  const std::string pts = dir.file("points.txt");
  test::write_text(pts, test::slurp(fixture("points/octahedron.off")));
  const std::string before = test::slurp(pts);
  // DIR/points.txt is the input.
  auto r = run(binary("delcert") + " refine --manifold builtin:sphere-2 --points " + q(pts) + " --out " + q(dir.path().string()));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("is the input file"), std::string::npos) << r.output;
  EXPECT_EQ(test::slurp(pts), before);
  EXPECT_FALSE(std::filesystem::exists(dir.file("report.json")));
  // --out naming an existing file (here the input itself).
  r = run(binary("delcert") + " refine --manifold builtin:sphere-2 --points " + q(pts) + " --out " + q(pts));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(test::slurp(pts), before);
}

}  // namespace
}  // namespace delcert::app
