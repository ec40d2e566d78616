#include "exact/number_types.hpp"

#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace delcert::exact {

mpq_class to_rational(double x) {
  if (!std::isfinite(x))
    throw std::invalid_argument("not a finite number (" + std::to_string(x) +
                                "): exact arithmetic needs finite coordinates");
  // mpq_set_d is exact for every finite double (GMP documentation).
  mpq_class q;
  mpq_set_d(q.get_mpq_t(), x);
  return q;
}

std::vector<mpq_class> to_rational(std::span<const double> x) {
  std::vector<mpq_class> out;
  out.reserve(x.size());
  for (double v : x) out.push_back(to_rational(v));
  return out;
}

bool is_dyadic(const mpq_class& q) {
  // A canonical denominator is a power of two iff it has a single set bit.
  return mpz_popcount(q.get_den_mpz_t()) == 1;
}

Interval enclose(const mpq_class& q) {
  // mpq_get_d truncates toward zero (GMP documentation) using integer operations only, so the
  // result does not depend on the FPU rounding mode. If the truncated value is not q itself,
  // the other bound is the next double away from zero.
  double t = mpq_get_d(q.get_mpq_t());
  if (std::isinf(t)) {
    // Beyond the double range: enclose by [DBL_MAX, inf] (or its negative).
    return t > 0 ? Interval{DBL_MAX, t} : Interval{t, -DBL_MAX};
  }
  mpq_class back;
  mpq_set_d(back.get_mpq_t(), t);
  if (back == q) return Interval::point(t);
  const double inf = std::numeric_limits<double>::infinity();
  if (sgn(q) > 0) return {t, std::nextafter(t, inf)};
  return {std::nextafter(t, -inf), t};
}

RationalConstant::RationalConstant(const mpq_class& value) : value_(value), enclosure_(enclose(value)) {
  value_.canonicalize();
}

}  // namespace delcert::exact
