// The certified restricted Voronoi diagram (RVD), one cell at a time (docs/design.md §3.8, issue 11).
// certify/restricted.hpp assembles the cells into Del_RM(P) and the covering radius.
//
// M = { F = 0 } (exact::ImplicitSystem, m = N - k), P the sample, p one of its points. The chart at
// p (exact::ChartEnclosure::at) writes x = p + T u + Nn h with T an exact basis of ker J_F(p) and
// Nn = J_F(p)^T (exact), so T^T Nn = 0 exactly: (u, h) are affine coordinates of R^N and
// |x - p|^2 = |T u|^2 + |Nn h|^2.
//
// THE BALL. options.graph_radius = r (ambient). Every statement below is about M ∩ B(p, r), B open.
// With g_T, g_N certified lower bounds of the smallest eigenvalues of T^T T and Nn^T Nn
// (exact::ChartEnclosure::gram_bounds), every x in B(p, r) has
// |u_a| <= |u| < r / sqrt(g_T) =: rho_u, so M ∩ B(p, r) lies over U0 = [-rho_u, rho_u]^m (U0 is
// derived from r, not a separate option), and over a box U its normal coordinates satisfy
// |h_l|^2 <= |Nn h|^2 / g_N < (r^2 - inf_U |T u|^2) / g_N: the slab H_ball(U).
//
// NO GRAPH ASSUMPTION (by default). The chart's Krawczyk uniqueness covers only its slab H: another
// sheet of M over the same u (the far side of a sphere, the other side of a thin neck) may lie in
// the ball outside H. It is not assumed away: the subdivision excludes it, box by box, as follows
// (or, with options.reach, by THE GRAPH LEMMA of rvd.cpp, whose hypothesis is that reach).
// With a selector, M = {F = 0, s > 0}; the statements below hold for all of {F = 0} ⊇ M, except
// that a vertex is reported only where s > 0 is proven, and a slab from the graph lemma holds the
// points of M only.
//
// THE SLAB INVARIANT. Each box U of the subdivision of U0 carries a normal slab H_eff(U) and a
// candidate set S(U) such that every point x of M ∩ B(p, r) ∩ Vor(p) with parameter u in U has its
// normal coordinate in H_eff(U), and every point of P outside S(U) + {p} is strictly farther than
// p from every point of Vor(p) ∩ (U x H_eff(U)) (Vor(p) the ambient Voronoi cell; both statements
// pass to sub-boxes). At the root, H_eff = H_ball(U0) and S = the points of the
// closed ball B(p, 2r) (if x in B(p, r) has d(x, q) <= d(x, p) then |q - p| <= 2 d(x, p) < 2r).
// For a child box U, let Hpar = H_eff(parent) ∩ H_ball(U) (still holds every such x: U lies in
// the parent's box). When exact::ChartEnclosure proves a unique point of M over every u in U in a
// slab Hc, H_eff(U) = Hc ∩ Hpar PROVIDED U x (Hpar \ Hc) is excluded (2k boxes, each tested with
// the parent's candidates, valid there, less those already certainly farther than p on all of
// U x Hpar: such a q is certainly farther on every part of it and could exclude nothing there,
// and any point of P certainly closer excludes, whatever list it comes from); else H_eff(U) = Hpar. Excluded means: outside the ball,
// free of M (some chart equation G_i excludes 0) or certainly closer to some candidate q than to
// p, tested on the box and, failing that, on halves along the widest normal side
// (options.normal_levels times). Then q is dropped from S when certainly farther than p on
// U x H_eff (sign of the affine form |q|^2 - |p|^2 - 2 x.(q - p), interval arithmetic under
// upward rounding); U is discarded when U x H_eff is excluded (outside the ball, or a candidate
// certainly closer; with a slab that is not the chart's, also after the normal halving). COMBINED
// SIGNS (rvd.cpp), with candidates A, B_i and t_i >= 0 (one B, or m of them): U is discarded when
// s_A + sum t_i s_Bi < 0 on U x H_eff, and A is dropped when s_A - sum t_i s_Bi > 0 there (A
// strictly farther than p wherever no B_i is closer).
// A child box whose parent's slab is the chart's starts from it: Krawczyk on U x Hpar contracts
// it to the child's own slab (no new guess, no difference test: Hpar already holds the invariant).
//   * a box with |S(U)| <= m holds no restricted Voronoi vertex (a vertex needs m + 1 nearest
//     points, all of which are in S(U) + {p}); with |S(U)| = m + 1 and the chart's slab, Krawczyk
//     on the N x N system {G(u, h) = 0, d(x, q_i)^2 = d(x, p)^2 (i = 1..m)} in U x H_eff proves
//     one vertex (unique_root) or none (no_root); otherwise the box is split (all sides halved).
// Hence: the kept boxes (not discarded) cover M ∩ Vor(p) ∩ B(p, r); covering_bound >= max |x - p|
// over M ∩ Vor(p) ∩ B(p, r); every restricted Voronoi vertex of p in B(p, r) is in `vertices` or
// inside an undecided box. If covering_bound < r, M ∩ Vor(p) has no point in the shell
// covering_bound <= |x - p| < r: the cell of p is the closed set found here, PROVIDED M ∩ Vor(p)
// does not also have a component beyond r (excluded globally by the open-and-closed argument of
// certify/restricted.hpp over all points: the caller's job). If covering_bound >= r the report
// says "cell reaches the chart boundary" (complete = false).
// Each vertex found is certified independently of the subdivision: a point of M (the unique root
// of {G = 0, equidistance} in its enclosure, Krawczyk) equidistant from the m + 1 points of its
// simplex, and every other point of P is checked directly (grid ball around the enclosure, signs
// in interval arithmetic) to be strictly farther: the simplex is in Del_RM(P). A root that fails
// that check is not reported (its box is split on, and ends UNDECIDED at the depth limit).
//
// Deterministic: one point, sequential depth-first subdivision; no dependence on thread count.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "exact/chart.hpp"
#include "exact/interval.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

struct RestrictedCellOptions {
  double graph_radius = 0;      // r > 0: the cell is analysed in the open ball B(p, r)
  int max_depth = 24;           // subdivision depth limit (each level halves every side of U)
  long max_boxes = 20000;       // boxes visited per point; beyond it the rest is undecided
  // Kept boxes with more candidates than p are split further (second pass) while their widest
  // u-side exceeds this fraction of rho_u and their bound exceeds the distance from p to the
  // farthest vertex found (sharpens covering_bound near the cell's corners; work only).
  double covering_width = 1.0 / 128;
  // Kept boxes whose candidate set has a face in no vertex simplex found (PURITY) are split while
  // their widest u-side exceeds this fraction of rho_u; narrower, the face is listed as unresolved.
  double purity_width = 0x1p-20;
  // Where the chart fails, the normal slab H_ball(U) is searched by halving up to this many times.
  int normal_levels = 6;
  // COMBINED SIGNS are tried on boxes with at most this many candidates besides p (their cost
  // grows with its square; larger boxes rarely gain). Work only.
  int combined_signs_max = 8;
  // THE GRAPH LEMMA (rvd.cpp): reach > 0 is a lower bound of the reach of M, TAKEN AS AN ASSUMPTION
  // (the spec's declared reach); then a chart slab proved unique needs no difference test where
  // the lemma's inequality holds. 0: nothing is assumed. selector: the s of M = {F = 0, s > 0}.
  double reach = 0;
  const exact::Polynomial* selector = nullptr;
  // A shape verified by certify/intrinsic.hpp (verify_declared_shape): a round sphere (N = m + 1)
  // or SO(3) is then analysed in a RATIONAL CHART (certify/detail/param_cell.hpp) wherever one
  // covers M ∩ B(p, r); nothing is assumed (reach, selector unused there). nullptr: implicit charts.
  const io::ShapeSpec* shape = nullptr;
  // GEODESIC (Del_M, certify/intrinsic_product.cpp): `shape` a product of round spheres, and the
  // cell is p's Voronoi cell for the geodesic distance d_M(x, pi(q)) (param_cell.cpp, GEODESIC),
  // analysed in the geodesic ball B_M(pi(p), r); never the implicit engine. projection_slack: an
  // upper bound of |q - pi(q)| over all points.
  bool geodesic = false;
  double projection_slack = 0;
  // THE WINDOW (Del_M on a general M, certify/intrinsic/general.cpp; implicit charts only). window
  // > 0: a candidate q leaves S(U) only when s_q > window on the box (s_q = |x - q|^2 - |x - p|^2):
  // every point of P outside S(U) + {p} is then farther than p by more than the window, and COMBINED
  // SIGNS (whose drops are not widened) are off. A kept box must moreover (a) have its chart slab
  // proved unique and window_graph(U, H) true (the caller's proof that the points of M in U x H lie
  // on its graph Y_p) and (b) have {p} + S(U) inside a vertex simplex found here; otherwise it is
  // split, and at the purity width it is an undecided box ("window: ..."), which makes the cell
  // incomplete. The vertices and the covering bound mean what they mean without it.
  double window = 0;
  std::function<bool(const exact::Box& U, const exact::Box& H)> window_graph;
  // The chart to analyse the cell in (implicit charts only), instead of ChartEnclosure::at: any chart
  // at p whose T and Nn are exactly orthogonal (the statements above need only that and the Gram
  // bounds); the window's boxes are then in the caller's coordinates. nullptr: the standard chart.
  const exact::ChartEnclosure* chart = nullptr;
};

struct RestrictedVoronoiVertex {
  std::vector<int> simplex;  // sorted point indices, p included (m + 1 of them; at most m for a face point)
  exact::Box x;              // N intervals: encloses the vertex (or face point), a point of M
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
  double graph_radius = 0;  // the radius r the statements hold for (options.graph_radius)
  // PURITY. Every kept box's candidate set K (p included) bounds the nearest-point sets of the
  // points of M in it. A face C of K containing p, with |C| <= m, that is not a face of a vertex
  // simplex found here may be a restricted Voronoi face of dimension > 0 without a vertex (then
  // Del_RM is not pure): such boxes are refined in the second pass, and the ones still in doubt at
  // the finest purity width are listed here, once per face (`candidates` = the face C). Before a
  // box is refined for a face C, a FACE POINT is sought (rvd.cpp): a certified point of M whose
  // nearest points in P are exactly C, which puts C in Del_RM(P) with no assumption; C is then
  // known, as is every face of it. Empty: every simplex of Del_RM containing p is a face of an
  // m-simplex in `vertices` or of a simplex in `face_points` (when complete).
  std::vector<UndecidedBox> unresolved_faces;
  // Simplices C (p in C, |C| <= m, no face of a vertex simplex found here) each with an enclosure
  // of a point of M whose nearest points in P are exactly C, sorted by simplex. With the cell
  // complete (and the covering argument of restricted.hpp) no m-simplex of Del_RM(P) contains C:
  // Del_RM(P) is not pure.
  std::vector<RestrictedVoronoiVertex> face_points;
  bool complete = false;  // no undecided box, covering_bound < graph_radius
  std::string reason;     // why not complete ("" when complete)
  // Counters.
  long boxes = 0, kept = 0, discarded = 0, krawczyk_calls = 0, krawczyk_failures = 0, chart_failures = 0;
  long reach_slabs = 0;  // chart slabs taken by the graph lemma (the reach assumption was used)
  bool rational_chart = false;  // analysed in a rational chart (RestrictedCellOptions::shape)
  int max_depth = 0;
};

// The analysis in its two passes, for a caller that refines the covering bound of many cells
// against one shared target (certify/restricted.cpp): first_pass() subdivides until every box is
// resolved and returns the largest distance from p to a restricted Voronoi vertex found (a lower
// bound of max_{x in M} d(x, P); 0 when none); second_pass(target) refines the kept boxes for the
// covering bound and purity, not refining a box whose bound is at most max(target, that distance).
// The target only decides work: every kept box contributes its own certified bound, whatever the
// target. Call first_pass() once, then second_pass() once.
// Throws as analyse_restricted_cell (below).
class RestrictedCell {
 public:
  RestrictedCell(const exact::ImplicitSystem& system, const io::PointSet& points, const detail::PointGrid& grid,
                 int p, const RestrictedCellOptions& options);
  ~RestrictedCell();
  RestrictedCell(RestrictedCell&&) noexcept;
  RestrictedCell& operator=(RestrictedCell&&) noexcept;
  double first_pass();
  RestrictedCellReport second_pass(double covering_target);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Both passes with no shared target (the cell's own vertices bound the refinement).
// Throws std::invalid_argument on a non-positive graph_radius, std::domain_error when J_F(p) is
// rank deficient or T^T T or Nn^T Nn cannot be bounded away from 0.
RestrictedCellReport analyse_restricted_cell(const exact::ImplicitSystem& system, const io::PointSet& points,
                                             const detail::PointGrid& grid, int p, const RestrictedCellOptions& options);

}  // namespace delcert::certify
