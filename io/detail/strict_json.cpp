#include "io/detail/strict_json.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "io/input_error.hpp"

namespace delcert::io::detail {

using nlohmann::json;

std::string json_member_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
std::string json_element_path(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Builds the DOM from nlohmann's SAX events. nlohmann does not tell a handler where a token is,
// so a small scanner walks the same text in step: every event but the container ends consumes
// exactly one token (a key, a value, '{' or '['), the ends consume '}' or ']', and separators
// (',' ':') and blanks are skipped. The lexer has already accepted each token when its event
// arrives, so the scanner only has to find token boundaries in valid JSON.
class StrictJsonBuilder {
 public:
  StrictJsonBuilder(const std::string& text, const std::string& file, StrictJson& doc)
      : text_(text), file_(file), doc_(doc) {
    if (text_.rfind("\xEF\xBB\xBF", 0) == 0) pos_ = 3;  // nlohmann skips a UTF-8 byte-order mark
  }

  bool null() { return value(json(nullptr)); }
  bool boolean(bool v) { return value(json(v)); }
  bool number_integer(json::number_integer_t v) { return value(json(v), true); }
  bool number_unsigned(json::number_unsigned_t v) { return value(json(v), true); }
  bool number_float(json::number_float_t v, const std::string&) { return value(json(v), true); }
  bool string(std::string& v) { return value(json(std::move(v))); }
  bool binary(json::binary_t&) { return value(json(nullptr)); }  // not produced by the JSON lexer

  bool start_object(std::size_t) { return open(json::object(), true); }
  bool start_array(std::size_t) { return open(json::array(), false); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    const long line = token_start();
    skip_token();
    Frame& f = frames_.back();
    if (auto it = f.keys.find(k); it != f.keys.end())
      throw InputError(file_, line, "duplicate key \"" + k + "\" (first at line " + std::to_string(it->second) + " in " +
                                        (f.path.empty() ? std::string("the top-level object") : "'" + f.path + "'") +
                                        "); each key may appear only once");
    f.keys.emplace(k, line);
    f.pending_key = k;
    doc_.key_lines_.emplace(json_member_path(f.path, k), line);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    const std::size_t end = std::min(position, text_.size());
    const long line = 1 + static_cast<long>(std::count(text_.begin(), text_.begin() + static_cast<long>(end), '\n'));
    throw InputError(file_, line, std::string("invalid JSON: ") + e.what());
  }

 private:
  struct Frame {
    json* container;
    std::string path;
    std::map<std::string, long> keys;  // objects: key -> line
    std::string pending_key;
    std::size_t next_index = 0;  // arrays
  };

  // Skips blanks and separators; returns the line of the next token.
  long token_start() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') ++line_;
      else if (c != ' ' && c != '\t' && c != '\r' && c != ',' && c != ':') break;
      ++pos_;
    }
    return line_;
  }
  // Moves past the token at pos_: a string, a structural character, or a number or literal.
  void skip_token() {
    if (pos_ >= text_.size()) return;
    const char c = text_[pos_];
    if (c == '"') {
      for (++pos_; pos_ < text_.size() && text_[pos_] != '"'; ++pos_)
        if (text_[pos_] == '\\') ++pos_;
      ++pos_;
    } else if (std::strchr("{}[]", c)) {
      ++pos_;
    } else {
      while (pos_ < text_.size() && !std::strchr(" \t\r\n,:{}[]\"", text_[pos_])) ++pos_;
    }
  }

  std::string next_path() {
    if (frames_.empty()) return "";
    Frame& f = frames_.back();
    return f.container->is_object() ? json_member_path(f.path, f.pending_key)
                                     : json_element_path(f.path, f.next_index++);
  }
  json* insert(json&& v) {
    if (frames_.empty()) {
      doc_.root_ = std::move(v);
      return &doc_.root_;
    }
    Frame& f = frames_.back();
    if (f.container->is_object()) return &((*f.container)[f.pending_key] = std::move(v));
    f.container->push_back(std::move(v));
    return &f.container->back();
  }
  bool value(json&& v, bool is_number = false) {
    const long line = token_start();
    const std::size_t start = pos_;
    skip_token();
    std::string path = next_path();
    if (is_number) doc_.numbers_[path] = text_.substr(start, pos_ - start);
    doc_.lines_[path] = line;
    insert(std::move(v));
    return true;
  }
  bool open(json&& empty, bool) {
    const long line = token_start();
    skip_token();
    if (static_cast<int>(frames_.size()) >= StrictJson::max_depth)
      throw InputError(file_, line, "JSON nested too deeply: more than " + std::to_string(StrictJson::max_depth) +
                                        " levels (the limit)");
    std::string path = next_path();
    doc_.lines_[path] = line;
    json* c = insert(std::move(empty));
    frames_.push_back(Frame{c, std::move(path), {}, {}, 0});
    return true;
  }
  bool close() {
    token_start();
    skip_token();
    frames_.pop_back();
    return true;
  }

  const std::string& text_;
  const std::string& file_;
  StrictJson& doc_;
  std::vector<Frame> frames_;
  std::size_t pos_ = 0;
  long line_ = 1;
};

StrictJson StrictJson::parse(const std::string& text, const std::string& file) {
  StrictJson doc;
  StrictJsonBuilder builder(text, file, doc);
  // strict = true: nothing but blanks may follow the document. Errors throw from the handler.
  json::sax_parse(text, &builder, json::input_format_t::json, true, false);
  return doc;
}

namespace {
// "a.b[2]" -> "a.b" -> "a" -> "".
std::string parent_path(const std::string& path) {
  const auto cut = path.find_last_of(".[");
  return cut == std::string::npos ? std::string() : path.substr(0, cut);
}
}  // namespace

long StrictJson::line(const std::string& path) const {
  for (std::string p = path;; p = parent_path(p)) {
    if (auto it = lines_.find(p); it != lines_.end()) return it->second;
    if (p.empty()) return 1;
  }
}

long StrictJson::key_line(const std::string& path) const {
  auto it = key_lines_.find(path);
  return it != key_lines_.end() ? it->second : line(path);
}

const std::string* StrictJson::number_text(const std::string& path) const {
  auto it = numbers_.find(path);
  return it == numbers_.end() ? nullptr : &it->second;
}

std::optional<mpz_class> StrictJson::integer(const std::string& path) const {
  const std::string* t = number_text(path);
  if (!t || t->find_first_of(".eE") != std::string::npos) return std::nullopt;
  return mpz_class(*t, 10);  // the lexer accepted it: -?(0|[1-9][0-9]*)
}

}  // namespace delcert::io::detail
