#include "io/detail/text_lines.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "io/input_error.hpp"

namespace delcert::io::detail {

namespace {

// The line starting at `start` (up to its newline), without its '#' comment.
std::string_view line_at(const std::string& text, std::size_t start) {
  std::size_t end = text.find('\n', start);
  if (end == std::string::npos) end = text.size();
  std::string_view line(text.data() + start, end - start);
  if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  return line;
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

}  // namespace

void Tokens::push_back(std::string_view t) {
  if (n_ < kInline) {
    in_place_[n_++] = t;
    return;
  }
  if (n_ == kInline) heap_.assign(in_place_.begin(), in_place_.end());
  heap_.push_back(t), ++n_;
}

Line Lines::operator[](std::size_t i) const {
  Line l{number_[i], {}};
  const std::string_view line = line_at(*text_, start_[i]);
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && blank(line[k])) ++k;
    const std::size_t s = k;
    while (k < line.size() && !blank(line[k])) ++k;
    if (k > s) l.tokens.push_back(line.substr(s, k - s));
  }
  return l;
}

Lines split_lines(const std::string& text) {
  Lines out;
  out.text_ = &text;
  long number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::string_view line = line_at(text, pos);
    ++number;
    if (std::any_of(line.begin(), line.end(), [](char c) { return !blank(c); }))
      out.number_.push_back(number), out.start_.push_back(pos);
    const std::size_t end = text.find('\n', pos);
    pos = end == std::string::npos ? text.size() : end + 1;
  }
  return out;
}

double parse_finite_double(std::string_view token, const std::string& file, long line) {
  double x = 0;
  const char* b = token.data();
  const char* e = b + token.size();
  if (b != e && *b == '+') ++b;
  auto [ptr, ec] = std::from_chars(b, e, x);
  if (ec == std::errc::result_out_of_range)
    throw InputError(file, line, "number '" + std::string(token) + "' is out of the range of a double");
  if (ec != std::errc() || ptr != e)
    throw InputError(file, line, "malformed number '" + std::string(token) + "'");
  if (!std::isfinite(x))
    throw InputError(file, line, "'" + std::string(token) + "' is not a finite number; coordinates must be finite");
  return x;
}

long parse_count(std::string_view token, const std::string& file, long line, const char* what) {
  long v = 0;
  auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size() || v < 0)
    throw InputError(file, line, std::string("expected ") + what + " (a non-negative integer), found '" +
                                     std::string(token) + "'");
  return v;
}

}  // namespace delcert::io::detail
