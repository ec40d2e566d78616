#include "certify/claims.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "core/io/atomic_file.hpp"
#include "core/io/input_error.hpp"
#include "exact/polynomial.hpp"

namespace delcert::certify {

namespace {

// 1-based line of the first occurrence of "key" in the text (0 if absent): JSON parsers do not
// keep positions, and a message that names the line is what lets a user fix the file.
long line_of_key(const std::string& text, const std::string& key) {
  auto pos = text.find("\"" + key + "\"");
  if (pos == std::string::npos) return 0;
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

}  // namespace

Claims parse_claims(const std::string& text, const std::string& file) {
  using nlohmann::json;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(std::min(e.byte, text.size())), '\n'));
    throw io::InputError(file, line, std::string("invalid JSON: ") + e.what());
  }
  if (!j.is_object()) throw io::InputError(file, 1, "expected a JSON object {\"format\": \"delcert-claims v1\", ...}");
  if (!j.contains("format") || j["format"] != "delcert-claims v1")
    throw io::InputError(file, std::max(1L, line_of_key(text, "format")),
                         "expected \"format\": \"delcert-claims v1\"; this reader knows version 1 only");
  Claims c;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (key == "format") continue;
    long line = line_of_key(text, key);
    std::optional<mpq_class>* slot = key == "eps"                ? &c.eps
                                     : key == "sparsity"         ? &c.sparsity
                                     : key == "gamma0"           ? &c.gamma0
                                     : key == "power_protection" ? &c.power_protection
                                                                 : nullptr;
    if (!slot)
      throw io::InputError(file, line, "unknown claim '" + key + "'; known: eps, sparsity, gamma0, power_protection");
    const json& v = it.value();
    if (v.is_null()) continue;
    mpq_class q;
    if (v.is_number_integer()) {
      q = mpq_class(std::to_string(v.get<long long>()));
    } else if (v.is_string()) {
      try {
        q = parse_rational(v.get<std::string>());
      } catch (const std::invalid_argument& e) {
        throw io::InputError(file, line, "claim '" + key + "': " + e.what());
      }
    } else {
      throw io::InputError(file, line,
                           "claim '" + key + "' must be an exact rational written as a string, e.g. \"0.05\" or \"1/20\"; found " +
                               v.dump());
    }
    if (q < 0 || (key == "eps" && q == 0))
      throw io::InputError(file, line, "claim '" + key + "' must be " + (key == "eps" ? "positive" : "non-negative"));
    if (key == "gamma0" && !(q > 0 && q <= 1)) throw io::InputError(file, line, "claim 'gamma0' must lie in (0, 1]");
    *slot = q;
  }
  return c;
}

Claims read_claims(const std::string& path) { return parse_claims(io::read_file(path), path); }

}  // namespace delcert::certify
