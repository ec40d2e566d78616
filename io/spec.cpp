#include "io/spec.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>

#include "exact/equations.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"
#include "io/detail/strict_json.hpp"

namespace delcert::io {

using nlohmann::json;

namespace {

// Every message names the file and the line of the field (StrictJson keeps the lines).
struct Ctx {
  const std::string& file;
  const detail::StrictJson& doc;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(file, doc.line(field), "field '" + field + "': " + what);
  }
};

// Refuses a key that is not in `known`: a misspelt optional key ("expeted") would otherwise turn a
// check off without a word.
void only_keys(const json& obj, const std::string& field, std::initializer_list<const char*> known, const Ctx& c) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (std::any_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; })) continue;
    std::string list;
    for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    const std::string path = detail::json_member_path(field, it.key());
    throw InputError(c.file, c.doc.key_line(path),
                     "unknown key '" + path + "'" + (list.empty() ? "" : "; known here: " + list));
  }
}

const json& require(const json& obj, const char* key, const Ctx& c, const std::string& parent = "") {
  if (!obj.contains(key)) c.fail(detail::json_member_path(parent, key), "missing; it is required");
  return obj.at(key);
}

// An integer in [lo, hi], read exactly from the number as written (never wrapped).
long get_int(const json& v, const std::string& field, const Ctx& c, long lo, long hi) {
  std::optional<mpz_class> z = v.is_number() ? c.doc.integer(field) : std::nullopt;
  if (!z) c.fail(field, "expected an integer, found " + v.dump());
  if (*z < lo || *z > hi)
    c.fail(field, z->get_str() + " is out of range: it must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  return z->get_si();
}

// A rational given as a JSON string ("0.1", "1/3") or a JSON integer (of any size, exact). JSON
// numbers with a fraction or exponent are refused: they are already rounded to binary and would
// silently change the manifold.
mpq_class get_rational(const json& v, const std::string& field, const Ctx& c) {
  if (v.is_number()) {
    if (auto z = c.doc.integer(field)) return mpq_class(*z);
  } else if (v.is_string()) {
    try {
      return exact::parse_rational(v.get<std::string>());
    } catch (const std::invalid_argument& e) {
      c.fail(field, e.what());
    }
  }
  c.fail(field, "expected an exact rational as a string such as \"0.1\" or \"1/3\", found " + v.dump());
}

std::vector<mpq_class> get_rationals(const json& v, const std::string& field, const Ctx& c, std::size_t n) {
  if (!v.is_array() || (n && v.size() != n))
    c.fail(field, "expected an array of " + (n ? std::to_string(n) + " " : std::string()) + "rationals");
  std::vector<mpq_class> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(get_rational(v[i], detail::json_element_path(field, i), c));
  return out;
}

std::string get_string(const json& v, const std::string& field, const Ctx& c) {
  if (!v.is_string()) c.fail(field, "expected a string, found " + v.dump());
  return v.get<std::string>();
}

exact::Polynomial get_polynomial(const json& v, const std::string& field, int n, const Ctx& c) {
  if (!v.is_string()) c.fail(field, "expected a polynomial as a string, found " + v.dump());
  std::string text = v.get<std::string>();
  std::string shown = text.size() > 200 ? text.substr(0, 200) + "..." : text;
  try {
    return exact::Polynomial::parse(text, n);
  } catch (const exact::PolynomialParseError& e) {
    c.fail(field, std::string(e.what()) + " at character " + std::to_string(e.offset + 1) + " of \"" + shown + "\"");
  } catch (const std::overflow_error& e) {  // not reachable within PolynomialLimits; never wrap
    c.fail(field, std::string("polynomial too large: ") + e.what());
  }
}

ShapeSpec get_shape(const json& v, const std::string& field, const char* kind_key, const ManifoldSpec& s, const Ctx& c) {
  if (!v.is_object()) c.fail(field, "expected an object");
  const std::string kind = get_string(require(v, kind_key, c, field), detail::json_member_path(field, kind_key), c);
  auto at = [&](const char* key) { return detail::json_member_path(field, key); };
  ShapeSpec sh;
  const int N = s.ambient_dimension, m = s.intrinsic_dimension;
  if (kind == "sphere") {
    only_keys(v, field, {kind_key, "center", "radius"}, c);
    sh.kind = ShapeSpec::Kind::sphere;
    if (m != N - 1) c.fail(field, "a sphere has intrinsic dimension N - 1");
    sh.center = v.contains("center") ? get_rationals(v.at("center"), at("center"), c, N)
                                     : std::vector<mpq_class>(N, mpq_class(0));
    sh.radius = get_rational(require(v, "radius", c, field), at("radius"), c);
    if (sh.radius <= 0) c.fail(at("radius"), "must be positive");
  } else if (kind == "product_of_circles") {
    only_keys(v, field, {kind_key, "radii"}, c);
    sh.kind = ShapeSpec::Kind::product_of_circles;
    sh.radii = get_rationals(require(v, "radii", c, field), at("radii"), c, 0);
    if (static_cast<int>(sh.radii.size()) != m || N != 2 * m)
      c.fail(at("radii"), "a product of m circles needs m radii and N = 2m");
    for (auto& r : sh.radii)
      if (r <= 0) c.fail(at("radii"), "radii must be positive");
  } else if (kind == "torus_of_revolution") {
    only_keys(v, field, {kind_key, "major_radius", "minor_radius"}, c);
    sh.kind = ShapeSpec::Kind::torus_of_revolution;
    if (m != 2 || N != 3) c.fail(field, "a torus of revolution is a surface in R^3");
    sh.major_radius = get_rational(require(v, "major_radius", c, field), at("major_radius"), c);
    sh.minor_radius = get_rational(require(v, "minor_radius", c, field), at("minor_radius"), c);
    if (!(sh.major_radius > sh.minor_radius && sh.minor_radius > 0))
      c.fail(field, "needs major_radius > minor_radius > 0");
  } else if (kind == "so3") {
    only_keys(v, field, {kind_key}, c);
    sh.kind = ShapeSpec::Kind::so3;
    if (m != 3 || N != 9) c.fail(field, "so3 has intrinsic dimension 3 in R^9");
  } else if (kind == "product") {
    only_keys(v, field, {kind_key, "factors"}, c);
    sh.kind = ShapeSpec::Kind::product;
    const json& fs = require(v, "factors", c, field);
    if (!fs.is_array() || fs.empty()) c.fail(at("factors"), "expected a non-empty array of factors");
    std::vector<bool> used(N, false);
    int dimension = 0;
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const std::string f = detail::json_element_path(at("factors"), i);
      const json& fv = fs[i];
      if (!fv.is_object()) c.fail(f, "expected {\"type\": \"sphere\" or \"so3\", \"coordinates\": [...], ...}");
      const std::string type = get_string(require(fv, "type", c, f), detail::json_member_path(f, "type"), c);
      ShapeFactor factor;
      if (type == "sphere") {
        only_keys(fv, f, {"type", "coordinates", "radius"}, c);
        factor.radius = get_rational(require(fv, "radius", c, f), detail::json_member_path(f, "radius"), c);
        if (factor.radius <= 0) c.fail(detail::json_member_path(f, "radius"), "must be positive");
      } else if (type == "so3") {
        only_keys(fv, f, {"type", "coordinates"}, c);
        factor.kind = ShapeFactor::Kind::so3;
      } else {
        c.fail(detail::json_member_path(f, "type"), "unknown factor type '" + type + "'; known: sphere, so3");
      }
      const std::string cf = detail::json_member_path(f, "coordinates");
      const json& cv = require(fv, "coordinates", c, f);
      if (!cv.is_array()) c.fail(cf, "expected an array of coordinate numbers 1..N");
      for (std::size_t k = 0; k < cv.size(); ++k) {
        const int x = static_cast<int>(get_int(cv[k], detail::json_element_path(cf, k), c, 1, N)) - 1;
        if (used[x]) c.fail(detail::json_element_path(cf, k), "coordinate x" + std::to_string(x + 1) + " is already in a factor");
        used[x] = true;
        factor.coordinates.push_back(x);
      }
      if (factor.kind == ShapeFactor::Kind::sphere && factor.coordinates.size() < 2)
        c.fail(cf, "a sphere factor needs at least 2 coordinates (a circle)");
      if (factor.kind == ShapeFactor::Kind::so3 && factor.coordinates.size() != 9)
        c.fail(cf, "an so3 factor needs 9 coordinates (a rotation matrix, row-major)");
      dimension += factor.dimension();
      sh.factors.push_back(std::move(factor));
    }
    for (int x = 0; x < N; ++x)
      if (!used[x]) c.fail(at("factors"), "coordinate x" + std::to_string(x + 1) + " is in no factor; the factors must cover x1..xN");
    if (dimension != m)
      c.fail(at("factors"), "the factors' dimensions add up to " + std::to_string(dimension) + ", not the intrinsic dimension " +
                                std::to_string(m));
  } else {
    c.fail(at(kind_key), "unknown kind '" + kind + "'; known: sphere, product_of_circles, torus_of_revolution, so3, product");
  }
  return sh;
}

}  // namespace

ManifoldSpec parse_spec(const std::string& text, const std::string& source) {
  const detail::StrictJson doc = detail::StrictJson::parse(text, source);
  const json& j = doc.root();
  Ctx c{source, doc};
  if (!j.is_object()) c.fail("(top level)", "expected a JSON object");
  const json& fmt = require(j, "format", c);
  if (!fmt.is_string() || fmt.get<std::string>() != "delcert-manifold v1")
    c.fail("format", "expected \"delcert-manifold v1\", found " + fmt.dump() + "; this reader knows version 1 only");
  only_keys(j, "",
            {"format", "name", "intrinsic_dimension", "ambient_dimension", "equations", "selector", "reach", "metric",
             "parametrization", "bounding_box", "residual_tolerance", "expected"},
            c);
  ManifoldSpec s;
  s.source = source;
  if (j.contains("name")) s.name = get_string(j.at("name"), "name", c);
  s.ambient_dimension = static_cast<int>(get_int(require(j, "ambient_dimension", c), "ambient_dimension", c, 2, kMaxAmbientDimension));
  const int N = s.ambient_dimension;
  s.intrinsic_dimension = static_cast<int>(get_int(require(j, "intrinsic_dimension", c), "intrinsic_dimension", c, 1, N - 1));
  const int m = s.intrinsic_dimension;
  if (N - m > exact::kMaxCodimension)
    c.fail("intrinsic_dimension", "the codimension N - m = " + std::to_string(N) + " - " + std::to_string(m) + " = " +
                                      std::to_string(N - m) + " exceeds the supported maximum " +
                                      std::to_string(exact::kMaxCodimension) +
                                      " (exact tangent bases); describe M in a smaller ambient space");
  const json& eq = require(j, "equations", c);
  if (!eq.is_array()) c.fail("equations", "expected an array of polynomial strings");
  if (static_cast<int>(eq.size()) != N - m)
    c.fail("equations", "has " + std::to_string(eq.size()) + " equations but a " + std::to_string(m) +
                            "-manifold in R^" + std::to_string(N) + " needs N - m = " + std::to_string(N - m));
  // Every equation (and the selector) is kept at its canonical scale (exact::at_canonical_scale:
  // times a positive rational, so the zero set and every sign are the written ones): whatever
  // reads the spec, the certifier's charts, Krawczyk and distance tests, the residual check and
  // the producer, sees F and c F (c > 0) as the same polynomial; `equation_text` keeps the text.
  for (std::size_t i = 0; i < eq.size(); ++i) {
    const std::string f = detail::json_element_path("equations", i);
    s.equations.push_back(exact::at_canonical_scale(get_polynomial(eq[i], f, N, c)));
    s.equation_text.push_back(eq[i].get<std::string>());
    if (s.equations.back().is_constant()) c.fail(f, "is constant; every equation must involve the coordinates");
  }
  if (j.contains("selector") && !j.at("selector").is_null()) {
    s.selector = exact::at_canonical_scale(get_polynomial(j.at("selector"), "selector", N, c));
    s.selector_text = j.at("selector").get<std::string>();
  }
  if (j.contains("reach") && !j.at("reach").is_null()) {
    const json& r = j.at("reach");
    if (!r.is_object()) c.fail("reach", "expected {\"value\": \"...\", \"kind\": \"exact\"|\"lower_bound\"}");
    only_keys(r, "reach", {"value", "kind"}, c);
    const json& v = require(r, "value", c, "reach");
    if (!v.is_string()) c.fail("reach.value", "expected a string such as \"1\" or \"sqrt(2)\"");
    ReachSpec rs;
    rs.text = v.get<std::string>();
    std::string t = rs.text;
    bool is_sqrt = t.rfind("sqrt(", 0) == 0 && t.size() > 6 && t.back() == ')';
    try {
      mpq_class q = exact::parse_rational(is_sqrt ? t.substr(5, t.size() - 6) : t);
      rs.squared = is_sqrt ? q : mpq_class(q * q);
      if (q <= 0) c.fail("reach.value", "must be positive");
    } catch (const std::invalid_argument& e) {
      c.fail("reach.value", std::string(e.what()) + "; write a rational or sqrt(rational)");
    }
    std::string kind = r.contains("kind") ? get_string(r.at("kind"), "reach.kind", c) : std::string("exact");
    if (kind != "exact" && kind != "lower_bound") c.fail("reach.kind", "expected \"exact\" or \"lower_bound\"");
    rs.exact = kind == "exact";
    s.reach = rs;
  }
  if (j.contains("metric") && !j.at("metric").is_null()) s.metric = get_shape(j.at("metric"), "metric", "type", s, c);
  if (j.contains("parametrization") && !j.at("parametrization").is_null())
    s.parametrization = get_shape(j.at("parametrization"), "parametrization", "name", s, c);
  if (j.contains("bounding_box") && !j.at("bounding_box").is_null()) {
    const json& b = j.at("bounding_box");
    if (!b.is_array() || static_cast<int>(b.size()) != N)
      c.fail("bounding_box", "expected " + std::to_string(N) + " intervals [lo, hi]");
    for (std::size_t i = 0; i < b.size(); ++i) {
      const std::string f = detail::json_element_path("bounding_box", i);
      auto iv = get_rationals(b[i], f, c, 2);
      if (!(iv[0] < iv[1])) c.fail(f, "needs lo < hi");
      s.bounding_box.emplace_back(iv[0].get_d(), iv[1].get_d());
    }
  }
  if (j.contains("residual_tolerance")) {
    s.residual_tolerance = get_rational(j.at("residual_tolerance"), "residual_tolerance", c);
    if (s.residual_tolerance < 0) c.fail("residual_tolerance", "must be non-negative");
  }
  if (j.contains("expected") && !j.at("expected").is_null()) {
    const json& e = j.at("expected");
    if (!e.is_object()) c.fail("expected", "expected an object {\"euler_characteristic\": ..., \"betti_z2\": [...], ...}");
    only_keys(e, "expected", {"euler_characteristic", "betti_z2", "betti_z3"}, c);
    // Exact integers within long; a value beyond is refused, never wrapped.
    constexpr long big = std::numeric_limits<long>::max();
    if (e.contains("euler_characteristic"))
      s.expected.euler_characteristic =
          get_int(e.at("euler_characteristic"), "expected.euler_characteristic", c, -big, big);
    for (auto [key, dst] : {std::pair{"betti_z2", &s.expected.betti_z2}, std::pair{"betti_z3", &s.expected.betti_z3}}) {
      if (!e.contains(key)) continue;
      const json& a = e.at(key);
      std::string f = detail::json_member_path("expected", key);
      if (!a.is_array() || static_cast<int>(a.size()) != m + 1) c.fail(f, "expected m + 1 integers");
      for (std::size_t i = 0; i < a.size(); ++i) dst->push_back(get_int(a[i], detail::json_element_path(f, i), c, 0, big));
    }
  }
  if (!s.parametrization && s.bounding_box.empty())
    c.fail("bounding_box", "missing: a spec without a parametrization needs a bounding box for sampling");
  return s;
}

namespace {

// Levenshtein distance (insertions, deletions, substitutions), case-insensitive.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearest_builtin_spec_name(const std::string& name) {
  std::string best;
  std::size_t best_distance = 0;
  for (const auto& n : builtin_spec_names()) {
    const std::size_t d = edit_distance(name, n);
    if (best.empty() || d < best_distance) best = n, best_distance = d;  // first of equals: the list's order
  }
  // Near enough to be a misspelling: at most a third of the name (at least 2 edits) away.
  const std::size_t allowed = std::max<std::size_t>(2, std::max(name.size(), best.size()) / 3);
  return best_distance <= allowed ? best : std::string();
}

std::string read_spec_text(const std::string& source) {
  constexpr std::string_view prefix = "builtin:";
  if (source.rfind(prefix, 0) == 0) {
    std::string name = source.substr(prefix.size());
    const char* text = builtin_spec_text(name);
    if (!text) {
      std::string known;
      for (auto& n : builtin_spec_names()) known += (known.empty() ? "" : ", ") + n;
      const std::string nearest = nearest_builtin_spec_name(name);
      throw InputError(source, 0,
                       "no built-in manifold '" + name + "'; " +
                           (nearest.empty() ? std::string() : "did you mean builtin:" + nearest + "? ") + "known: " + known);
    }
    return text;
  }
  // "--manifold sphere-2": a built-in's name without the prefix, taken for a file that is not there.
  std::error_code error;
  if (!std::filesystem::exists(source, error)) {
    const std::string nearest = nearest_builtin_spec_name(source);
    if (!nearest.empty())
      throw InputError(source, 0, "no such file; for the built-in manifold, write --manifold builtin:" + nearest);
  }
  return read_file(source);
}

ManifoldSpec read_spec(const std::string& source) { return parse_spec(read_spec_text(source), source); }

mpq_class parse_residual_tolerance(const std::string& text, const std::string& option) {
  mpq_class t;
  try {
    t = exact::parse_rational(text);
  } catch (const std::invalid_argument& e) {
    throw InputError(option, 0, "'" + text + "' is not a number (" + e.what() +
                                    "); give a positive decimal such as 1e-6 or a fraction such as 1/1000000");
  }
  if (t <= 0)
    throw InputError(option, 0, "'" + text + "' is not positive; the tolerance is the largest |F_i(p)| accepted, > 0");
  return t;
}

}  // namespace delcert::io
