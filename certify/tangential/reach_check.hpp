// Refuting a declared reach (part of check 1, input_sanity). The spec's reach is an input taken on
// trust where it is used (THE GRAPH LEMMA of certify/rvd.cpp, codimension >= 4); two points of M can
// prove it false.
//
// FEDERER (1959, Thm 4.18): if M has reach >= τ > 0, then for all x, y in M
//   dist(y - x, T_x M) <= |y - x|^2 / (2 τ).
// So two points x, y of M with dist(y - x, T_x M) > |y - x|^2 / (2 τ) prove reach(M) < τ: the spec's
// reach (exact or a lower bound, both claim reach(M) >= τ) is false.
//
// THE POINTS OF M. The sample points are only near M. For each sample point p the interval Krawczyk
// test of check 1 (exact::ManifoldDistance, exact/manifold_distance.hpp) proves a point p* of M
// (F(p*) = 0, the selector > 0) in a box P*, with J_F of rank k = N - m on a box around p*, so
// T_{p*} M = ker J where J = J_F(p*), and P_N = J^T G^{-1} J (G = J J^T, invertible) is the
// orthogonal projection on the normal space (J's row space).
//
// THE BOUNDS, for the pair (p, q) with boxes P*, Q* and d = q* - p* (every interval operation outward
// rounded under upward rounding, so each computed enclosure holds the exact value; overflow gives
// an infinite bound, which refutes nothing):
//  * J lies in J_F(P*) (exact::jacobian_enclosure), d in Q* - P*, so J d lies in J_F(P*) (Q* - P*);
//    |J d|^2 >= sum_e mig((J d)_e)^2 (mig: the smallest magnitude in the interval, 0 if it holds 0).
//  * λ_max(G) <= Λ, Gershgorin's bound on the interval matrix J_F(P*) J_F(P*)^T
//    (exact::gram_eigenvalue_bounds), the same for every J in J_F(P*).
//  * dist(d, T_{p*} M)^2 = |P_N d|^2 = (J d)^T G^{-1} (J d) >= |J d|^2 / λ_max(G) >= |J d|^2 / Λ
//    (G^{-1}'s eigenvalues are >= 1 / λ_max(G)): normal_distance_lower = sqrt(that), rounded down.
//  * |d|^2 <= sum_v sup((Q*_v - P*_v)^2) and τ >= τ_lo (the largest double <= the declared reach):
//    federer_bound_upper = that / (2 τ_lo), rounded up.
// ROW SCALING. J_F's rows are first multiplied by powers of two 2^{s_e} (magnitude about 1): for
// D = diag(2^{s_e}), (D J)^T (D G D)^{-1} (D J) = J^T G^{-1} J, so P_N and the bound above are the same
// with D J in place of J; Gershgorin's Λ is tighter for rows of like lengths. (2^{s_e} is exact, or
// +infinity for a row below 2^-1023, which only makes Λ infinite: the point then refutes nothing;
// the interval products are outward rounded.)
// normal_distance_lower > federer_bound_upper then proves the Federer inequality violated at
// (p*, q*). Pairs farther apart than 2 τ cannot refute (dist(d, T) <= |d|), so the search radius is
// capped at 2 τ (rounded up) plus the points' distances to M.
#pragma once

#include <optional>

#include "certify/certificate.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

namespace detail {
class PointGrid;
}  // namespace detail

struct ReachWitness {
  int i = -1, j = -1;                 // the sample points (i < j)
  int tangent_at = -1;                // i or j: the point whose tangent space is used
  double normal_distance_lower = 0;   // <= dist(q* - p*, T_{p*} M), p* the point of M near tangent_at
  double squared_distance_upper = 0;  // >= |q* - p*|^2
  double federer_bound_upper = 0;     // >= |q* - p*|^2 / (2 declared reach); < normal_distance_lower
};

// Tests every pair of points within `radius` of each other (grid queries; capped as above), both
// orientations, and returns the witness with the lowest (i, j), then i's tangent space first; none
// when no pair refutes the reach (which proves nothing: the test only refutes). Points whose point
// of M cannot be certified (check 1 refuses them already) are skipped. `system`: the spec's
// equations; `reach`: the spec's declared reach.
std::optional<ReachWitness> refute_declared_reach(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                                                  const io::PointSet& points, const detail::PointGrid& grid,
                                                  const io::ReachSpec& reach, double radius, int threads);

// Check 1 REFUTED by the witness: witness kind "declared_reach_is_false", and a line in the summary.
void record_reach_refutation(CheckEntry& entry, const ReachWitness& w, const io::ReachSpec& reach);

}  // namespace delcert::certify
