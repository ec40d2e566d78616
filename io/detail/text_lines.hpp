// Internal helper for the text readers: splits a file into numbered, tokenised lines,
// skipping blank lines and '#' comments, and parses numbers strictly.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace delcert::io::detail {

// One line's tokens: views into the text, the first eight held in place (no allocation for a
// usual line: a point, a simplex).
class Tokens {
 public:
  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  std::string_view operator[](std::size_t i) const { return data()[i]; }
  const std::string_view* begin() const { return data(); }
  const std::string_view* end() const { return data() + n_; }
  operator std::span<const std::string_view>() const { return {data(), n_}; }
  void push_back(std::string_view t);

 private:
  static constexpr std::size_t kInline = 8;
  const std::string_view* data() const { return n_ <= kInline ? in_place_.data() : heap_.data(); }
  std::array<std::string_view, kInline> in_place_{};
  std::vector<std::string_view> heap_;  // every token, once there are more than kInline
  std::size_t n_ = 0;
};

struct Line {
  long number;    // 1-based line number in the file
  Tokens tokens;  // views into the text
};

// Every non-empty, non-comment line of a text, 16 bytes each (its number and where it starts):
// a line is split into tokens when it is read (lines[i], or the iteration), so a file of 1M
// points does not hold 3M token views at once. The text must outlive it.
class Lines {
 public:
  std::size_t size() const { return number_.size(); }
  bool empty() const { return number_.empty(); }
  Line operator[](std::size_t i) const;
  Line back() const { return (*this)[size() - 1]; }
  class iterator {
   public:
    iterator(const Lines* lines, std::size_t i) : lines_(lines), i_(i) {}
    Line operator*() const { return (*lines_)[i_]; }
    iterator& operator++() { return ++i_, *this; }
    bool operator!=(const iterator& o) const { return i_ != o.i_; }

   private:
    const Lines* lines_;
    std::size_t i_;
  };
  iterator begin() const { return {this, 0}; }
  iterator end() const { return {this, size()}; }

 private:
  friend Lines split_lines(const std::string& text);
  const std::string* text_ = nullptr;
  std::vector<long> number_;
  std::vector<std::size_t> start_;  // offset of the line in the text
};

Lines split_lines(const std::string& text);

// Strict parsers: the whole token must be a finite number / a non-negative integer.
// They throw InputError(file, line, ...) with a message naming the token.
double parse_finite_double(std::string_view token, const std::string& file, long line);
long parse_count(std::string_view token, const std::string& file, long line, const char* what);

}  // namespace delcert::io::detail
