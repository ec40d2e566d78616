#include "core/refine/picking_region.hpp"

#include <cmath>

namespace delcert::refine {

Eigen::VectorXd sample_picking_region(const PickingRegion& region, sampling::Random& random) {
  const auto m = region.tangent.cols();
  Eigen::VectorXd u(m);
  double n2 = 0;
  do {
    for (Eigen::Index i = 0; i < m; ++i) u[i] = random.normal();
    n2 = u.squaredNorm();
  } while (!(n2 > 1e-300));
  // Uniform in the unit m-ball: direction uniform on the sphere, radius with density ∝ r^(m-1).
  const double r = std::pow(random.uniform(), 1.0 / static_cast<double>(m));
  u *= r / std::sqrt(n2);
  return region.centre + region.tangent * (region.radius * u);
}

std::optional<Eigen::VectorXd> pick_in_region(const manifold::Manifold& manifold, std::span<const double> p, const manifold::Frame& frame,
                                              const PickingRegion& region, sampling::Random& random, double max_distance,
                                              Eigen::VectorXd* y_out) {
  Eigen::VectorXd y = sample_picking_region(region, random);
  if (y_out) *y_out = y;
  manifold::NewtonOptions options;
  options.max_distance = max_distance;
  auto x = manifold.psi(p, frame, y, options);
  if (!x || !x->allFinite()) return std::nullopt;
  if (!manifold.on_selected_component(manifold::as_span(*x))) return std::nullopt;
  return x;
}

}  // namespace delcert::refine
