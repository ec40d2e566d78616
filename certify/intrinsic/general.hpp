// Del_M(P) on a general M, with no closed-form geodesic distance (issue 40; docs/certificate.md,
// "Del_M without a closed-form metric"). The geodesic distance d_M is never computed: it is bounded,
//   |x - y| <= d_M(x, y) <= Φ_K(|x - y|) = (2/K) arcsin(K |x - y| / 2),
// the upper bound proven on the GRAPH BALL of each point (below) from a certified bound K of M's
// normal curvature (exact/geodesic_bounds.hpp, Schur's comparison), and Del_M is decided where the
// bounds separate, with the restricted engine's certified data (check 12) as the guide:
//
// CONVENTION. A sample point p is only near M: d_M(x, p) := d_M(x, p') for a point p' of M nearest
// to p, so |p - p'| <= delta_p (check 1's certified bound of d(p, M)). Every statement below holds
// for EVERY point p' of M within delta_p of p, hence for every choice of nearest point.
//
// THE GRAPH BALL of q (GraphBall). The chart of q (exact::ChartEnclosure::at) proves by Krawczyk that
// Y_q = M ∩ (U0 x Hg) is the graph of a continuous h over the box U0 = [-rho, rho]^m (one point over
// each u, in the slab Hg), which holds q' (Hg contains the normal coordinates of every point within
// delta_q of q). Y_q is connected. With c_Y >= max_{x in Y_q} |x - q| and K bounding |II| on the box
// [q +- (c_Y + R)] (so on every point of M within R of a point of Y_q), Φ_K(c_Y + delta_q) < R and
// K R <= π: for every x in Y_q, d_M(x, q') <= Φ_K(|x - q| + delta_q).
// Proof (open and closed): Ω = {x in Y_q : d_M(x, q') <= Φ_K(c_Y + delta_q)} is closed (d_M is
// continuous), holds q'. If x in Ω and x~ in Y_q is close enough that d_M(x~, q') < R, a minimizing
// geodesic from x~ to q' (M is compact) has length L < R <= π/K and lies within chord distance L of
// x~, where K bounds its curvature |γ''| = |II(γ', γ')|; by Schur's comparison |x~ - q'| >=
// (2/K) sin(K L / 2), so L <= Φ_K(|x~ - q'|) <= Φ_K(|x~ - q| + delta_q) <= Φ_K(c_Y + delta_q): x~
// is in Ω, which is open. Y_q is connected: Ω = Y_q, and the sharper bound holds at each x.
//
// EXISTENCE (each m-simplex σ of Del_RM(P)). In the chart of its finding point p, a box U_v around
// its restricted Voronoi vertex. E(u) = (|x - p_i|^2 - |x - p|^2)_i, x = x(u) on the graph, has
// exactly one zero in U_v, nondegenerate (Krawczyk on {G = 0, E = 0}: every matrix of the interval
// Jacobian is nonsingular, so is the Schur complement D(E o x)), so its degree is ±1; the same for
// B E with B a nonsingular matrix (det B != 0 exactly). G(u) = (d_M(x, p_i')^2 - d_M(x, p')^2)_i
// is continuous, and |G_i - E_i| <= e_i from the bounds above. On each face of U_v some component
// of B E exceeds the matching bound of |B (G - E)|: the homotopy B E + t B (G - E) has no zero on
// the boundary, so deg(B G) = ±1, and G has a zero w in x(U_v): all points of σ are at one geodesic
// distance ρ from w. Every other point q has d_M(w, q') >= |w - q| - delta_q > max_i Φ_{K_i}(|w -
// p_i| + delta_i) >= ρ on all of x(U_v) (interval arithmetic): the open geodesic ball B_M(w, ρ) holds
// no point and its sphere exactly σ. So σ is in Del_M(P), strictly (protected).
//
// COMPLETENESS (THE WINDOW). For x in M with Euclidean nearest point p, every point q of N_M(x)
// (the points of P nearest to x in d_M) satisfies |x - q| - delta_q <= d_M(x, q') <= d_M(x, p') <=
// Φ_{K_p}(|x - p| + delta_p), so |x - q| <= |x - p| + s_p with s_p = Φ_{K_p}(r + delta_p) - r +
// max delta (Φ_K(t) - t is nondecreasing), for x in Y_p with |x - p| < r. The restricted cell
// engine run with that window (rvd.hpp, THE WINDOW) covers M ∩ Vor(p) ∩ B(p, r) with kept boxes
// whose candidate sets hold N_M(x), each inside a restricted Voronoi vertex's simplex. With Del_RM's
// covering argument (check 11: every x of M within c < r of P), every N_M(x) lies in an m-simplex
// of Del_RM(P): every simplex of Del_M(P) is a face of one, and its m-simplices are among them.
#pragma once

#include <vector>

#include "certify/intrinsic/intrinsic.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::certify {

// What the general engine reads from the checks before it (none of it is trusted blindly: the
// restricted data are certified results, and the engine checks what it uses).
struct GeneralMetricInput {
  const exact::ImplicitSystem* system = nullptr;
  const std::vector<double>* distance_to_M = nullptr;  // check 1: per point, d(p, M) <= it
  const RestrictedDelaunay* restricted = nullptr;      // check 12, with check 11's covering argument
  RestrictedCellOptions cell;                          // check 12's cell options (selector, reach)
};

namespace detail {
IntrinsicDelaunay intrinsic_delaunay_general(const io::ManifoldSpec& spec, const io::PointSet& points,
                                             const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                             const GeneralMetricInput& input, int threads);
}  // namespace detail

}  // namespace delcert::certify
