// Internal helper for the text readers: splits a file into numbered, tokenised lines,
// skipping blank lines and '#' comments, and parses numbers strictly.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace delcert::io::detail {

struct Line {
  long number;                           // 1-based line number in the file
  std::vector<std::string_view> tokens;  // views into the text
};

// Every non-empty, non-comment line. `text` must outlive the result.
std::vector<Line> split_lines(const std::string& text);

// Strict parsers: the whole token must be a finite number / a non-negative integer.
// They throw InputError(file, line, ...) with a message naming the token.
double parse_finite_double(std::string_view token, const std::string& file, long line);
long parse_count(std::string_view token, const std::string& file, long line, const char* what);

}  // namespace delcert::io::detail
