// What exact/ asks of a manifold's system of equations F = 0, for the spec reader to enforce once
// (io/spec.cpp), so that every consumer (charts, Krawczyk, distance tests, residuals; certifier and
// producer alike) sees the same equations.
#pragma once

#include "exact/polynomial.hpp"

namespace delcert::exact {

// The largest codimension N - m supported: the exact tangent bases are cofactor formulas
// instantiated for k x k minors with k <= 8 (exact/detail/kernels.hpp). The spec reader refuses a
// larger one up front (exit 2), so that no run ends in an internal error halfway.
inline constexpr int kMaxCodimension = 8;

// The equation p = 0 written at a canonical scale: p times a positive rational that depends only
// on the ray {c p : c > 0}. First the primitive part (denominators cleared, the numerators' gcd
// divided out: integer coefficients with gcd 1), then division by the power of two 2^e with the
// largest |coefficient| in [1, 2). Multiplying by a positive rational is exact in rationals and keeps
// the zero set, and the sign of p everywhere (a selector's sign, a distance's orientation); only the
// magnitude goes, which is what made an equation times 10^-400 underflow every enclosure of its
// coefficients (and times 10^400 overflow them). So c p and p give the same polynomial for every
// rational c > 0 (and equal up to sign for c < 0). Where the common denominator has more than
// PolynomialLimits::max_coefficient_bits bits the primitive step is skipped (only the power of two is
// taken out): the coefficients stay of bounded size, and only such absurd specs lose the equality.
Polynomial at_canonical_scale(const Polynomial& p);

}  // namespace delcert::exact
