#include "io/claims.hpp"

#include <nlohmann/json.hpp>

#include <utility>

#include "exact/polynomial.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/detail/strict_json.hpp"

namespace delcert::io {

Claims parse_claims(const std::string& text, const std::string& file) {
  using nlohmann::json;
  // Strict: a repeated key is refused (a DOM keeps the last one silently), every number is read
  // as written, and every message names the line.
  const detail::StrictJson doc = detail::StrictJson::parse(text, file);
  const json& j = doc.root();
  if (!j.is_object()) throw InputError(file, 1, "expected a JSON object {\"format\": \"delcert-claims v2\", ...}");
  const bool v1 = j.contains("format") && j.at("format") == "delcert-claims v1";
  if (!v1 && !(j.contains("format") && j.at("format") == "delcert-claims v2"))
    throw InputError(file, doc.line("format"),
                     "expected \"format\": \"delcert-claims v2\" (or v1); this reader knows versions 1 and 2");
  Claims c;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (key == "format") continue;
    const long line = doc.key_line(key);
    if (!v1 && key == "secure") {  // the one yes/no claim (check 7)
      if (!it.value().is_boolean())
        throw InputError(file, line, "claim 'secure' must be true or false (every m-simplex is secure, Definition 3.1)");
      c.secure = it.value().get<bool>();
      continue;
    }
    if (!v1 && key == "eps")
      throw InputError(file, line,
                       "'eps' is not a version 2 claim: write \"star_radius\" (every star simplex has R_p(s) < value) "
                       "or \"covering\" (d(x, P) < value for every x in M), or declare \"delcert-claims v1\"");
    std::optional<mpq_class>* slot = (v1 ? key == "eps" : key == "star_radius") ? &c.star_radius
                                     : !v1 && key == "covering"                 ? &c.covering
                                     : key == "sparsity"                        ? &c.sparsity
                                     : key == "gamma0"                          ? &c.gamma0
                                     : key == "power_protection"                ? &c.power_protection
                                                                                : nullptr;
    if (!slot)
      throw InputError(file, line, "unknown claim '" + key + "'; known: " +
                                       (v1 ? "eps, sparsity, gamma0, power_protection (version 1)"
                                           : "star_radius, covering, sparsity, gamma0, power_protection, secure"));
    const json& v = it.value();
    if (v.is_null()) continue;
    mpq_class q;
    if (auto z = v.is_number() ? doc.integer(key) : std::nullopt) {
      q = mpq_class(*z);  // a JSON integer, exactly as written, of any size
    } else if (v.is_string()) {
      try {
        q = exact::parse_rational(v.get<std::string>());
      } catch (const std::invalid_argument& e) {
        throw InputError(file, line, "claim '" + key + "': " + e.what());
      }
    } else {
      throw InputError(file, line,
                           "claim '" + key + "' must be an exact rational written as a string, e.g. \"0.05\" or \"1/20\", "
                           "or a JSON integer; found " + (doc.number_text(key) ? *doc.number_text(key) : v.dump()));
    }
    const bool positive = slot == &c.star_radius || slot == &c.covering;
    if (q < 0 || (positive && q == 0))
      throw InputError(file, line, "claim '" + key + "' must be " + (positive ? "positive" : "non-negative"));
    if (key == "gamma0" && !(q > 0 && q <= 1)) throw InputError(file, line, "claim 'gamma0' must lie in (0, 1]");
    *slot = q;
  }
  return c;
}

Claims read_claims(const std::string& path) { return parse_claims(read_file(path), path); }

std::string format_claims(const Claims& c) {
  nlohmann::ordered_json j;
  j["format"] = "delcert-claims v2";
  const std::pair<const char*, const std::optional<mpq_class>*> keys[] = {
      {"star_radius", &c.star_radius}, {"covering", &c.covering}, {"sparsity", &c.sparsity}, {"gamma0", &c.gamma0}, {"power_protection", &c.power_protection}};
  for (const auto& [key, value] : keys)
    if (*value) j[key] = exact::rational_to_string(**value);
  if (c.secure) j["secure"] = true;
  return j.dump(2) + "\n";
}

}  // namespace delcert::io
