// COVERAGE OF ALL OF M (issue 39): the last step of the covering argument of certify/restricted.hpp,
// which by itself shows only that every connected component of M holding a point x with
// d(x, P) <= c lies within c of P. Components with no sample point near them are what this file
// excludes, by proof, never by the spec's `expected` Betti numbers (they are what check 8 compares
// the complex with: the user's expectation, not a premise).
//
// Given: every restricted cell complete, c = max_p covering_bound_p < r = min_p r_p (the cells'
// radii), so that (THE COVERING ARGUMENT) for every x in M:  d(x, P) < r  implies  d(x, P) <= c.
// (x's nearest point q has d(x, q) < r <= r_q, so x lies in M ∩ Vor(q) ∩ B(q, r_q), which q's kept
// boxes cover, each within covering_bound_q <= c of q.)
//
// ARGUMENT 1, CONNECTED SHAPE. When the spec's equations are exactly those of a declared shape
// (certify/intrinsic.hpp verify_declared_shape: a round sphere, a product of round spheres or
// circles, SO(3) with the determinant as selector), M is connected. A restricted Voronoi vertex
// found is a point of M with d <= c, so d(., P) maps M into [0, c] ∪ [r, inf), two disjoint closed
// sets, and the connected image of M meets the first: d(x, P) <= c on all of M.
//
// ARGUMENT 2, THE BOX SEARCH. The spec's bounding box B is declared to contain M (a trusted input
// like the reach, stated in the certificate). B is subdivided, bisecting the widest side; a box X
// is DONE when
//   (a) some equation's interval enclosure F_i(X) excludes 0 (the natural extension, intersected
//       with the mean value form F_i(x0) + grad F_i(X) . (X - x0) around the centre x0), or the
//       selector s of M = {F = 0, s > 0} has s(X) <= 0: X holds no point of M; or
//   (b) X lies in the open ball B(p, r) of one sample point p: the distance from p to the farthest
//       corner of X, computed under upward rounding, is below r rounded down. Then every x in
//       M ∩ X has d(x, P) <= |x - p| < r, hence d(x, P) <= c by the covering argument.
// (Any p works; the grid's nearest point to X's centre is tried.) If every leaf is DONE, every
// point of M ∩ B is within c of P, and with M ⊂ B, P is a c-sample of M.
// A box that is neither when its widest side reaches the size limit w (chosen so that its diagonal
// is at most (r - c) / 8: a box meeting M near a point within c of P passes (b) long before) is
// searched for a point of M far from P: the m coordinates where the Jacobian at its centre is worst
// conditioned (column-pivoted QR) are fixed at the centre, and Krawczyk on the k = N - m equations
// in the other k coordinates (a square system, in a box three times X's extent there) proves a
// unique point x* of {F = 0} in a box X*; with a selector s(X*) > 0 is required (x* in M). A
// certified lower bound of d(x*, P) over ALL of P comes from the grid: D = min over the points of
// a non-empty ball query of their distance upper bounds to X*'s centre x~; every point of P
// outside B(x~, D + 2h) (h >= the half-diagonal of X*) is farther from x* than that nearest one,
// so the minimum of the exact lower bounds (rational gaps, MPFR square root) over the points of
// grid.ball(x~, D + 2h) bounds d(x*, P) from below. When that bound exceeds c, c is not a covering
// radius of M (a FAR POINT, the witness); else the box is split on to w / 4 and then UNDECIDED.
// The search stops at the first far point whose bound reaches `target` (the covering claim, or
// just above c without one), at the box budget, or when every box is done.
//
// Deterministic: sequential depth-first subdivision; the result does not depend on threads.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/interval.hpp"
#include "exact/polynomial.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"

namespace delcert::certify {

struct CoverageOptions {
  long max_boxes = 4000000;  // boxes of the search; beyond it the search is UNDECIDED
};

struct FarPoint {
  exact::Box x;               // N intervals holding exactly one point x* of M (Krawczyk)
  double distance_lower = 0;  // certified: d(x*, P) >= this
  int nearest = -1;           // a point of P attaining the bound's minimum
};

struct CoverageSearch {
  bool covered = false;                    // every point of M ∩ B within c of P
  std::optional<FarPoint> far;             // the far point with the largest bound found (> c)
  std::vector<std::vector<double>> undecided;  // centres of undecided boxes (the first few)
  std::string reason;                      // why not covered ("" when covered)
  long boxes = 0, excluded = 0, inside_balls = 0, krawczyk_calls = 0, undecided_boxes = 0;
  double size_limit = 0;                   // w
};

// The box search over `box` (N intervals; the declared bounding box), with c < r as above and
// `selector` the s of M = {F = 0, s > 0} or nullptr. Stops at a far point with bound >= target.
CoverageSearch search_coverage(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                               const io::PointSet& points, const detail::PointGrid& grid, const exact::Box& box,
                               double c, double r, double target, const CoverageOptions& options = {});

struct CoverageProof {
  bool proven = false;       // every point of M is within R.covering of P
  std::string argument;      // what is proven, and from what (the certificate's assumptions.components)
  std::string reason;        // why not proven ("" when proven)
  std::optional<CoverageSearch> search;  // when the box search ran
};

// Argument 1 when `connected_shape` names a verified shape and R holds a vertex, else argument 2
// when the spec declares a bounding box, else not proven. Nothing when R.covering_certified is
// false (the covering argument itself does not hold). `target`: as search_coverage.
CoverageProof prove_coverage(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                             const std::vector<std::pair<double, double>>& bounding_box,
                             const std::string& connected_shape, const io::PointSet& points,
                             const detail::PointGrid& grid, const RestrictedDelaunay& R, double target,
                             const CoverageOptions& options = {});

}  // namespace delcert::certify
