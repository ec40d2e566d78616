// Internal helper for the text readers: splits a file into numbered, tokenised lines,
// skipping blank lines and '#' comments, and parses numbers strictly.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace delcert::io::detail {

struct Line {
  long number;                               // 1-based line number in the file
  std::span<const std::string_view> tokens;  // views into the text, stored by the Lines
};

// Every non-empty, non-comment line of a text, their tokens in one array: no allocation per line
// (1M points are 1M lines; a vector of tokens per line took about 150 bytes each). The text must
// outlive it. Movable, not copyable (the lines' spans point into its own token array, which a
// move keeps in place).
class Lines {
 public:
  Lines() = default;
  Lines(Lines&&) = default;
  Lines& operator=(Lines&&) = default;
  Lines(const Lines&) = delete;
  Lines& operator=(const Lines&) = delete;
  std::size_t size() const { return lines_.size(); }
  bool empty() const { return lines_.empty(); }
  const Line& operator[](std::size_t i) const { return lines_[i]; }
  const Line& back() const { return lines_.back(); }
  std::vector<Line>::const_iterator begin() const { return lines_.begin(); }
  std::vector<Line>::const_iterator end() const { return lines_.end(); }

 private:
  friend Lines split_lines(const std::string& text);
  std::vector<std::string_view> tokens_;
  std::vector<Line> lines_;
};

Lines split_lines(const std::string& text);

// Strict parsers: the whole token must be a finite number / a non-negative integer.
// They throw InputError(file, line, ...) with a message naming the token.
double parse_finite_double(std::string_view token, const std::string& file, long line);
long parse_count(std::string_view token, const std::string& file, long line, const char* what);

}  // namespace delcert::io::detail
