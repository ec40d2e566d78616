// The `delcert` command line (issue 13 §5): --version, refused option values (exit status 2, one
// short line saying what is wrong and what to give, no 300-digit numbers, nothing written) and
// the one default thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "tests/test_support.hpp"

namespace delcert::app {
namespace {

using test::binary;
using test::run;

// The version of project(delcert VERSION ...) in the top CMakeLists.txt.
std::string project_version() {
  std::ifstream in(std::string(DELCERT_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  std::smatch m;
  const std::string s = text.str();
  EXPECT_TRUE(std::regex_search(s, m, std::regex(R"(project\(delcert VERSION ([0-9.]+))")));
  return m.size() > 1 ? m[1].str() : "";
}

TEST(DelcertCli, VersionPrintsOneLineFromTheProjectVersion) {
  auto r = run(binary("delcert") + " --version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.output, "delcert " + project_version() + "\n");
}

struct Refused {
  const char* args;     // after `delcert`; @OUT@ is a path in an empty directory
  const char* message;  // the whole line, as printed
};

class DelcertRefusedOption : public ::testing::TestWithParam<Refused> {};

TEST_P(DelcertRefusedOption, ExitsTwoWithAShortMessageAndWritesNothing) {
  test::TempDir dir("cli-refused");
  std::string args = GetParam().args;
  for (auto pos = args.find("@OUT@"); pos != std::string::npos; pos = args.find("@OUT@"))
    args.replace(pos, 5, dir.file("out"));
  auto r = run(binary("delcert") + " " + args);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(std::string(GetParam().message) + "\n"), std::string::npos) << r.output;
  EXPECT_FALSE(std::regex_search(r.output, std::regex("[0-9]{25}"))) << "a huge number in: " << r.output;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

constexpr const char* kSample = "sample --manifold builtin:sphere-2 --out @OUT@ ";
constexpr const char* kSeedRange = "; give a seed from 0 to 18446744073709551615";

std::vector<Refused> refused_cases() {
  static const std::string s = kSample, refine = "refine --manifold builtin:sphere-2 --eps 0.5 --out @OUT@ ",
                           tangential = "tangential --manifold builtin:sphere-2 --points nowhere.txt --out @OUT@ ",
                           threads = "; give 0 (one thread per hardware thread) or a thread count from 1 to 256";
  static const std::vector<std::string> owned = {
      // --seed: CLI11 alone read -1 as 2^64-1, 2^64 as 2^64-1 and 010 as 8.
      s + "--eps 0.5 --seed -1", "--seed: -1 is negative" + std::string(kSeedRange),
      s + "--eps 0.5 --seed abc", "--seed: abc is not a whole number" + std::string(kSeedRange),
      s + "--eps 0.5 --seed 1.5", "--seed: 1.5 is not a whole number" + std::string(kSeedRange),
      s + "--eps 0.5 --seed 0x10", "--seed: 0x10 is not a whole number" + std::string(kSeedRange),
      s + "--eps 0.5 --seed 18446744073709551616",
      "--seed: 18446744073709551616 is above 18446744073709551615" + std::string(kSeedRange),
      s + "--eps 0.5 --seed " + std::string(300, '9'),
      "--seed: 99999999999999999999... (300 characters) is above 18446744073709551615" + std::string(kSeedRange),
      refine + "--seed -1", "--seed: -1 is negative" + std::string(kSeedRange),
      // --eps of sample: CLI::PositiveNumber printed DBL_MIN and DBL_MAX with all their digits. Now
      // sample reads --eps as refine does (an exact decimal or fraction), with refine's messages.
      s + "--eps -1", "--eps: must be positive",
      s + "--eps 0", "--eps: must be positive",
      s + "--eps 1e400", "--eps: must be at most 1.8e308 (the largest double): delcert computes with doubles",
      s + "--eps 1e-400", "--eps: must be at least 4.9e-324 (the smallest positive double): delcert computes with doubles",
      s + "--eps nan", "--eps: 'nan' is not a number; write a decimal or a fraction, e.g. 0.1 or 1/10",
      s + "--eps abc", "--eps: 'abc' is not a number; write a decimal or a fraction, e.g. 0.1 or 1/10",
      // An eps whose net would need more than the dense sample's cap: refused at once (it ran for hours).
      s + "--eps 1e-300",
      // The suggestion is one that is accepted (it was 0.0066, refused: tests/core/sampling checks it).
      "--eps: 1e-300 is too small for this command: its eps-net needs a dense sample of more than 1e308 points, more "
      "than the cap of 4e+06 (about 30 per net point: nets of at most about 133333 points); give eps >= 0.0069",
      "refine --manifold builtin:sphere-2 --out @OUT@ --eps 1e-3",
      "--eps: 0.001 is too small for this command: its eps-net needs a dense sample of about 2.02e+08 points, more "
      "than the cap of 4e+06 (about 30 per net point: nets of at most about 133333 points); give eps >= 0.0071",
      // A built-in's name without builtin:, and misspelt built-in names, name the nearest built-in.
      "sample --manifold sphere-2 --eps 0.5 --out @OUT@",
      "delcert: sphere-2: no such file; for the built-in manifold, write --manifold builtin:sphere-2",
      "sample --manifold builtin:sphere2 --eps 0.5 --out @OUT@",
      "delcert: builtin:sphere2: no built-in manifold 'sphere2'; did you mean builtin:sphere-2? known: clifford-torus-2, "
      "clifford-torus-3, so3, sphere-2, sphere-3, torus-of-revolution",
      "refine --manifold builtin:clifford-torus --eps 0.5 --out @OUT@",
      "delcert: builtin:clifford-torus: no built-in manifold 'clifford-torus'; did you mean builtin:clifford-torus-2? "
      "known: clifford-torus-2, clifford-torus-3, so3, sphere-2, sphere-3, torus-of-revolution",
      "sample --manifold builtin:kleinbottle --eps 0.5 --out @OUT@",
      "delcert: builtin:kleinbottle: no built-in manifold 'kleinbottle'; known: clifford-torus-2, clifford-torus-3, so3, "
      "sphere-2, sphere-3, torus-of-revolution",
      // --threads: CLI::NonNegativeNumber printed DBL_MAX with all its digits.
      tangential + "--threads -1", "--threads: -1 is negative" + threads,
      tangential + "--threads 257", "--threads: 257 is above 256" + threads,
      refine + "--threads 99999999999999999999", "--threads: 99999999999999999999 is above 256" + threads,
      refine + "--threads two", "--threads: two is not a whole number" + threads,
      // The caps were size_t: -1 wrapped to 2^64-1.
      refine + "--max-rounds -1", "--max-rounds: -1 is negative; give a round count from 0 to 18446744073709551615",
      refine + "--max-inserted -5",
      "--max-inserted: -5 is negative; give a point count from 0 to 18446744073709551615",
  };
  std::vector<Refused> cases;
  for (std::size_t i = 0; i + 1 < owned.size(); i += 2) cases.push_back({owned[i].c_str(), owned[i + 1].c_str()});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Cases, DelcertRefusedOption, ::testing::ValuesIn(refused_cases()));

// sample --help says that the dense sample, hence the net, is capped, and what happens beyond.
TEST(DelcertCli, SampleHelpNamesTheCap) {
  auto r = run(binary("delcert") + " sample --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("capped at 4000000 points (nets of at most about 133k points)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("names the smallest eps that fits"), std::string::npos) << r.output;
}

// refine's constants are exact rationals: one beyond double's range names the limit, not its digits.
TEST(DelcertCli, RefineEpsBeyondDoubleNamesTheLimit) {
  test::TempDir dir("cli-refine-eps");
  auto r = run(binary("delcert") + " refine --manifold builtin:sphere-2 --eps 1e400 --out " + dir.file("out"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--eps: must be at most 1.8e308 (the largest double)"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// sample --eps takes refine's exact syntax: 1/4 and 0.25 are the same eps, the same bytes.
TEST(DelcertCli, SampleEpsIsAFractionOrADecimal) {
  test::TempDir dir("cli-sample-eps");
  auto a = run(binary("delcert") + " sample --manifold builtin:sphere-2 --eps 1/4 --out " + dir.file("a.txt"));
  auto b = run(binary("delcert") + " sample --manifold builtin:sphere-2 --eps 0.25 --out " + dir.file("b.txt"));
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(a.output.find("eps                1/4\n"), std::string::npos) << a.output;
  EXPECT_EQ(test::slurp(dir.file("a.txt")), test::slurp(dir.file("b.txt")));
}

// A seed is read in decimal: a leading zero is not octal.
TEST(DelcertCli, SeedWithLeadingZerosIsDecimal) {
  test::TempDir dir("cli-seed");
  auto r = run(binary("delcert") + " sample --manifold builtin:sphere-2 --eps 0.8 --seed 010 --out " + dir.file("a.txt"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("seed               10\n"), std::string::npos) << r.output;
  r = run(binary("delcert") + " sample --manifold builtin:sphere-2 --eps 0.8 --seed 18446744073709551615 --out " +
          dir.file("b.txt"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("seed               18446744073709551615\n"), std::string::npos) << r.output;
}

// Every command that takes --threads defaults to 0, one thread per hardware thread, and says so.
TEST(DelcertCli, ThreadsDefaultToAllCoresInEveryCommand) {
  for (const char* command : {"tangential", "refine"}) {
    auto r = run(binary("delcert") + " " + command + " --help");
    EXPECT_EQ(r.status, 0) << command;
    EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(--threads [^\n]*=0\s)"))) << command << ":\n" << r.output;
    EXPECT_NE(r.output.find("0 (the default) = one per hardware thread"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace delcert::app
