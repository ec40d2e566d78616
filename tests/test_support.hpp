// Small helpers shared by the test executables: fixture paths, temporary directories and
// running the built command-line tools.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "tests/test_paths.hpp"

namespace delcert::test {

inline std::string fixture(const std::string& relative) { return std::string(DELCERT_FIXTURES_DIR) + "/" + relative; }
inline std::string binary(const std::string& name) { return std::string(DELCERT_BINARY_DIR) + "/" + name; }

// A fresh, empty directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    auto base = std::filesystem::temp_directory_path();
    for (int i = 0;; ++i) {
      path_ = base / ("delcert-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(i));
      if (std::filesystem::create_directory(path_)) break;
    }
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int status = -1;     // exit status
  std::string output;  // stdout and stderr, interleaved
};

// Runs a shell command line; captures stdout+stderr.
inline CommandResult run(const std::string& command) {
  CommandResult r;
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  int st = ::pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// DELCERT_TEST_SCALE (default 1) scales the size of the long soundness suites (differential,
// mutation): scripts/sanitize.sh runs them at 0.1, a long run on demand at 20.
inline double test_scale() {
  const char* s = std::getenv("DELCERT_TEST_SCALE");
  const double v = s && *s ? std::atof(s) : 1.0;
  return v > 0 ? v : 1.0;
}
// `base` scaled by test_scale(), at least 1.
inline int scaled(int base) { return std::max(1, static_cast<int>(std::lround(base * test_scale()))); }

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace delcert::test
