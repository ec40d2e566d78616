// Two checks shared by the restricted-cell engines (certify/rvd.cpp: implicit charts;
// certify/detail/param_cell.cpp: rational charts). Neither depends on how the cell was searched.
#pragma once

#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/rvd.hpp"
#include "exact/interval.hpp"
#include "io/points.hpp"

namespace delcert::certify::detail {

// Direct check, independent of any chart, graph assumption or candidate set: every point of P
// outside `simplex` (sorted point indices, p among them) is strictly farther than p from every x
// in X (N intervals). A point q with d(x, q) <= d(x, p) has |q - c| <= d(q, x) + d(x, c) <=
// d(x, p) + d(x, c) (c the centre of X), so grid.ball(c, sup |x - p| + sup |x - c|) holds every
// such q; each sign d(x, q)^2 - d(x, p)^2 = |q - p|^2 - 2 (x - p).(q - p) is enclosed in interval
// arithmetic under upward rounding, from the exact doubles of the points.
bool others_strictly_farther(const io::PointSet& points, const PointGrid& grid, int p, const std::vector<int>& simplex,
                             const exact::Box& X);

// PURITY (rvd.hpp): is every face C of K = {p} + S (S point indices other than p, |S| <= m) with p
// in C and |C| <= m a face of a vertex simplex or of a face point found so far? On failure `face`
// is the first such C (sorted), the larger faces first.
bool faces_known(int p, int m, const std::vector<int>& S, const std::vector<RestrictedVoronoiVertex>& vertices,
                 const std::vector<RestrictedVoronoiVertex>& face_points, std::vector<int>& face);

// The largest certified lower bound of |x - p| over the report's vertices x (a lower bound of
// max_{x in M} d(x, P): each vertex is a point of M at that distance from its nearest points), 0
// when there are none.
double farthest_vertex(const RestrictedCellReport& report, const io::PointSet& points, int p);

// Ends a cell's report: vertices sorted by simplex (and enclosure), overlapping enclosures of one
// simplex kept once (a root on a face shared by two boxes is found twice; each holds a genuine
// vertex, and for Del_RM only the simplex matters), face points sorted, a cell with kept boxes but
// no vertex nor face point listed as possibly impure, and `reason` / `complete` set: complete
// when no box is undecided and the covering bound is below the ball's radius r.
void finish_report(RestrictedCellReport& report, int p, double r);

}  // namespace delcert::certify::detail
