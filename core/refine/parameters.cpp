#include "core/refine/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "exact/polynomial.hpp"
#include "io/input_error.hpp"

namespace delcert::refine {

mpq_class mu0_times(const mpq_class& x) {
  mpq_class r = x / kMu0Reciprocal;
  r.canonicalize();
  return r;
}

ExactParameter::ExactParameter(const mpq_class& q) : value(q), text(exact::rational_to_string(q)) { value.canonicalize(); }

ExactParameter ExactParameter::parse(std::string_view text) {
  ExactParameter p;
  p.value = exact::parse_rational(text);
  p.text = std::string(text);
  return p;
}

namespace {

bool positive_double(const mpq_class& q) {
  const double d = q.get_d();
  return d > 0 && std::isfinite(d);
}

// Why a positive q is no positive finite double: named limits, never the 300-digit numbers.
std::string double_range_reason(const mpq_class& q) {
  return q > 1 ? "must be at most 1.8e308 (the largest double): delcert computes with doubles"
               : "must be at least 4.9e-324 (the smallest positive double): delcert computes with doubles";
}

}  // namespace

void validate_eps(const ExactParameter& eps) {
  if (!(eps.value > 0)) throw ParameterError("--eps", "must be positive");
  if (!positive_double(eps.value)) throw ParameterError("--eps", double_range_reason(eps.value));
}

void validate(const Constants& c) {
  if (c.eps) validate_eps(*c.eps);
  if (!(c.gamma0.value > 0 && c.gamma0.value <= 1)) throw ParameterError("--gamma0", "must lie in (0, 1]");
  if (!(c.alpha.value > 0 && c.alpha.value < 1))
    throw ParameterError("--alpha", "must lie in (0, 1); the paper takes alpha < 1/2");
  if (!(c.beta.value > 0)) throw ParameterError("--beta", "must be positive; the paper takes beta > 1");
  if (!positive_double(c.beta.value)) throw ParameterError("--beta", double_range_reason(c.beta.value));
  if (c.delta0 && !(c.delta0->value >= 0 && c.delta0->value < 1))
    throw ParameterError("--delta0", "must lie in [0, 1); the paper takes delta0 < 1/4");
}

ConstantsAsDoubles as_doubles(const Constants& c) {
  ConstantsAsDoubles d;
  d.eps = c.eps.value().value.get_d();
  d.gamma0 = c.gamma0.value.get_d();
  d.alpha = c.alpha.value.get_d();
  d.beta = c.beta.value.get_d();
  d.delta0 = c.delta0.value().value.get_d();
  return d;
}

mpq_class default_delta0(const mpq_class& gamma0, int m) {
  mpq_class d(1);
  for (int i = 0; i < (m + 2) / 2; ++i) d *= gamma0;
  d.canonicalize();
  return d;
}

void resolve_delta0(Constants& c, int m) {
  if (!c.delta0) c.delta0 = ExactParameter(default_delta0(c.gamma0.value, m));
}

mpq_class decimal_above(double x) {
  if (!(x > 0) || !std::isfinite(x)) throw std::invalid_argument("decimal_above: needs a positive finite number");
  const int e = static_cast<int>(std::floor(std::log10(x))) - 1;  // two significant digits: k 10^e
  mpz_class p10;
  mpz_ui_pow_ui(p10.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(e)));
  for (long k = std::max(1L, static_cast<long>(std::floor(x / std::pow(10.0, e))));; ++k) {
    mpq_class q(k);
    if (e >= 0)
      q *= p10;
    else
      q /= p10;
    q.canonicalize();
    if (q.get_d() > x) return q;
  }
}

ExactParameter parse_rational_option(const std::string& option, const std::string& text) {
  try {
    return ExactParameter::parse(text);
  } catch (const std::invalid_argument&) {
    throw io::InputError(option, 0, "'" + text + "' is not a number; write a decimal or a fraction, e.g. 0.1 or 1/10");
  }
}

ExactParameter parse_eps_option(const std::string& text) {
  ExactParameter eps = parse_rational_option("--eps", text);
  try {
    validate_eps(eps);
  } catch (const ParameterError& e) {
    throw io::InputError(e.option(), 0, e.reason());
  }
  return eps;
}

Constants parse_constants(const ConstantTexts& a, int m) {
  auto checked = [](auto&& validate_part) {
    try {
      validate_part();
    } catch (const ParameterError& e) {
      throw io::InputError(e.option(), 0, e.reason());
    }
  };
  Constants c;
  if (!a.delta0) c.gamma0 = parse_rational_option("--gamma0", a.gamma0);
  if (a.eps) c.eps = parse_eps_option(*a.eps);
  c.gamma0 = parse_rational_option("--gamma0", a.gamma0);
  c.alpha = parse_rational_option("--alpha", a.alpha);
  c.beta = parse_rational_option("--beta", a.beta);
  if (a.delta0) c.delta0 = parse_rational_option("--delta0", *a.delta0);
  resolve_delta0(c, m);
  checked([&] { validate(c); });
  return c;
}

const char* to_string(SizingKind k) { return k == SizingKind::curvature ? "curvature" : "uniform"; }

void resolve_sizing(SizingField& s, const ExactParameter& eps) {
  auto finite_positive = [](const mpq_class& q) {
    const double d = q.get_d();
    return q > 0 && std::isfinite(d) && d > 0;
  };
  if (!finite_positive(s.c.value)) throw ParameterError("--sizing-c", "must be a positive number (got " + s.c.text + ")");
  if (!s.floor) {
    mpq_class f = eps.value / kDefaultFloorDivisor;
    f.canonicalize();
    s.floor = ExactParameter(f);
  }
  if (!finite_positive(s.floor->value))
    throw ParameterError("--eps-floor", "must be a positive number (got " + s.floor->text + ")");
  if (s.floor->value > eps.value)
    throw ParameterError("--eps-floor", "must not exceed --eps = " + eps.text + " (got " + s.floor->text +
                                            "): eps is the field's cap, the floor its lower bound");
}

}  // namespace delcert::refine
