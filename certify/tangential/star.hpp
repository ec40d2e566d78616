// Checks 3, 6 and the eps claim at one sample point p: the tangential star of p, exactly.
//
// Setting (docs/design.md §2, §3.2). T_p = p + ker J_F(p) at p's exact coordinates, with the exact
// rational basis U of exact/tangent_space.hpp. A cell s = {p, v1..vm} has a centre c in T_p at
// equal ambient distance R = R_p(s) from its vertices; s is in star(p) iff its ball B(c, R)
// contains no sample point (the regular triangulation of the weighted projections, exactly).
// Every sign is decided by exact/'s filtered predicates (interval filter, then exact); the
// certifier's own interval code here only encloses values for reporting (margins, radii) and
// bounds the search radius.
//
// Verifying a claimed star (what "the claimed star is the true star" means):
//   (a) every claimed cell has a strictly empty ball: sign(|c - q|^2 - R^2) > 0 for every
//       sample point q outside the cell. Sufficiency of the tested set: it contains every point
//       within distance r of p (detail/grid.hpp), and r >= 2R for every cell, while a point inside
//       B(c, R) is at distance < |q - c| + |c - p| < 2R from p.
//   (b) the link of p closes: every ridge {p} + (m-1 link vertices) lies in exactly two cells.
// (a) proves each cell is a cell of the regular triangulation (so the cells have disjoint
// interiors); the link of an interior vertex of a triangulation is strongly connected across
// ridges, so by (b) the claimed cells are all of star(p). When (a) fails, orientation tests (the
// two cells at a ridge on opposite sides; a generic ray from p in exactly one cell) diagnose how
// the claimed star fails to tile a neighbourhood of p.
//
// Computing a star (audit mode, or to name what is missing or extra): gift-wrapping across
// ridges, first in double precision, then verified by (a) + (b) exactly; if the verification
// fails, gift-wrapping again with exact predicates. The first cell comes from a small linear
// program (the power cell of p is {y : 2 b(q).y <= s(q)}; one of its vertices is a cell),
// solved in double and, if that cell fails verification, in exact rationals.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"

namespace delcert::certify {

namespace detail {
class PointGrid;
}  // namespace detail

using Simplex = std::vector<int>;  // sorted global vertex indices

struct StarSettings {
  const io::PointSet* points = nullptr;
  const exact::ImplicitSystem* system = nullptr;
  const detail::PointGrid* grid = nullptr;
  int m = 0;
  std::optional<mpq_class> power_protection;  // claimed delta-check^2 (a squared distance)
  std::optional<mpq_class> eps;               // claimed eps: every R_p(s) < eps
  // Claimed eps(p) per point (claims v3, star_radius_per_point): every R_p(s) < eps(p) at p.
  // Exclusive with eps; null when absent.
  const std::vector<mpq_class>* eps_per_point = nullptr;
};

// One cell {p, ...} tested at p (its fields ordered without padding; certify.cpp keeps a star's cells only for witnesses).
struct CellReport {
  Simplex simplex;
  exact::Interval conflict_power{};        // enclosure of |c - q|^2 - R^2 (< 0) for `conflict`
  exact::Interval radius2{};               // enclosure of R_p(s)^2
  exact::Interval margin{};                // enclosure of min_{q not in s} |c - q|^2 - R^2
  exact::Interval protection_power{};      // enclosure of |c - q|^2 - R^2 for `protection_point`
  int conflict = -1;                       // a point strictly inside B(c, R), if any
  int tie = -1;                            // a point exactly on the sphere, if any
  int margin_point = -1;                   // the q attaining the smallest lower bound
  int protection_point = -1;               // a q with |c - q|^2 - R^2 <= claim, if any
  int protection_sign = 1;                 // its exact sign of |c - q|^2 - R^2 - claim
  int eps_sign = -1;                       // exact sign(R^2 - eps^2) (eps(p)^2 per point; when claimed)
  bool degenerate = false;                 // projection to T_p affinely dependent (no centre)
  bool empty() const { return !degenerate && conflict < 0 && tie < 0; }
};

struct StarReport {
  int p = -1;
  enum class State { proven, degenerate, incomplete };
  State state = State::incomplete;  // proven: star(p) known exactly; degenerate: exact ties
  std::string reason;               // why not proven
  bool claimed_verified = false;    // the claimed star at p is proven to be star(p)
  std::vector<CellReport> star;     // the cells of star(p) (best effort when not proven)
  std::vector<CellReport> claimed;  // each claimed m-simplex at p, tested at p (empty when claimed_verified)
  std::string link_problem;         // why the claimed star is not a closed star, if so
  double search_radius = 0;         // every point within this distance of p was tested
  // Enclosures of the exact tangent basis U (N x m) and of G = U^T U (m x m) at p, for check 7 on
  // the same rank (not sent between MPI ranks; without them check 7 recomputes U).
  std::vector<exact::Interval> basis_enclosure, gram_enclosure;
  bool searched_all = false;        // every sample point was tested
  // An MPI rank whose part plus halo (detail/grid.hpp, PointGrid::covers) did not hold the ball of
  // this radius around p, which the search needed: the star is then not determined (state
  // incomplete). 0 otherwise, and always in one process.
  double halo_needed = 0;
  // What certify.cpp keeps of `star` when it drops it (keep_for_checks): the simplices, m + 1 vertices each, and extremes.
  std::vector<int> vertices;
  int cells = 0, min_margin_cell = -1, min_margin_point = -1, max_radius_cell = -1;
  exact::Interval min_margin{INFINITY, INFINITY}, max_radius2{-INFINITY, -INFINITY};
  // Cell i's simplex, read in place (no allocation: check 4 compares it for every simplex at every vertex).
  std::span<const int> simplex(int i) const { const std::size_t k = vertices.size() / cells; return {vertices.data() + i * k, k}; }
  std::vector<Simplex> simplices() const {
    std::vector<Simplex> s;
    s.reserve(cells);
    for (int i = 0; i < cells; ++i) s.emplace_back(simplex(i).begin(), simplex(i).end());
    return s;
  }
};

// `claimed`: the m-simplices of the given complex that contain p (null in audit mode).
StarReport analyse_star(const StarSettings& settings, int p, const std::vector<Simplex>* claimed,
                        exact::FilterContext& ctx);

// Tests one m-simplex s (containing p) as a cell at p: conflict, tie, margin, claims.
CellReport test_cell(const StarSettings& settings, int p, const Simplex& s, exact::FilterContext& ctx);

// Check 7 at p: which cells of star(p) are secure (paper Definition 3.1) in the local Euclidean
// metric of p (orthogonal projection onto T_p): the projected simplex has a Delaunay ball of
// radius r < eps, delta-protected (|c' - q'| > r + delta for every projected point q' of the
// points within 5 eps of p), thickness >= upsilon0 and shortest edge >= mu0 eps.
struct SecureParams {
  mpq_class eps, delta, upsilon0, shortest;  // shortest = mu0 * eps
  // Enclosures of eps^2, delta, upsilon0^2, shortest^2 (filled by prepare()).
  exact::Interval eps2_enclosure, delta_enclosure, upsilon0_2_enclosure, shortest2_enclosure;
  void prepare();
};
struct SecureReport {
  long secure = 0, insecure = 0;
  long undecided = 0;        // not evaluated: more than 50 000 points within 5 eps of p
  long exact_fallbacks = 0;  // cells decided in exact rationals after the interval filter
  double halo_needed = 0;    // > 0: an MPI rank's halo did not hold W (radius halo_needed); the cells are `undecided`
  std::vector<std::pair<Simplex, std::string>> failures;  // (simplex, first failed condition), capped
};
// `report`: the star analysis of p, if available (its enclosures of the tangent basis are reused).
SecureReport analyse_secure(const StarSettings& settings, int p, const std::vector<Simplex>& star,
                            const SecureParams& params, exact::FilterContext& ctx, const StarReport* report = nullptr);

}  // namespace delcert::certify
