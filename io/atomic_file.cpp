#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "io/input_error.hpp"

namespace delcert::io {

namespace {

namespace fs = std::filesystem;

fs::path directory_of(const fs::path& target) { return target.has_parent_path() ? target.parent_path() : fs::path("."); }

// Writes `content` to a temporary file beside `path` and returns its name; throws (removing it)
// on failure.
fs::path write_temporary(const std::string& path, const std::string& content) {
  fs::path target(path);
  fs::path dir = directory_of(target);
  if (!fs::is_directory(dir))
    throw InputError(path, 0, "cannot write: directory '" + dir.string() + "' does not exist; create it first");
  fs::path tmp = dir / ("." + target.filename().string() + ".tmp." + std::to_string(::getpid()));
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw InputError(path, 0, std::string("cannot write: ") + std::strerror(errno));
  bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  ok = (std::fflush(f) == 0) && ok;
  ok = (::fsync(::fileno(f)) == 0 || errno == EINVAL) && ok;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "write failed (disk full?); nothing was written");
  }
  return tmp;
}

// Same file: by identity when both exist, else by their weakly canonical absolute paths.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    bool eq = fs::equivalent(a, b, ec);
    if (!ec) return eq;
  }
  fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec), cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return ca == cb;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& content) { write_files_atomically({{path, content}}); }

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<fs::path> tmps;
  try {
    for (const auto& [path, content] : files) tmps.push_back(write_temporary(path, content));
  } catch (...) {
    for (const auto& t : tmps) std::remove(t.c_str());
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(tmps[i], files[i].first, ec);
    if (ec) {
      for (std::size_t j = i; j < tmps.size(); ++j) std::remove(tmps[j].c_str());
      throw InputError(files[i].first, 0,
                       "cannot replace file: " + ec.message() +
                           (i ? " (" + std::to_string(i) + " earlier output(s) were already replaced)" : std::string()));
    }
  }
}

void check_output_path(const std::string& path, const std::string& option, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& other_outputs, bool directory_may_be_created) {
  const fs::path target(path);
  std::error_code ec;
  if (path.empty()) throw InputError(path, 0, option + ": empty output path");
  if (fs::is_directory(target, ec))
    throw InputError(path, 0, option + ": is a directory; give a file name for the output");
  const fs::path dir = directory_of(target);
  if (!directory_may_be_created && !fs::is_directory(dir, ec))
    throw InputError(path, 0, option + ": cannot write: directory '" + dir.string() + "' does not exist; create it first");
  for (const auto& in : inputs) {
    if (in.empty() || in.rfind("builtin:", 0) == 0) continue;
    if (same_file(target, fs::path(in)))
      throw InputError(path, 0, option + " is the input file '" + in + "': it would be overwritten; choose another output path");
  }
  for (const auto& o : other_outputs)
    if (!o.empty() && same_file(target, fs::path(o)))
      throw InputError(path, 0, option + " is also the output '" + o + "'; give each output its own path");
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file: " + std::string(std::strerror(errno)));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace delcert::io
