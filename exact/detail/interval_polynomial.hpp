// Interval evaluation of exact polynomials, shared by the Krawczyk solver and the certified
// distance to M (exact/krawczyk.cpp, exact/manifold_distance.cpp). Private to exact/.
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/interval.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact::detail {

// The enclosures of p's coefficients, in the order of p.terms().
inline std::vector<Interval> coefficient_enclosures(const Polynomial& p) {
  std::vector<Interval> out;
  for (const auto& t : p.terms()) out.push_back(enclose(t.coefficient));
  return out;
}

// Interval evaluation of p over the box x (the caller holds upward rounding): every term is an
// enclosure of its true value (coefficient enclosed, powers by repeated interval products), so
// the sum encloses p(x) for every x in the box.
inline IA evaluate(const Polynomial& p, const std::vector<Interval>& coef, std::span<const IA> x) {
  return p.evaluate_with<IA>(x, [&](std::size_t i) { return to_ia(coef[i]); });
}

inline bool finite(const IA& x) { return std::isfinite(x.inf()) && std::isfinite(x.sup()); }

}  // namespace delcert::exact::detail
