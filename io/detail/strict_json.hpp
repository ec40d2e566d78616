// Strict JSON reading for the files delcert trusts (manifold specs, claims): nlohmann::json is
// fed through a SAX handler that
//   * refuses a key repeated in one object ("duplicate key", at the line of the second one):
//     a DOM parser keeps the last silently, so {"eps": "0.5", "eps": "2"} would read as 2;
//   * refuses nesting deeper than max_depth (no file of ours needs more than 4 levels);
//   * remembers the line of every value and the text of every number as written, so that
//     callers can report FILE:LINE for any field and read integers of any size exactly (a DOM
//     holds 2^64 - 1 as uint64 and 2^64 as a double, and get<long>() wraps the first).
//
// Paths name values the way the messages do: "" for the document, "key" for a top-level member,
// "reach.value" for a nested one, "equations[0]" for an array element.
#pragma once

#include <gmpxx.h>

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>

namespace delcert::io::detail {

class StrictJson {
 public:
  static constexpr int max_depth = 64;

  // Throws InputError(file, line, ...) for invalid JSON, a duplicate key or too deep nesting.
  static StrictJson parse(const std::string& text, const std::string& file);

  const nlohmann::json& root() const { return root_; }
  // Line of the value at `path`; for a path that is not in the document (a missing key), the
  // line of the nearest enclosing value that is.
  long line(const std::string& path) const;
  // Line of the key of the member at `path` (for "unknown key" messages), else line(path).
  long key_line(const std::string& path) const;
  // The value at `path` as an exact integer: a JSON number written without fraction or
  // exponent, of any size. nullopt for anything else.
  std::optional<mpz_class> integer(const std::string& path) const;
  // The number at `path` exactly as written, or nullptr when it is not a number.
  const std::string* number_text(const std::string& path) const;

 private:
  friend class StrictJsonBuilder;
  nlohmann::json root_;
  std::map<std::string, long> lines_, key_lines_;
  std::map<std::string, std::string> numbers_;
};

// "parent.key" / "key" at the top level.
std::string json_member_path(const std::string& parent, const std::string& key);
// "parent[i]".
std::string json_element_path(const std::string& parent, std::size_t i);

}  // namespace delcert::io::detail
