// delcert: the producer's command-line tool (docs/design.md §9). One file per subcommand.
// Exit status: 0 success, 2 bad input or usage, 4 refinement did not converge.
#include <cstdio>
#include <iostream>
#include <vector>

#include "core/app/command.hpp"
#include "io/input_error.hpp"
#include "io/spec.hpp"

namespace delcert::app {

std::string manifold_option_help() {
  std::string s = "manifold spec: a JSON file or builtin:NAME (";
  auto names = io::builtin_spec_names();
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + ")";
}

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

}  // namespace delcert::app

int main(int argc, char** argv) {
  using namespace delcert::app;
  CLI::App app{"delcert: tangential Delaunay complexes of manifolds, refined until they are provably correct."};
  app.require_subcommand(1);
  std::vector<Command> commands{add_sample_command(app), add_tangential_command(app), add_refine_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  try {
    for (auto& c : commands)
      if (c.sub && c.sub->parsed()) return c.run();
  } catch (const delcert::io::InputError& e) {
    std::cerr << "delcert: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "delcert: error: " << e.what() << "\n";
    return kExitBadInput;
  }
  return kExitBadInput;
}
