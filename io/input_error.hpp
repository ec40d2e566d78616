// Errors in user-supplied files. The message always reads "FILE:LINE: what is wrong" (LINE is
// omitted when the problem is not tied to a line) followed, where useful, by what to do.
#pragma once

#include <stdexcept>
#include <string>

namespace delcert::io {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, long line, const std::string& what)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what),
        file_(file), line_(line) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }  // 1-based; 0 when not tied to a line

 private:
  std::string file_;
  long line_;
};

}  // namespace delcert::io
