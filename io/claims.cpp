#include "io/claims.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string_view>
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
  const bool v3 = j.contains("format") && j.at("format") == "delcert-claims v3";
  if (!v1 && !v3 && !(j.contains("format") && j.at("format") == "delcert-claims v2"))
    throw InputError(file, doc.line("format"),
                     "expected \"format\": \"delcert-claims v2\" (or v1, or v3 with per-point claims); this reader "
                     "knows versions 1, 2 and 3");
  Claims c;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (key == "format") continue;
    const long line = doc.key_line(key);
    if (v3 && (key == "star_radius_per_point" || key == "covering_per_point")) {
      if (!it.value().is_string() || it.value().get<std::string>().empty())
        throw InputError(file, line, "claim '" + key + "' must name a file (relative to this file's directory) "
                                     "holding one exact rational per point, e.g. \"eps.txt\"");
      const std::string name = it.value().get<std::string>();
      const bool star = key == "star_radius_per_point";
      (star ? c.star_radius_per_point_file : c.covering_per_point_file) = name;
      const std::string path = (std::filesystem::path(file).parent_path() / name).string();
      (star ? c.star_radius_per_point_path : c.covering_per_point_path) = path;
      const std::string& other = star ? c.covering_per_point_path : c.star_radius_per_point_path;
      if (!other.empty() && other == path)  // the same file: read once
        (star ? c.star_radius_per_point : c.covering_per_point) = star ? c.covering_per_point : c.star_radius_per_point;
      else {
        std::string values;
        try {
          values = read_file(path);
        } catch (const InputError& e) {
          throw InputError(path, 0, "cannot open the file named by '" + key + "' in " + file + " (" + e.what() +
                                        "): the name is relative to that file's directory");
        }
        (star ? c.star_radius_per_point : c.covering_per_point) = parse_per_point(values, path);
      }
      continue;
    }
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
                                       (v1   ? "eps, sparsity, gamma0, power_protection (version 1)"
                                        : v3 ? "star_radius, covering, star_radius_per_point, covering_per_point, "
                                               "sparsity, gamma0, power_protection, secure"
                                             : "star_radius, covering, sparsity, gamma0, power_protection, secure "
                                               "(per-point claims need \"delcert-claims v3\")"));
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
  if (c.star_radius && !c.star_radius_per_point_file.empty())
    throw InputError(file, doc.key_line("star_radius_per_point"),
                     "give either 'star_radius' (one bound) or 'star_radius_per_point' (a bound per point), not both");
  if (c.covering && !c.covering_per_point_file.empty())
    throw InputError(file, doc.key_line("covering_per_point"),
                     "give either 'covering' (one bound) or 'covering_per_point' (a bound per point), not both");
  return c;
}

std::vector<mpq_class> parse_per_point(const std::string& text, const std::string& path) {
  std::vector<mpq_class> out;
  std::size_t begin = 0;
  long line = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    ++line;
    std::string_view s(text.data() + begin, end - begin);
    begin = end + 1;
    if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    if (s.empty() || s.front() == '#') continue;
    mpq_class q;
    try {
      q = exact::parse_rational(std::string(s));
    } catch (const std::invalid_argument& e) {
      throw InputError(path, line, "value " + std::to_string(out.size()) + " (point " + std::to_string(out.size()) +
                                       "): " + e.what() + "; write one exact rational per line, e.g. 0.05 or 1/20");
    }
    if (q <= 0)
      throw InputError(path, line, "value for point " + std::to_string(out.size()) + " must be positive (a radius)");
    out.push_back(std::move(q));
  }
  return out;
}

std::string format_per_point(const std::vector<mpq_class>& values) {
  std::string s = "# delcert per-point eps: one exact rational per point, in the order of the points\n";
  for (const auto& q : values) s += exact::rational_to_string(q) + "\n";
  return s;
}

Claims read_claims(const std::string& path) { return parse_claims(read_file(path), path); }

std::string format_claims(const Claims& c) {
  nlohmann::ordered_json j;
  const bool v3 = !c.star_radius_per_point_file.empty() || !c.covering_per_point_file.empty();
  j["format"] = v3 ? "delcert-claims v3" : "delcert-claims v2";
  const std::pair<const char*, const std::optional<mpq_class>*> keys[] = {
      {"star_radius", &c.star_radius}, {"covering", &c.covering}, {"sparsity", &c.sparsity}, {"gamma0", &c.gamma0}, {"power_protection", &c.power_protection}};
  for (const auto& [key, value] : keys) {
    if (*value) j[key] = exact::rational_to_string(**value);
    if (std::string(key) == "covering") {
      if (!c.star_radius_per_point_file.empty()) j["star_radius_per_point"] = c.star_radius_per_point_file;
      if (!c.covering_per_point_file.empty()) j["covering_per_point"] = c.covering_per_point_file;
    }
  }
  if (c.secure) j["secure"] = true;
  return j.dump(2) + "\n";
}

}  // namespace delcert::io
