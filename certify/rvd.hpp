// The certified restricted Voronoi diagram (RVD), one cell at a time (docs/design.md §3.8, issue 11).
// First increment: a library component, not yet part of the certificate.
//
// M = { F = 0 } (exact::ImplicitSystem, m = N - k), P the sample, p one of its points. The chart at
// p (exact::ChartEnclosure::at) writes x = p + T u + Nn h with T an exact basis of ker J_F(p) and
// Nn = J_F(p)^T (exact), so T^T Nn = 0 exactly: (u, h) are affine coordinates of R^N and
// |x - p|^2 = |T u|^2 + |Nn h|^2.
//
// THE BALL. options.graph_radius = r (ambient). Every statement below is about M ∩ B(p, r), B open.
// With g_T, g_N certified lower bounds of the smallest eigenvalues of T^T T and Nn^T Nn
// (Gershgorin or det / trace^(dim - 1), exact rationals), every x in B(p, r) has
// |u_a| <= |u| < r / sqrt(g_T) =: rho_u, so M ∩ B(p, r) lies over U0 = [-rho_u, rho_u]^m (U0 is
// derived from r, not a separate option), and over a box U its normal coordinates satisfy
// |h_l|^2 <= |Nn h|^2 / g_N < (r^2 - inf_U |T u|^2) / g_N: the slab H_ball(U).
//
// THE GRAPH ASSUMPTION (the caller's, not checked here): M ∩ B(p, r) meets every line
// p + T u + span(Nn) in at most one point (it is a graph over T_p). Lemma: this holds when
// r < tau / 2, tau the reach of M. Proof sketch: if x != y in M ∩ B(p, r) have the same u, then
// y - x is normal to T_p; by Federer (Curvature measures, 1959, Thm 4.18) y - x makes an angle at
// most arcsin(|y - x| / (2 tau)) <= arcsin(r / tau) with T_x, and by Boissonnat, Lieutier,
// Wintraecken (The reach, metric distortion, geodesic convexity and the variation of tangent
// spaces, JACT 2019, Thm 3) the angle between T_x and T_p is at most 2 arcsin(|x - p| / (2 tau))
// < 2 arcsin(r / (2 tau)); so pi/2 <= arcsin(r/tau) + 2 arcsin(r/(2 tau)), false for r <= tau/2
// (the right side is 58.96 degrees at r = tau/2). For the unit sphere the exact bound is r < sqrt 2.
// The chart's own Krawczyk uniqueness covers only its slab H: the assumption is what excludes other
// sheets of M over the same u inside the ball.
//
// WHAT IS CERTIFIED. Each box U of the subdivision of U0 gets a normal slab H_eff: the chart's
// enclosure H when exact::ChartEnclosure proves a unique point over every u in U in H AND that piece
// lies inside B(p, r) (then, by the graph assumption, it is THE point of M ∩ B(p, r) over u); else
// H_ball(U) (which holds every point of M ∩ B(p, r) over U, no assumption needed). Where the chart
// fails (e.g. beyond the fold of a sphere seen from p), H_ball(U) is first searched by halving
// (options.normal_levels): U is discarded when every piece is outside the ball, free of M (some
// chart equation G_i excludes 0 on it) or certainly closer to some candidate q than to p.
// Every other decision concerns U x H_eff:
//   * discarded: |x - p| >= r on all of it, or some q is certainly closer than p on all of it
//     (|q|^2 - |p|^2 - 2 x.(q - p) < 0, affine in (u, h), interval arithmetic under upward rounding);
//   * q dropped from the candidate set S(U) when it is certainly farther than p (same sign > 0);
//     children inherit S(U);
//   * S(p) initially: the points in the closed ball B(p, 2r): if x in B(p, r) has
//     d(x, q) <= d(x, p), then |q - p| <= d(q, x) + d(x, p) <= 2 d(x, p) < 2r;
//   * a box with |S(U)| <= m holds no restricted Voronoi vertex (a vertex needs m + 1 nearest
//     points, all of which are in S(U)); with |S(U)| = m + 1 and H_eff the chart's, Krawczyk on the
//     N x N system {G(u, h) = 0, d(x, q_i)^2 = d(x, p)^2 (i = 1..m)} in U x H proves one vertex
//     (unique_root) or none (no_root); otherwise the box is split (all sides halved).
// Hence, under the graph assumption: the kept boxes (not discarded) cover M ∩ Vor(p) ∩ B(p, r);
// covering_bound >= max |x - p| over M ∩ Vor(p) ∩ B(p, r); every restricted Voronoi vertex of p in
// B(p, r) is in `vertices` or inside an undecided box. If covering_bound < r, M ∩ Vor(p) has no
// point in the shell covering_bound <= |x - p| < r: the cell of p is the closed set found here,
// PROVIDED M ∩ Vor(p) does not also have a component beyond r (excluded globally by the
// open-and-closed argument of docs/design.md §3.8 over all points: the caller's job). If
// covering_bound >= r the report says "cell reaches the chart boundary" (complete = false).
// Each vertex found is certified WITHOUT the graph assumption: a point of M (the unique root of
// {G = 0, equidistance} in its enclosure, Krawczyk) equidistant from the m + 1 points of its
// simplex, and every other point of P is checked directly (grid ball around the enclosure, signs
// in interval arithmetic) to be strictly farther: the simplex is in Del_RM(P). A root that fails
// that check is not reported (its box is split on, and ends UNDECIDED at the depth limit).
//
// THE REACH LIMIT (options.reach = tau > 0). p is a double, near but in general not on M. The
// chart at u = 0 encloses the point p' = p + Nn h0 of M (Krawczyk: unique in its slab), so
// delta := |p - p'| is bounded. With J = J_F(p) and J' = J_F(p') (rows scaled like Nn's columns,
// which changes neither kernel nor row space), every unit t in ker J has |J' t| = |(J' - J) t|
// <= ||J' - J||_F and its component normal to T_{p'} M is J'^T (J' J'^T)^-1 J' t, of norm at most
// |J' t| / sigma_min(J'); by Weyl, sigma_min(J')^2 >= g_N - ||J' J'^T - J J^T||_F. So the largest
// principal angle theta between ker J and T_{p'} M has sin(theta) <= s, s computed in intervals
// over the enclosure of p'. Now let x != y in M ∩ B(p, r) with y - x in span(Nn) (normal to ker J).
// Then angle(y - x, T_{p'}) >= pi/2 - theta; but angle(y - x, T_x) <= arcsin(|y - x| / (2 tau))
// <= arcsin(r / tau) (Federer 1959, Thm 4.18: d(y - x, T_x) <= |y - x|^2 / (2 tau)) and
// angle(T_x, T_{p'}) <= 2 arcsin(|x - p'| / (2 tau)) <= 2 arcsin((r + delta) / (2 tau))
// (Boissonnat, Lieutier, Wintraecken 2019, the tangent-variation bound cited above), so
// pi/2 <= theta + arcsin(r/tau) + 2 arcsin((r + delta)/(2 tau)). With arcsin z <= (pi/2) z on
// [0, 1] (convexity) and theta <= (pi/2) sin(theta), this is impossible when
// (2 r + delta) / tau + s < 1, i.e. for r < r_lim := (tau (1 - s) - delta) / 2 (computed as a
// certified lower bound; for p on M, s = delta = 0 and r_lim = tau / 2).
//
// Deterministic: one point, sequential depth-first subdivision; no dependence on thread count.
#pragma once

#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "exact/interval.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"

namespace delcert::certify {

struct RestrictedCellOptions {
  double graph_radius = 0;      // r > 0 (see THE GRAPH ASSUMPTION)
  // A certified lower bound of the reach tau of M (0: none declared). When given, the graph
  // assumption is PROVEN (see THE REACH LIMIT): the radius used is min(graph_radius, the limit),
  // reported as RestrictedCellReport::graph_radius.
  double reach = 0;
  int max_depth = 24;           // subdivision depth limit (each level halves every side of U)
  long max_boxes = 200000;      // boxes visited per point; beyond it the rest is undecided
  // Kept boxes with more candidates than p are split further (second pass) while their widest
  // u-side exceeds this fraction of rho_u and their bound exceeds the distance from p to the
  // farthest vertex found (sharpens covering_bound near the cell's corners; work only).
  double covering_width = 1.0 / 128;
  // Kept boxes whose candidate set has a face in no vertex simplex found (PURITY) are split while
  // their widest u-side exceeds this fraction of rho_u; narrower, the face is listed as unresolved.
  double purity_width = 1.0 / 1024;
  // Where the chart fails, the normal slab H_ball(U) is searched by halving up to this many times.
  int normal_levels = 6;
};

struct RestrictedVoronoiVertex {
  std::vector<int> simplex;  // sorted point indices, p included (m + 1 of them)
  exact::Box x;              // N intervals: encloses the vertex, a point of M
};

struct UndecidedBox {
  std::vector<double> location;  // N coordinates: centre of the box's enclosure
  std::vector<int> candidates;   // sorted S(U), p included
  std::string reason;
};

struct RestrictedCellReport {
  int point = -1;
  std::vector<RestrictedVoronoiVertex> vertices;  // sorted by simplex, then by x
  // Certified upper bound of max |x - p| over the kept pieces (the covering contribution of p's
  // cell), and the centre of the box enclosure where it is attained.
  double covering_bound = 0;
  std::vector<double> covering_location;
  std::vector<UndecidedBox> undecided;
  // The radius r the statements hold for (options.graph_radius, capped by the reach limit when a
  // reach is given) and whether the graph property in B(p, r) was proven from the reach (else it
  // is the caller's assumption).
  double graph_radius = 0;
  bool graph_property_proven = false;
  // PURITY. Every kept box's candidate set K (p included) bounds the nearest-point sets of the
  // points of M in it. A face C of K containing p, with |C| <= m, that is not a face of a vertex
  // simplex found here may be a restricted Voronoi face of dimension > 0 without a vertex (then
  // Del_RM is not pure): such boxes are refined in the second pass, and the ones still in doubt at
  // the finest purity width are listed here, once per face (`candidates` = the face C). Empty: every simplex of Del_RM
  // containing p is a face of an m-simplex in `vertices` (when complete).
  std::vector<UndecidedBox> unresolved_faces;
  bool complete = false;  // no undecided box, covering_bound < graph_radius
  std::string reason;     // why not complete ("" when complete)
  // Counters.
  long boxes = 0, kept = 0, discarded = 0, krawczyk_calls = 0, krawczyk_failures = 0, chart_failures = 0;
  int max_depth = 0;
};

// Throws std::invalid_argument on a non-positive graph_radius, std::domain_error when J_F(p) is
// rank deficient or Gershgorin cannot bound T^T T or Nn^T Nn away from 0.
RestrictedCellReport analyse_restricted_cell(const exact::ImplicitSystem& system, const io::PointSet& points,
                                             const detail::PointGrid& grid, int p, const RestrictedCellOptions& options);

}  // namespace delcert::certify
