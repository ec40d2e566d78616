// The squared angle g(u) = acos(1 - u)^2 in double interval arithmetic, for geodesic distances on
// round spheres: two points x, y of a sphere of radius r at angle theta have cos theta =
// <x, y> / r^2 =: 1 - u and geodesic distance^2 r^2 g(u) (certify/detail/param_cell.cpp,
// GEODESIC). g is increasing on [0, 2] and analytic on [0, 2) (the cut locus is u = 2, the
// antipode; unlike acos itself, g is smooth at u = 0), with the series
//   g(u) = sum_{n >= 1} c_n u^n,   c_n = 2^(n+1) / (n^2 binom(2n, n)),
// from arcsin(s)^2 = (1/2) sum_n (2s)^(2n) / (n^2 binom(2n, n)) (|s| <= 1) with theta =
// 2 arcsin(s), s^2 = u / 2 (1 - cos theta = 2 sin^2(theta / 2)). c_1 = 2, c_2 = 1/3, and
// c_{n+1} / c_n = 2 n^2 / ((2n + 2)(2n + 1)) < 1/2, so every coefficient is positive and, for
// 0 <= u <= 1, the tail after the term of index N is at most term_N (u/2) / (1 - u/2) <= term_N.
// The slope g'(u) = 2 theta / sin theta = sum_n n c_n u^(n-1) has the same ratio bound
// ((n + 1) c_{n+1} u / (n c_n) = n u / (2n + 1) < u / 2) and is finite only on [0, 2).
//
// ROUNDING. The functions require exact::UpwardRounding (the IntervalNumber contract). Every
// coefficient c_n (and n c_n) is enclosed by that recurrence in interval arithmetic (outward).
// For 0 <= U = [ul, uh] <= 1 every coefficient, power and term is >= 0, so the partial sum is
// computed as two chains of doubles: upper bounds by rounded-up products and sums of upper
// bounds, lower bounds as -((-a) * b) and -((-a) - b) of lower bounds (a rounded-up -x is >= -x).
// A polynomial with positive coefficients is increasing on U >= 0, so the chains bound
// [S_N(ul), S_N(uh)]: its range. Underflow: a product below the smallest subnormal rounds up to
// it in the upper chain and to -0 or 0 in the lower one, both still bounds; overflow cannot occur
// (u <= 1, c_n <= 2, n c_n <= 2). The tail [0, term] is added to the upper bound.
// For u beyond 1, g(u) = (pi - sqrt(g(2 - u)))^2 (acos(1 - u) = pi - acos(u - 1)) with 2 - u < 1
// and pi enclosed by its two neighbouring doubles; g increasing, the range of an interval U
// reaching beyond 1 is [g(inf U), g(sup U)], each end so evaluated at a point. The series stops
// early (2^-12 of the sum's width) on wide intervals only: the tail bound keeps it an enclosure.
#pragma once

#include <optional>

#include "exact/interval_arithmetic.hpp"

namespace delcert::exact {

// An enclosure of {acos(1 - u)^2 : u in U ∩ [0, 2]} (the part outside [0, 2] is ignored: a true
// u lies in it, and only rounding makes an enclosure poke out). Throws std::domain_error when
// U misses [0, 2]. Requires UpwardRounding.
// The series stops once a term is below relative_tolerance of the sum (or 2^-12 of its width):
// the tail bound is added, so the result is an enclosure whatever the tolerance; a looser one is
// only cheaper and wider.
IntervalNumber acos_squared(const IntervalNumber& U, double relative_tolerance = 0x1p-60);

// An enclosure of {g'(u) : u in U ∩ [0, 2]} = {2 theta / sin theta}, or nothing when U reaches
// beyond 1 (the series would converge slowly, and diverges at the cut locus u = 2). Requires
// UpwardRounding.
std::optional<IntervalNumber> acos_squared_slope(const IntervalNumber& U);

}  // namespace delcert::exact
