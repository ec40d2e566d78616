#include "core/io/spec.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "core/io/atomic_file.hpp"
#include "core/io/input_error.hpp"

namespace delcert::io {

using nlohmann::json;

namespace {

struct Ctx {
  const std::string& file;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(file, 0, "field '" + field + "': " + what);
  }
};

const json& require(const json& obj, const char* key, const Ctx& c, const std::string& prefix = "") {
  if (!obj.contains(key)) c.fail(prefix + key, "missing; it is required");
  return obj.at(key);
}

long get_int(const json& v, const std::string& field, const Ctx& c) {
  if (!v.is_number_integer()) c.fail(field, "expected an integer, found " + v.dump());
  return v.get<long>();
}

// A rational given as a JSON string ("0.1", "1/3") or an integer. JSON floats are refused:
// they are already rounded to binary and would silently change the manifold.
mpq_class get_rational(const json& v, const std::string& field, const Ctx& c) {
  if (v.is_number_integer()) return mpq_class(std::to_string(v.get<long>()));
  if (!v.is_string()) c.fail(field, "expected an exact rational as a string such as \"0.1\" or \"1/3\", found " + v.dump());
  try {
    return parse_rational(v.get<std::string>());
  } catch (const std::invalid_argument& e) {
    c.fail(field, e.what());
  }
}

std::vector<mpq_class> get_rationals(const json& v, const std::string& field, const Ctx& c, std::size_t n) {
  if (!v.is_array() || (n && v.size() != n))
    c.fail(field, "expected an array of " + (n ? std::to_string(n) + " " : std::string()) + "rationals");
  std::vector<mpq_class> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(get_rational(v[i], field + "[" + std::to_string(i) + "]", c));
  return out;
}

Polynomial get_polynomial(const json& v, const std::string& field, int n, const Ctx& c) {
  if (!v.is_string()) c.fail(field, "expected a polynomial as a string, found " + v.dump());
  std::string text = v.get<std::string>();
  try {
    return Polynomial::parse(text, n);
  } catch (const PolynomialParseError& e) {
    c.fail(field, std::string(e.what()) + " at character " + std::to_string(e.offset + 1) + " of \"" + text + "\"");
  }
}

ShapeSpec get_shape(const json& v, const std::string& field, const char* kind_key, const ManifoldSpec& s, const Ctx& c) {
  if (!v.is_object()) c.fail(field, "expected an object");
  const json& k = require(v, kind_key, c, field + ".");
  if (!k.is_string()) c.fail(field + "." + kind_key, "expected a string");
  std::string kind = k.get<std::string>();
  ShapeSpec sh;
  const int N = s.ambient_dimension, m = s.intrinsic_dimension;
  if (kind == "sphere") {
    sh.kind = ShapeSpec::Kind::sphere;
    if (m != N - 1) c.fail(field, "a sphere has intrinsic dimension N - 1");
    sh.center = v.contains("center") ? get_rationals(v["center"], field + ".center", c, N)
                                     : std::vector<mpq_class>(N, mpq_class(0));
    sh.radius = get_rational(require(v, "radius", c, field + "."), field + ".radius", c);
    if (sh.radius <= 0) c.fail(field + ".radius", "must be positive");
  } else if (kind == "product_of_circles") {
    sh.kind = ShapeSpec::Kind::product_of_circles;
    sh.radii = get_rationals(require(v, "radii", c, field + "."), field + ".radii", c, 0);
    if (static_cast<int>(sh.radii.size()) != m || N != 2 * m)
      c.fail(field + ".radii", "a product of m circles needs m radii and N = 2m");
    for (auto& r : sh.radii)
      if (r <= 0) c.fail(field + ".radii", "radii must be positive");
  } else if (kind == "torus_of_revolution") {
    sh.kind = ShapeSpec::Kind::torus_of_revolution;
    if (m != 2 || N != 3) c.fail(field, "a torus of revolution is a surface in R^3");
    sh.major_radius = get_rational(require(v, "major_radius", c, field + "."), field + ".major_radius", c);
    sh.minor_radius = get_rational(require(v, "minor_radius", c, field + "."), field + ".minor_radius", c);
    if (!(sh.major_radius > sh.minor_radius && sh.minor_radius > 0))
      c.fail(field, "needs major_radius > minor_radius > 0");
  } else if (kind == "so3") {
    sh.kind = ShapeSpec::Kind::so3;
    if (m != 3 || N != 9) c.fail(field, "so3 has intrinsic dimension 3 in R^9");
  } else {
    c.fail(field + "." + kind_key,
           "unknown kind '" + kind + "'; known: sphere, product_of_circles, torus_of_revolution, so3");
  }
  return sh;
}

}  // namespace

ManifoldSpec parse_spec(const std::string& text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + std::min(e.byte, text.size()), '\n'));
    throw InputError(source, line, std::string("invalid JSON: ") + e.what());
  }
  Ctx c{source};
  if (!j.is_object()) c.fail("(top level)", "expected a JSON object");
  const json& fmt = require(j, "format", c);
  if (!fmt.is_string() || fmt.get<std::string>() != "delcert-manifold v1")
    c.fail("format", "expected \"delcert-manifold v1\", found " + fmt.dump() + "; this reader knows version 1 only");
  ManifoldSpec s;
  s.source = source;
  s.name = j.value("name", std::string());
  s.intrinsic_dimension = static_cast<int>(get_int(require(j, "intrinsic_dimension", c), "intrinsic_dimension", c));
  s.ambient_dimension = static_cast<int>(get_int(require(j, "ambient_dimension", c), "ambient_dimension", c));
  const int N = s.ambient_dimension, m = s.intrinsic_dimension;
  if (N < 2 || N > 64) c.fail("ambient_dimension", "must be between 2 and 64");
  if (m < 1 || m >= N) c.fail("intrinsic_dimension", "must be between 1 and ambient_dimension - 1");
  const json& eq = require(j, "equations", c);
  if (!eq.is_array()) c.fail("equations", "expected an array of polynomial strings");
  if (static_cast<int>(eq.size()) != N - m)
    c.fail("equations", "has " + std::to_string(eq.size()) + " equations but a " + std::to_string(m) +
                            "-manifold in R^" + std::to_string(N) + " needs N - m = " + std::to_string(N - m));
  for (std::size_t i = 0; i < eq.size(); ++i) {
    s.equations.push_back(get_polynomial(eq[i], "equations[" + std::to_string(i) + "]", N, c));
    s.equation_text.push_back(eq[i].get<std::string>());
    if (s.equations.back().is_constant())
      c.fail("equations[" + std::to_string(i) + "]", "is constant; every equation must involve the coordinates");
  }
  if (j.contains("selector") && !j["selector"].is_null()) {
    s.selector = get_polynomial(j["selector"], "selector", N, c);
    s.selector_text = j["selector"].get<std::string>();
  }
  if (j.contains("reach") && !j["reach"].is_null()) {
    const json& r = j["reach"];
    if (!r.is_object()) c.fail("reach", "expected {\"value\": \"...\", \"kind\": \"exact\"|\"lower_bound\"}");
    const json& v = require(r, "value", c, "reach.");
    if (!v.is_string()) c.fail("reach.value", "expected a string such as \"1\" or \"sqrt(2)\"");
    ReachSpec rs;
    rs.text = v.get<std::string>();
    std::string t = rs.text;
    bool is_sqrt = t.rfind("sqrt(", 0) == 0 && t.size() > 6 && t.back() == ')';
    try {
      mpq_class q = parse_rational(is_sqrt ? t.substr(5, t.size() - 6) : t);
      rs.squared = is_sqrt ? q : mpq_class(q * q);
      if (q <= 0) c.fail("reach.value", "must be positive");
    } catch (const std::invalid_argument& e) {
      c.fail("reach.value", std::string(e.what()) + "; write a rational or sqrt(rational)");
    }
    std::string kind = r.value("kind", std::string("exact"));
    if (kind != "exact" && kind != "lower_bound") c.fail("reach.kind", "expected \"exact\" or \"lower_bound\"");
    rs.exact = kind == "exact";
    s.reach = rs;
  }
  if (j.contains("metric") && !j["metric"].is_null()) s.metric = get_shape(j["metric"], "metric", "type", s, c);
  if (j.contains("parametrization") && !j["parametrization"].is_null())
    s.parametrization = get_shape(j["parametrization"], "parametrization", "name", s, c);
  if (j.contains("bounding_box") && !j["bounding_box"].is_null()) {
    const json& b = j["bounding_box"];
    if (!b.is_array() || static_cast<int>(b.size()) != N)
      c.fail("bounding_box", "expected " + std::to_string(N) + " intervals [lo, hi]");
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto iv = get_rationals(b[i], "bounding_box[" + std::to_string(i) + "]", c, 2);
      if (!(iv[0] < iv[1])) c.fail("bounding_box[" + std::to_string(i) + "]", "needs lo < hi");
      s.bounding_box.emplace_back(iv[0].get_d(), iv[1].get_d());
    }
  }
  if (j.contains("residual_tolerance")) {
    s.residual_tolerance = get_rational(j["residual_tolerance"], "residual_tolerance", c);
    if (s.residual_tolerance < 0) c.fail("residual_tolerance", "must be non-negative");
  }
  if (j.contains("expected") && !j["expected"].is_null()) {
    const json& e = j["expected"];
    if (e.contains("euler_characteristic"))
      s.expected.euler_characteristic = get_int(e["euler_characteristic"], "expected.euler_characteristic", c);
    for (auto [key, dst] : {std::pair{"betti_z2", &s.expected.betti_z2}, std::pair{"betti_z3", &s.expected.betti_z3}}) {
      if (!e.contains(key)) continue;
      const json& a = e[key];
      std::string f = std::string("expected.") + key;
      if (!a.is_array() || static_cast<int>(a.size()) != m + 1) c.fail(f, "expected m + 1 integers");
      for (std::size_t i = 0; i < a.size(); ++i) dst->push_back(get_int(a[i], f + "[" + std::to_string(i) + "]", c));
    }
  }
  if (!s.parametrization && s.bounding_box.empty())
    c.fail("bounding_box", "missing: a spec without a parametrization needs a bounding box for sampling");
  return s;
}

ManifoldSpec read_spec(const std::string& source) {
  constexpr std::string_view prefix = "builtin:";
  if (source.rfind(prefix, 0) == 0) {
    std::string name = source.substr(prefix.size());
    const char* text = builtin_spec_text(name);
    if (!text) {
      std::string known;
      for (auto& n : builtin_spec_names()) known += (known.empty() ? "" : ", ") + n;
      throw InputError(source, 0, "no built-in manifold '" + name + "'; known: " + known);
    }
    return parse_spec(text, source);
  }
  return parse_spec(read_file(source), source);
}

}  // namespace delcert::io
