#include "exact/angle_series.hpp"

#include <array>
#include <stdexcept>


namespace delcert::exact {

namespace {

constexpr int kTerms = 64;  // at u <= 1 the terms fall by 2 each: 2^-64 of the first one is below every rounding

// Enclosures [lo, hi] of c_n and of n c_n (n = 1..kTerms), by the recurrence of angle_series.hpp
// in interval arithmetic under upward rounding (each step outward, so each entry encloses its
// value). All are positive.
struct Coefficients {
  std::array<double, kTerms + 1> lo{}, hi{}, slope_lo{}, slope_hi{};
};
const Coefficients& coefficients() {
  static const Coefficients k = [] {
    UpwardRounding up;
    Coefficients t;
    IntervalNumber c(2);
    for (int n = 1; n <= kTerms; ++n) {
      const IntervalNumber d = c * IntervalNumber(n);
      t.lo[n] = c.inf(), t.hi[n] = c.sup(), t.slope_lo[n] = d.inf(), t.slope_hi[n] = d.sup();
      c = c * IntervalNumber(2.0 * n * n) / (IntervalNumber(2.0 * n + 2) * IntervalNumber(2.0 * n + 1));
    }
    return t;
  }();
  return k;
}

// U ∩ [0, 2], or throws.
IntervalNumber clamp(const IntervalNumber& U) {
  const double lo = std::max(U.inf(), 0.0), hi = std::min(U.sup(), 2.0);
  if (!(lo <= hi)) throw std::domain_error("acos_squared: the argument misses [0, 2]");
  return IntervalNumber(lo, hi);
}

// sum_n k_n U^(n - shift) with k_n = c_n (the series of g, power n) or n c_n (g', power n - 1),
// for 0 <= U <= 1, stopped once a term's upper bound is below `tolerance` of the sum's lower bound
// or below 2^-12 of the sum's width (the range is that wide anyway), or after kTerms; plus the
// tail [0, term] (angle_series.hpp: ratio < 1/2). Every quantity is >= 0, so the lower and upper
// chains are kept apart in doubles under upward rounding: an upper bound of a product or sum of
// nonnegative upper bounds is the rounded-up result; a lower bound of a * b is -((-a) * b) (the
// rounded-up value of -ab is >= -ab), of a + b likewise -((-a) - b).
IntervalNumber series(const IntervalNumber& U, bool slope, double tolerance = 0x1p-60) {
  const Coefficients& k = coefficients();
  const auto& klo = slope ? k.slope_lo : k.lo;
  const auto& khi = slope ? k.slope_hi : k.hi;
  const double ulo = U.inf(), uhi = U.sup();
  double plo = 1, phi = 1, slo = 0, shi = 0, thi = 0;
  for (int n = 1; n <= kTerms; ++n) {
    if (!slope) plo = -((-plo) * ulo), phi = phi * uhi;  // U^n for g; U^(n-1) for g' (1 at n = 1)
    const double tlo = -((-klo[n]) * plo);
    thi = khi[n] * phi;
    slo = -((-slo) - tlo), shi = shi + thi;
    if (slope) plo = -((-plo) * ulo), phi = phi * uhi;
    if (thi <= tolerance * slo || thi <= 0x1p-12 * (shi - slo)) break;
  }
  return IntervalNumber(slo, shi + thi);
}

// g at a point interval X = [x, x] (or a few ulps wide) in [0, 2]: the series below 1, and above
// g(u) = (pi - sqrt(g(2 - u)))^2 (acos(1 - u) = pi - acos(1 - (2 - u))), 2 - u <= 1.
IntervalNumber at(const IntervalNumber& X, double tolerance) {
  if (X.sup() <= 1) return series(X, false, tolerance);
  const IntervalNumber pi(3.141592653589793, 3.1415926535897936);  // the doubles below and above pi
  const IntervalNumber other = IntervalNumber(2) - X;
  const IntervalNumber theta = pi - sqrt(series(IntervalNumber(std::max(other.inf(), 0.0), other.sup()), false, tolerance));
  return square(IntervalNumber(std::max(theta.inf(), 0.0), theta.sup()));
}

}  // namespace

IntervalNumber acos_squared(const IntervalNumber& U, double relative_tolerance) {
  const IntervalNumber u = clamp(U);
  if (u.sup() <= 1) return series(u, false, relative_tolerance);
  // g is increasing: its range is [g(lo), g(hi)], each end at a point.
  return IntervalNumber(at(IntervalNumber(u.inf()), relative_tolerance).inf(),
                        at(IntervalNumber(u.sup()), relative_tolerance).sup());
}

std::optional<IntervalNumber> acos_squared_slope(const IntervalNumber& U) {
  const IntervalNumber u = clamp(U);
  if (u.sup() > 1) return std::nullopt;
  return series(u, true);
}

}  // namespace delcert::exact
