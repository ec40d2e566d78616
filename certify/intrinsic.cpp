#include "certify/intrinsic.hpp"

#include <stdexcept>

#include "certify/detail/intrinsic_engines.hpp"

namespace delcert::certify {

IntrinsicDelaunay compute_intrinsic_delaunay(const io::ManifoldSpec& spec, const io::PointSet& points,
                                             const detail::PointGrid& grid,
                                             const std::vector<std::vector<int>>& candidates, int threads) {
  const int m = spec.intrinsic_dimension, N = spec.ambient_dimension;
  for (const auto& s : candidates) {
    if (static_cast<int>(s.size()) != m + 1) throw std::invalid_argument("an intrinsic candidate is not an m-simplex");
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i] < 0 || static_cast<std::size_t>(s[i]) >= points.size() || (i && s[i - 1] >= s[i]))
        throw std::invalid_argument("an intrinsic candidate is not a sorted set of point indices");
  }
  IntrinsicDelaunay D;
  if (!spec.metric) {
    D.reason = "no closed-form geodesic distance: the spec declares no metric";
    return D;
  }
  const io::ShapeSpec& g = *spec.metric;
  if (g.kind == io::ShapeSpec::Kind::sphere && N == m + 1)
    return detail::intrinsic_delaunay_sphere(g, points, grid, candidates, threads);
  if (g.kind == io::ShapeSpec::Kind::product_of_circles && N == 2 * m &&
      static_cast<int>(g.radii.size()) == m)
    return detail::intrinsic_delaunay_flat_torus(g, points, grid, candidates, threads);
  D.metric = g.kind == io::ShapeSpec::Kind::so3 ? "so3"
             : g.kind == io::ShapeSpec::Kind::sphere ? "sphere"
             : g.kind == io::ShapeSpec::Kind::product_of_circles ? "product_of_circles"
                                                                 : "torus_of_revolution";
  D.reason = "Del_M for the declared metric (" + D.metric + ", m = " + std::to_string(m) + ", N = " +
             std::to_string(N) + ") is not built in this version (docs/design.md §12)";
  return D;
}

}  // namespace delcert::certify
