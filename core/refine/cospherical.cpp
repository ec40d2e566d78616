#include "core/refine/cospherical.hpp"

#include <algorithm>
#include <cmath>

#include "core/refine/simplex_measures.hpp"
#include "core/spatial/distance.hpp"

namespace delcert::refine {

namespace {

// L(σ)^2 from the vertex coordinates.
double shortest_edge2(const io::PointSet& points, std::span<const int> cell) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < cell.size(); ++a)
    for (std::size_t b = a + 1; b < cell.size(); ++b)
      best = std::min(best, spatial::squared_distance(points.point(cell[a]), points.point(cell[b])));
  return best;
}

bool member_with_l2(const io::PointSet& points, std::span<const int> cell, std::span<const double> centre, double radius2,
                    std::size_t q, double sigma_l2, const CosphOptions& o, CosphMember* out) {
  if (std::find(cell.begin(), cell.end(), static_cast<int>(q)) != cell.end()) return false;
  const auto pq = points.point(q);
  const double power = spatial::squared_distance(centre, pq) - radius2;
  if (power < o.lower) return false;
  double l2 = sigma_l2;
  for (int v : cell) l2 = std::min(l2, spatial::squared_distance(points.point(v), pq));
  const double L = std::max(std::sqrt(l2), o.length_floor);
  const double bound = o.delta0 * o.delta0 * L * L;
  if (power > bound + o.slack) return false;
  if (out) *out = {q, power, bound};
  return true;
}

}  // namespace

bool cosph_member(const io::PointSet& points, std::span<const int> cell, std::span<const double> centre, double radius2,
                  std::size_t q, const CosphOptions& options, CosphMember* out) {
  return member_with_l2(points, cell, centre, radius2, q, shortest_edge2(points, cell), options, out);
}

std::vector<CosphMember> cosph_members(const io::PointSet& points, const spatial::NeighbourIndex& index, std::span<const int> cell,
                                       std::span<const double> centre, double radius2, const CosphOptions& options) {
  const double sigma_l2 = shortest_edge2(points, cell);
  const double L = std::max(std::sqrt(sigma_l2), options.length_floor);
  const double reach2 = radius2 + options.delta0 * options.delta0 * L * L + std::max(0.0, options.slack);
  std::vector<CosphMember> out;
  index.for_each_in_ball(centre, reach2, [&](std::size_t q, double) {
    CosphMember m;
    if (member_with_l2(points, cell, centre, radius2, q, sigma_l2, options, &m)) out.push_back(m);
  });
  std::sort(out.begin(), out.end(), [](const CosphMember& a, const CosphMember& b) { return a.q < b.q; });
  return out;
}

bool cosph_test(const io::PointSet& points, std::span<const int> cell, std::span<const double> centre, double radius2,
                std::size_t q, double eps, double gamma0, const CosphOptions& options) {
  if (!(radius2 < eps * eps)) return false;
  if (!make_simplex(points, cell).is_good(gamma0)) return false;
  return cosph_member(points, cell, centre, radius2, q, options);
}

}  // namespace delcert::refine
