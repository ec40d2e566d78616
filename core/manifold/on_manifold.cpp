#include "core/manifold/on_manifold.hpp"

#include <cstdio>

#include "io/input_error.hpp"

namespace delcert::manifold {

void check_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& path) {
  const double tolerance = manifold.spec().residual_tolerance.get_d();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = manifold.residual(points.point(i));
    if (!(r <= tolerance)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.3g exceeds the spec's residual_tolerance %.3g", r, tolerance);
      throw io::InputError(path, 0,
                           "point " + std::to_string(i) + " (0-based) is not on " + manifold.spec().name +
                               ": max |F_i(p)| = " + buf + "; project the points onto M first");
    }
    if (!manifold.on_selected_component(points.point(i)))
      throw io::InputError(path, 0,
                           "point " + std::to_string(i) + " (0-based) is on the wrong component of " +
                               manifold.spec().name + " (the spec's selector is not positive there)");
  }
}

// Every sampled point must satisfy the equations to the spec's residual tolerance (the check
// input points get). With a parametrization the points come from it alone, so a failure means
// the parametrization and the equations describe different sets: refuse, writing nothing.
void check_sample_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& spec_path) {
  const double tolerance = manifold.spec().residual_tolerance.get_d();
  const std::string what = manifold.spec().parametrization ? "the spec's parametrization does not satisfy its equations"
                                                           : "a point projected onto M does not satisfy the equations";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = manifold.residual(points.point(i));
    if (!(r <= tolerance)) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "max |F_i(p)| = %.3g exceeds the residual_tolerance %.3g", r, tolerance);
      throw io::InputError(spec_path, 0,
                           what + " (sampled point " + std::to_string(i) + ": " + buf + "); fix the spec. Nothing was written");
    }
    if (!manifold.on_selected_component(points.point(i)))
      throw io::InputError(spec_path, 0,
                           "a sampled point is not on the component the spec's selector chooses (sampled point " +
                               std::to_string(i) + "); fix the spec. Nothing was written");
  }
}

}  // namespace delcert::manifold
