// `delcert tangential`: a round trip through files, and bad input giving exit status 2 with no
// output file.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/tangential/tangential_complex.hpp"
#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "tests/core/tangential/test_support.hpp"
#include "tests/test_paths.hpp"

namespace delcert::tangential {
namespace {

namespace fs = std::filesystem;

class TangentialCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("delcert_tangential_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs delcert with the arguments; returns its exit status.
  int run(const std::string& args) {
    const std::string cmd = std::string(DELCERT_BINARY_DIR) + "/delcert tangential " + args + " > " +
                            (dir_ / "stdout.txt").string() + " 2> " + (dir_ / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string stderr_text() const { return io::read_file(path("stderr.txt")); }

  fs::path dir_;
};

TEST_F(TangentialCli, RoundTrip) {
  auto s = testing::builtin_sample("sphere-2", 500, 201);
  io::write_points(path("points.txt"), s.points);
  ASSERT_EQ(run("--manifold builtin:sphere-2 --points " + path("points.txt") + " --out " + path("complex.txt") +
                " --stats " + path("stats.json") + " --threads 2"),
            0)
      << stderr_text();
  // The file holds the library's complex.
  io::ComplexFile file = io::read_complex(path("complex.txt"));
  TangentialComplex tc(s.points, s.planes);
  EXPECT_EQ(file.complex.simplices, tc.assemble().complex.simplices);
  EXPECT_EQ(file.complex.num_vertices, 500u);
  // The summary.
  auto j = nlohmann::json::parse(io::read_file(path("stats.json")));
  EXPECT_EQ(j["format"], "delcert-tangential-stats v1");
  EXPECT_EQ(j["points"], 500);
  EXPECT_EQ(j["euler_characteristic"], 2);
  EXPECT_EQ(j["expected_euler_characteristic"], 2);
  EXPECT_EQ(j["consistent"], true);
  EXPECT_EQ(j["inconsistent_simplices"]["count"], 0);
  EXPECT_EQ(j["pseudomanifold"], true);
  EXPECT_EQ(j["maximal_simplices"]["by_dimension"][2], 2 * 500 - 4);
  EXPECT_EQ(j["star_simplices"], 3 * (2 * 500 - 4));
  EXPECT_GT(j["max_radius"].get<double>(), 0.0);
  EXPECT_TRUE(j["time_seconds"].contains("stars"));
  // The same bytes with one thread.
  ASSERT_EQ(run("--manifold builtin:sphere-2 --points " + path("points.txt") + " --out " + path("complex1.txt") +
                " --threads 1"),
            0);
  EXPECT_EQ(io::read_file(path("complex.txt")), io::read_file(path("complex1.txt")));
}

TEST_F(TangentialCli, BadInputExitsTwoWithoutOutput) {
  auto s = testing::builtin_sample("sphere-2", 50, 202);
  io::write_points(path("points.txt"), s.points);
  const std::string out = " --out " + path("complex.txt") + " --stats " + path("stats.json");
  // Points in R^3 for a manifold in R^4.
  EXPECT_EQ(run("--manifold builtin:sphere-3 --points " + path("points.txt") + out), 2);
  EXPECT_NE(stderr_text().find("points.txt"), std::string::npos);
  // A missing file.
  EXPECT_EQ(run("--manifold builtin:sphere-2 --points " + path("missing.txt") + out), 2);
  // A point off the manifold.
  io::PointSet off = s.points;
  off.coordinates[3 * 17] *= 1.5;
  io::write_points(path("off.txt"), off);
  EXPECT_EQ(run("--manifold builtin:sphere-2 --points " + path("off.txt") + out), 2);
  EXPECT_NE(stderr_text().find("point 17"), std::string::npos) << stderr_text();
  // Malformed text.
  std::ofstream(path("garbage.txt")) << "delcert-points v1\n3 2\n1 0 0\n0 nan 1\n";
  EXPECT_EQ(run("--manifold builtin:sphere-2 --points " + path("garbage.txt") + out), 2);
  // An unknown manifold and a missing option.
  EXPECT_EQ(run("--manifold builtin:nope --points " + path("points.txt") + out), 2);
  EXPECT_EQ(run("--manifold builtin:sphere-2" + out), 2);
  EXPECT_FALSE(fs::exists(path("complex.txt")));
  EXPECT_FALSE(fs::exists(path("stats.json")));
}

}  // namespace
}  // namespace delcert::tangential
