// Replays every input kept in fuzz/regressions/TARGET/ (inputs that once crashed a fuzz target)
// through the same reader entry point as the fuzzer (fuzz/readers.hpp). Each must either be
// accepted (and then round-trip) or be refused with the reader's documented error; any other
// exception fails the test, and a crash, sanitizer report or hang fails it under ctest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "fuzz/readers.hpp"
#include "tests/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

const std::map<std::string, std::function<bool(const std::string&)>>& readers() {
  static const std::map<std::string, std::function<bool(const std::string&)>> r{
      {"points", delcert::fuzz::points},   {"complex", delcert::fuzz::complex},
      {"spec", delcert::fuzz::spec},       {"claims", delcert::fuzz::claims},
      {"polynomial", delcert::fuzz::polynomial},
  };
  return r;
}

fs::path regressions_dir() { return fs::path(DELCERT_SOURCE_DIR) / "fuzz" / "regressions"; }

struct Case {
  std::string target;
  fs::path file;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.target << "/" << c.file.filename().string(); }

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  if (!fs::is_directory(regressions_dir())) return cases;
  for (const auto& dir : fs::directory_iterator(regressions_dir())) {
    if (!dir.is_directory()) continue;
    for (const auto& f : fs::directory_iterator(dir.path()))
      if (f.is_regular_file() && f.path().filename() != "README.md")
        cases.push_back({dir.path().filename().string(), f.path()});
  }
  std::sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) { return a.file < b.file; });
  return cases;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class FuzzRegression : public ::testing::TestWithParam<Case> {};

TEST_P(FuzzRegression, AcceptedOrRefusedWithTheDocumentedError) {
  const Case& c = GetParam();
  auto reader = readers().find(c.target);
  ASSERT_NE(reader, readers().end()) << "fuzz/regressions/" << c.target << "/ names no fuzz target";
  const std::string data = slurp(c.file);
  try {
    reader->second(data);
  } catch (const std::exception& e) {
    FAIL() << c.file << ": undocumented " << typeid(e).name() << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegression, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.target + "_" + info.param.file.filename().string();
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

// The directory layout the test relies on: one folder per fuzz target, each non-empty.
TEST(FuzzRegressions, EveryFolderNamesATarget) {
  ASSERT_TRUE(fs::is_directory(regressions_dir()));
  for (const auto& dir : fs::directory_iterator(regressions_dir())) {
    if (dir.is_directory()) {
      EXPECT_TRUE(readers().count(dir.path().filename().string())) << dir.path();
    }
  }
  EXPECT_FALSE(all_cases().empty());
}

// The reader entry points themselves: a fixture each reader accepts, and one it refuses.
TEST(FuzzReaders, AcceptAndRefuseAsDocumented) {
  const fs::path fx = DELCERT_FIXTURES_DIR;
  EXPECT_TRUE(delcert::fuzz::points(slurp(fx / "points" / "octahedron.off")));
  EXPECT_FALSE(delcert::fuzz::points(slurp(fx / "bad" / "points-nan.txt")));
  EXPECT_TRUE(delcert::fuzz::complex(slurp(fx / "complexes" / "octahedron.off")));
  EXPECT_FALSE(delcert::fuzz::complex(slurp(fx / "bad" / "complex-out-of-range.txt")));
  EXPECT_TRUE(delcert::fuzz::spec(slurp(fx / "manifolds" / "sphere-2.json")));
  EXPECT_FALSE(delcert::fuzz::spec(slurp(fx / "bad" / "spec-invalid-json.json")));
  EXPECT_TRUE(delcert::fuzz::claims(slurp(fx / "certify" / "octahedron-claims.json")));
  EXPECT_FALSE(delcert::fuzz::claims(slurp(fx / "certify" / "claims-unknown-key.json")));
  EXPECT_TRUE(delcert::fuzz::polynomial("3;x1^2 + x2^2 + x3^2 - 1/4"));
  EXPECT_TRUE(delcert::fuzz::polynomial("2.5e-3"));
  EXPECT_FALSE(delcert::fuzz::polynomial("2;x3"));
  EXPECT_FALSE(delcert::fuzz::polynomial("x1 +"));
}

}  // namespace
