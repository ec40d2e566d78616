// The trust boundary (docs/design.md §5): certify/ includes exact/, the plain file readers of core/io,
// CGAL number types, Eigen, nlohmann json, CLI11 and the standard library, nothing else of ours
// (no core/manifold, core/spatial, core/sampling, core/tangential, no CGAL kernel or
// triangulation), and its target never links the producer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

const std::vector<std::string> kAllowedOurs = {"certify/", "exact/", "core/io/points.hpp", "core/io/complex.hpp",
                                                "core/io/spec.hpp", "core/io/atomic_file.hpp", "core/io/input_error.hpp",
                                                "core/io/strict_json.hpp"};
const std::vector<std::string> kAllowedCgal = {"CGAL/Interval_nt.h", "CGAL/Mpzf.h", "CGAL/Gmpq.h", "CGAL/FPU.h"};

// Forbidden includes in `text` ("line: include"), empty when it respects the boundary.
std::vector<std::string> violations(const std::string& text) {
  std::vector<std::string> out;
  std::regex inc(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::smatch m;
    if (!std::regex_search(line, m, inc)) continue;
    std::string path = m[2];
    bool ok;
    if (path.rfind("CGAL/", 0) == 0) {
      ok = std::find(kAllowedCgal.begin(), kAllowedCgal.end(), path) != kAllowedCgal.end();
    } else if (path.rfind("core/", 0) == 0 || path.rfind("certify/", 0) == 0 || path.rfind("exact/", 0) == 0 ||
               m[1] == "\"") {
      ok = false;
      for (const auto& a : kAllowedOurs) ok = ok || path.rfind(a, 0) == 0;
    } else {
      ok = path.rfind("gudhi/", 0) != 0 && path.rfind("boost/", 0) != 0;  // system, Eigen, gmp, json, CLI11
    }
    if (!ok) out.push_back(std::to_string(n) + ": " + path);
  }
  return out;
}

TEST(TrustBoundary, TheCheckerCatchesForbiddenIncludes) {
  EXPECT_TRUE(violations("#include \"exact/tangent_space.hpp\"\n#include <CGAL/Interval_nt.h>\n#include <vector>\n").empty());
  EXPECT_EQ(violations("#include \"core/manifold/manifold.hpp\"\n").size(), 1u);
  EXPECT_EQ(violations("  #  include <CGAL/Regular_triangulation.h>\n").size(), 1u);
  EXPECT_EQ(violations("#include \"core/tangential/star.hpp\"\n#include \"core/io/text_lines.hpp\"\n").size(), 2u);
  EXPECT_EQ(violations("#include <gudhi/Tangential_complex.h>\n").size(), 1u);
}

TEST(TrustBoundary, CertifySourcesRespectTheBoundary) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(DELCERT_SOURCE_DIR) / "certify";
  int files = 0;
  long lines = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    std::ifstream f(entry.path());
    std::string text((std::istreambuf_iterator<char>(f)), {});
    if (ext == ".cpp" || ext == ".hpp") {
      ++files;
      lines += std::count(text.begin(), text.end(), '\n');
      for (const auto& v : violations(text)) ADD_FAILURE() << entry.path().string() << ":" << v << " crosses the trust boundary";
    }
    if (entry.path().filename() == "CMakeLists.txt") {
      for (const char* target : {"delcert_core", "CGAL::CGAL", "gudhi"}) {
        // Only comments may mention them.
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
          auto code = line.substr(0, line.find('#'));
          EXPECT_EQ(code.find(target), std::string::npos) << "certify/CMakeLists.txt links " << target << ": " << line;
        }
      }
    }
  }
  EXPECT_GT(files, 5);
  EXPECT_LT(lines, 4000) << "certify/ should stay small enough to read whole";
}

}  // namespace
