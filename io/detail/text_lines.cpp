#include "io/detail/text_lines.hpp"

#include <charconv>
#include <cmath>

#include "io/input_error.hpp"

namespace delcert::io::detail {

Lines split_lines(const std::string& text) {
  Lines out;
  std::vector<std::size_t> first;  // each line's first token in out.tokens_ (spans are set at the end:
                                   // the array moves while it grows)
  long number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++number;
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::size_t begin = out.tokens_.size();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      std::size_t s = i;
      while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i > s) out.tokens_.push_back(line.substr(s, i - s));
    }
    if (out.tokens_.size() > begin) out.lines_.push_back({number, {}}), first.push_back(begin);
  }
  out.tokens_.shrink_to_fit();
  for (std::size_t l = 0; l < out.lines_.size(); ++l) {
    const std::size_t e = l + 1 < first.size() ? first[l + 1] : out.tokens_.size();
    out.lines_[l].tokens = std::span<const std::string_view>(out.tokens_.data() + first[l], e - first[l]);
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
