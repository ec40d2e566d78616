#include "certify/restricted/restricted.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "certify/certificate.hpp"
#include "certify/detail/parallel.hpp"
#include "certify/restricted/sphere_hull.hpp"
#include "exact/interval_arithmetic.hpp"

namespace delcert::certify {

namespace {

// Cells analysed together before the covering target is raised. Their first passes are held in
// memory until their second passes: about 0.4 MB per cell at m = 3 (measured on S^3), so 256
// cells keep the peak near 100 MB whatever the number of points.
constexpr std::size_t kChunk = 256;

// The distance from p to its nearest other point (floating point: it only picks a radius).
double nearest_distance(const io::PointSet& P, const detail::PointGrid& grid, int p) {
  const auto pp = P.point(p);
  for (double t = grid.spacing(); std::isfinite(t); t *= 2) {
    double best = INFINITY;
    for (int q : grid.ball(pp, t)) {
      if (q == p) continue;
      double scale = 0, d = 0;  // scaled, so that neither 1e-300 nor 1e300 coordinates under/overflow
      for (std::size_t v = 0; v < pp.size(); ++v) scale = std::max(scale, std::abs(P.point(q)[v] - pp[v]));
      for (std::size_t v = 0; v < pp.size(); ++v) d += std::pow((P.point(q)[v] - pp[v]) / scale, 2);
      best = std::min(best, scale * std::sqrt(d));
    }
    if (best <= t) return best;
    if (t >= grid.diameter()) return best;
  }
  return grid.diameter();
}

// The largest circumradius of the m-simplices (m + 1 vertices) of `simplices`; 0 when none.
double largest_circumradius(const io::PointSet& P, const std::vector<std::vector<int>>& simplices, int m) {
  exact::UpwardRounding up;
  double largest = 0;
  for (const auto& s : simplices) {
    if (static_cast<int>(s.size()) != m + 1 || m < 1 ||
        std::any_of(s.begin(), s.end(), [&](int v) { return v < 0 || static_cast<std::size_t>(v) >= P.size(); }))
      continue;
    std::vector<std::vector<exact::IntervalNumber>> a;
    for (int v : s) a.emplace_back(P.point(v).begin(), P.point(v).end());
    const double R = detail::circumradius_upper(a);
    if (std::isfinite(R)) largest = std::max(largest, R);
  }
  return largest;
}

}  // namespace

RestrictedDelaunay compute_restricted_delaunay(const exact::ImplicitSystem& system, const io::PointSet& P,
                                               const detail::PointGrid& grid, const RestrictedDelaunayOptions& o) {
  const int n = static_cast<int>(P.size());
  RestrictedDelaunay R;
  R.cells.resize(n);
  // The first radii: r_p = 2 max(own nearest-neighbour distance, the median one) (the median
  // keeps a point of a close pair from a radius that its cell would outgrow), or 5/4 of the
  // largest circumradius of the expected simplices where smaller (RestrictedDelaunayOptions::expected).
  const double expected = o.expected ? largest_circumradius(P, *o.expected, system.intrinsic_dimension()) : 0;
  std::vector<double> nn(n);
  detail::parallel_for(n, o.threads, [&](std::size_t p, int) { nn[p] = nearest_distance(P, grid, static_cast<int>(p)); });
  std::vector<double> sorted = nn;
  double median = 0;
  if (n > 0) std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end()), median = sorted[n / 2];
  const double r_cap = 2 * grid.diameter();  // a ball this large holds all of P: larger never helps
  std::vector<double> radius(n);
  for (int p = 0; p < n; ++p) {
    radius[p] = 2 * std::max(nn[p], median);
    if (expected > 0) radius[p] = std::min(radius[p], 1.25 * expected);
    if (!(radius[p] > 0 && std::isfinite(radius[p]))) radius[p] = grid.diameter();
    // THE GRAPH LEMMA (rvd.cpp) holds out to nearly the reach from p: start inside it when it is used.
    if (o.cell.reach > 0) radius[p] = std::min(radius[p], 0.8 * o.cell.reach);
    // A point off M: its cell on M is at least d_p away (RestrictedDelaunayOptions::distance_to_M).
    if (o.distance_to_M && static_cast<std::size_t>(p) < o.distance_to_M->size()) {
      const double d = (*o.distance_to_M)[p];
      if (d > radius[p] / 64 && std::isfinite(d)) radius[p] = std::min(r_cap, radius[p] + d);
    }
  }
  // A note for a reason about point p when it is off M by more than a 64th of its first radius
  // (RestrictedDelaunayOptions::distance_to_M): far from M a cell is only found in a larger ball.
  auto far_from_M = [&, first = radius](int p) -> std::string {
    if (!o.distance_to_M || p < 0 || static_cast<std::size_t>(p) >= o.distance_to_M->size()) return "";
    const double d = (*o.distance_to_M)[p];
    if (!(d > first[p] / 64)) return "";
    return "; point " + std::to_string(p) + " is up to " + num(d) + " from M (check 1), and its cell on M is at least its "
           "distance to M away from it";
  };
  // Boxes per cell: 4 times more, twice at most, for a cell that ran out nearly done (its only
  // undecided boxes are the ones left, under a quarter of its budget). Work only: a cell with
  // boxes undecided otherwise (exact ties, under- or overflow) is not worth a larger budget.
  std::vector<long> budget(n, o.cell.max_boxes);
  std::vector<int> todo(n);
  for (int p = 0; p < n; ++p) todo[p] = p;
  double target = 0;  // the covering target: the largest vertex distance found so far
  for (int round = 0; !todo.empty(); ++round) {
    // In chunks of a fixed size (not of the thread count: the result must not depend on it), the
    // first passes, then the second passes against the largest vertex distance found so far
    // (COVERING TARGET in restricted.hpp).
    for (std::size_t begin = 0; begin < todo.size(); begin += kChunk) {
      const std::size_t count = std::min(kChunk, todo.size() - begin);
      std::vector<std::optional<RestrictedCell>> cells(count);
      std::vector<double> lower(count);
      detail::parallel_for(count, o.threads, [&](std::size_t i, int) {
        RestrictedCellOptions co = o.cell;
        co.graph_radius = radius[todo[begin + i]];
        co.max_boxes = budget[todo[begin + i]];
        cells[i].emplace(system, P, grid, todo[begin + i], co);
        lower[i] = cells[i]->first_pass();
      });
      target = std::max(target, *std::max_element(lower.begin(), lower.end()));
      detail::parallel_for(count, o.threads, [&](std::size_t i, int) {
        R.cells[todo[begin + i]] = cells[i]->second_pass(target);
        cells[i].reset();
      });
      if (o.progress) o.progress(begin + count, todo.size());
    }
    R.rounds_used = round + 1;
    double c = 0;
    for (const auto& cell : R.cells) c = std::max(c, cell.covering_bound);
    std::vector<int> again;
    // With THE GRAPH LEMMA, up to 0.95 reach first (beyond it the lemma fails near p and cells are slow).
    const double lemma_cap = 0.95 * o.cell.reach;
    for (int p = 0; p < n; ++p) {
      const RestrictedCellReport& cell = R.cells[p];
      const bool reaches = cell.undecided.empty() && !cell.complete;  // reaches its ball's boundary
      const bool grow = (reaches || !(c < cell.graph_radius)) && radius[p] < r_cap;
      const long left = std::count_if(cell.undecided.begin(), cell.undecided.end(),
                                      [](const UndecidedBox& u) { return u.reason == "box budget exhausted"; });
      const bool out_of_boxes = left > 0 && left == static_cast<long>(cell.undecided.size()) && 4 * left < budget[p] &&
                                budget[p] < 16 * o.cell.max_boxes;
      if (!grow && !out_of_boxes) continue;
      if (round < o.rounds) again.push_back(p);
      if (out_of_boxes) budget[p] *= 4;  // (the same radius, unless it must grow too)
      if (grow) {
        const double next = std::min(r_cap, std::max(2 * radius[p], 1.5 * c));
        radius[p] = radius[p] < lemma_cap ? std::min(next, lemma_cap) : next;
      }
    }
    if (again.empty()) break;
    todo = std::move(again);
  }

  // Assemble: the simplices (first certified vertex of each), the covering bound, the cross-check.
  std::vector<std::pair<std::vector<int>, RestrictedSimplex>> found;  // sorted by simplex
  std::map<std::vector<int>, RestrictedSimplex> faces;
  std::vector<std::pair<const RestrictedVoronoiVertex*, int>> vertex_refs;  // (vertex, the point whose cell lists it)
  R.min_radius = INFINITY;
  auto distance_lower = [&](const RestrictedVoronoiVertex& v, int p) {
    exact::UpwardRounding up;
    exact::IntervalNumber d(0);  // |x - p|^2 over the enclosure: d(x, P) = |x - p|
    for (std::size_t i = 0; i < v.x.size(); ++i)
      d += exact::square(exact::to_interval_number(v.x[i]) - exact::IntervalNumber(P.point(p)[i]));
    return exact::sqrt(d).inf();
  };
  for (int p = 0; p < n; ++p) {
    const RestrictedCellReport& cell = R.cells[p];
    R.boxes += cell.boxes, R.krawczyk_calls += cell.krawczyk_calls, R.krawczyk_failures += cell.krawczyk_failures;
    R.chart_failures += cell.chart_failures, R.reach_slabs += cell.reach_slabs;
    R.rational_chart_cells += cell.rational_chart;
    if (!cell.complete) R.incomplete_points.push_back(p);
    R.min_radius = std::min(R.min_radius, cell.graph_radius);
    if (cell.covering_bound > R.covering || R.covering_point < 0) R.covering = cell.covering_bound, R.covering_point = p;
    for (const auto& v : cell.vertices) vertex_refs.emplace_back(&v, p);
    for (const auto& v : cell.face_points)
      if (!faces.count(v.simplex)) faces.emplace(v.simplex, RestrictedSimplex{v.simplex, p, v, distance_lower(v, p)});
  }
  // The m-simplices, each from the first cell (by point index) and the first of its vertices there
  // that found it: a stable sort of the vertices by simplex, in (cell, vertex) order.
  std::stable_sort(vertex_refs.begin(), vertex_refs.end(), [](auto& a, auto& b) { return a.first->simplex < b.first->simplex; });
  for (std::size_t i = 0; i < vertex_refs.size(); ++i) {
    const RestrictedVoronoiVertex& v = *vertex_refs[i].first;
    const int p = vertex_refs[i].second;
    if (i > 0 && vertex_refs[i - 1].first->simplex == v.simplex) continue;
    const double lower = distance_lower(v, p);
    found.emplace_back(v.simplex, RestrictedSimplex{v.simplex, p, v, lower});
    R.vertex_distance_lower = std::max(R.vertex_distance_lower, lower);
  }
  auto covered = [](const std::vector<int>& f, const auto& simplices) {  // a proper face of one of them?
    return std::any_of(simplices.begin(), simplices.end(), [&](const auto& e) {
      return e.first.size() > f.size() && std::includes(e.first.begin(), e.first.end(), f.begin(), f.end());
    });
  };
  for (const auto& [f, rs] : faces)
    if (!covered(f, found) && !covered(f, faces)) R.lower_faces.push_back(rs);
  for (auto& [s, rs] : found) {
    for (int q : s) {
      if (q == rs.found_at || !R.cells[q].complete) continue;
      const auto& V = R.cells[q].vertices;
      if (std::none_of(V.begin(), V.end(), [&](const RestrictedVoronoiVertex& v) { return v.simplex == s; }))
        R.cross_check_failures.push_back({s, rs.found_at, q});
    }
    R.simplices.push_back(std::move(rs));
  }
  int farthest = 0;  // the point farthest from M (check 1's bounds), for the reasons below
  if (o.distance_to_M)
    for (int p = 0; p < n && static_cast<std::size_t>(p) < o.distance_to_M->size(); ++p)
      if ((*o.distance_to_M)[p] > (*o.distance_to_M)[farthest]) farthest = p;
  if (!R.incomplete_points.empty())
    R.reason = std::to_string(R.incomplete_points.size()) + " cell(s) not complete (first: point " +
               std::to_string(R.incomplete_points[0]) + ": " + R.cells[R.incomplete_points[0]].reason +
               far_from_M(R.incomplete_points[0]) + ")";
  else if (!(R.covering < R.min_radius))
    R.reason = "the covering bound is not below every analysed radius";
  else if (R.simplices.empty() && faces.empty())
    R.reason = "no restricted Voronoi vertex or face point was found, so no point of M is known to be within the "
               "covering bound of P: the covering argument has no anchor" +
               (far_from_M(farthest).empty() ? std::string() : " (" + far_from_M(farthest).substr(2) + ")");
  else if (!R.cross_check_failures.empty())
    R.reason = std::to_string(R.cross_check_failures.size()) +
               " restricted Voronoi vertex(es) found at one point of their simplex but not at another whose cell is "
               "complete: the program contradicts itself";
  R.covering_certified = R.reason.empty();
  return R;
}

}  // namespace delcert::certify
