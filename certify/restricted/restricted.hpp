// The restricted Delaunay complex Del_RM(P) and the certified covering radius, assembled from the
// restricted Voronoi cells of every point (certify/rvd.hpp; docs/design.md §3.8). Read by checks
// 11 (covering), 12 (restricted_delaunay) and 13 (tangential_equals_restricted).
//
// THE RADIUS. Every cell is analysed in a ball B(p, r_p) (no reach and no graph property is
// assumed: rvd.hpp). The first radius is r_p = 2 max(d_p, median of the d_q), d_p the distance from
// p to its nearest other point (a cell rarely reaches farther), at most 0.8 reach with THE GRAPH
// LEMMA of rvd.cpp (which holds out to nearly the reach); points whose cell reaches its
// ball's boundary, or
// whose radius is not above the largest covering bound c found so far, are analysed again with a
// larger radius, and those that ran out of their box budget nearly done with 4 times the budget,
// twice at most (at most `rounds` times in all).
//
// THE COVERING ARGUMENT (open and closed). Let c = max_p covering_bound_p and suppose every cell
// is complete (no undecided box) and c < r_p for every p. Let
// f(x) = d(x, P) on M (continuous). For x in M with a nearest point q, either f(x) >= r_q or x is
// in M ∩ Vor(q) ∩ B(q, r_q), which the kept boxes of q cover, so f(x) <= c_q <= c. Hence f takes
// no value in (c, min_p r_p), a non-empty interval, and on each connected component of M the
// image of f is an interval: it lies in [0, c] as soon as the component has one point with
// f <= c. Every restricted Voronoi vertex found is such a point. So if every component of M holds
// a restricted Voronoi vertex, P is a c-sample of M: d(x, P) <= c < eps' for every x in M. That
// no component of M is left out is not assumed: certify/coverage.hpp proves it (a verified
// connected shape, or a search of the spec's bounding box), and run_certify clears
// covering_certified when it cannot; the spec's expected Betti numbers are never a premise.
// Under the same conditions, every restricted Voronoi vertex of P lies within c of its points,
// hence inside the analysed balls: the vertices found are ALL of them, and the purity test of
// rvd.hpp covers every restricted Voronoi face.
//
// COVERING TARGET (work only). A kept box whose certified bound is at most some distance d(x, P)
// with x in M already known (a restricted Voronoi vertex found anywhere) cannot raise c above that
// known value much, so refining it only tightens a bound that is not the maximum. The cells are
// analysed in chunks of a fixed size: first passes, then second passes refined only above the
// largest vertex distance found so far (rvd.hpp, RestrictedCell). Every kept box still adds its
// own certified bound: the target changes how tight c is, never whether it is an upper bound; and
// the chunks do not depend on the thread count, so neither does c.
//
// CROSS-CHECK. A vertex found at p (certified without any assumption) must also be found at each
// other point of its simplex whose cell is complete (it is within c < r of that point too); a miss
// would mean the program contradicts itself, and makes the result incomplete.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/rvd.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"

namespace delcert::certify {

struct RestrictedDelaunayOptions {
  int threads = 1;
  int rounds = 4;    // radius increases after the first analysis
  RestrictedCellOptions cell;  // graph_radius is set per round
  // Work only: the complex under test. Every ball must reach beyond the covering bound (THE COVERING
  // ARGUMENT), about the largest circumradius of Del_RM's simplices (within 4% on the built-ins'
  // outputs): first radii are at most 5/4 of it. Too small a ball is only analysed again, larger.
  const std::vector<std::vector<int>>* expected = nullptr;
  // Work only: a certified upper bound of each point's distance to M (check 1's, SanityResult), or
  // nullptr. M ∩ Vor(p) lies at least d(p, M) from p, so a ball of radius below it finds nothing
  // there: a point off M by more than a 64th of its first radius has d_p added to that radius.
  const std::vector<double>* distance_to_M = nullptr;
  std::function<void(std::size_t, std::size_t)> progress;  // (cells done, cells of the round); for a progress line
};

struct RestrictedSimplex {
  std::vector<int> simplex;        // sorted, m + 1 points (fewer in lower_faces)
  int found_at = -1;               // the point whose cell certified it
  RestrictedVoronoiVertex vertex;  // its certified vertex (an enclosure of a point of M) or face point
  double distance_lower = 0;       // certified lower bound of d(vertex, P) = |vertex - found_at|
};

struct CrossCheckFailure {
  std::vector<int> simplex;
  int found_at = -1, missed_at = -1;
};

struct RestrictedDelaunay {
  std::vector<RestrictedCellReport> cells;  // per point
  std::vector<RestrictedSimplex> simplices; // the m-simplices found, sorted by simplex, unique
  // Simplices of dimension < m proven in Del_RM(P) by a face point (rvd.hpp), each a face of no
  // simplex in `simplices` and of no larger one here, sorted. With covering_certified, Del_RM(P)
  // is not pure: every m-simplex is in `simplices`.
  std::vector<RestrictedSimplex> lower_faces;
  std::vector<CrossCheckFailure> cross_check_failures;
  std::vector<int> incomplete_points;       // cells not complete (see RestrictedCellReport::reason)
  double covering = 0;                      // c = max_p covering_bound_p (an upper bound where complete)
  int covering_point = -1;                  // the p attaining it
  double min_radius = 0;                    // min_p r_p
  double vertex_distance_lower = 0;         // max over `simplices` of distance_lower: <= max_{x in M} d(x, P)
  int rounds_used = 0;
  // The covering argument holds (see above): every cell complete and proven, c < min_p r_p, no
  // cross-check failure, and an ANCHOR: some point of M with d(x, P) <= c is known (a restricted
  // Voronoi vertex or a face point found). Without one, f = d(., P) may stay above min_p r_p on all
  // of M (every point of P farther from M than its ball reaches: every cell is then complete and
  // empty, c = 0), and nothing is known about Del_RM(P). Then `simplices` are all the m-simplices
  // of Del_RM(P) on the components of M that hold an anchor; run_certify also requires coverage of
  // all of M (certify/coverage.hpp), and then `simplices` are all the m-simplices of Del_RM(P).
  bool covering_certified = false;
  std::string reason;                       // why not, when not
  long boxes = 0, krawczyk_calls = 0, krawczyk_failures = 0, chart_failures = 0, reach_slabs = 0;
  long rational_chart_cells = 0;  // cells analysed in a rational chart (certify/detail/param_cell.hpp)
};

RestrictedDelaunay compute_restricted_delaunay(const exact::ImplicitSystem& system, const io::PointSet& points,
                                               const detail::PointGrid& grid, const RestrictedDelaunayOptions& options);

}  // namespace delcert::certify
