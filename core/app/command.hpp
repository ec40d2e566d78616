// Each `delcert` subcommand lives in its own file and registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "core/manifold/manifold.hpp"
#include "io/points.hpp"

namespace delcert::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNotConverged = 4;

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;  // may throw io::InputError (-> exit 2)
};

// Help text for --manifold, listing the built-in names.
std::string manifold_option_help();

// Rejects input points that are not on M to the spec's residual tolerance, or are on a component
// the spec's selector excludes: their tangent flat would mean nothing. Throws io::InputError
// naming `path`.
void check_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& path);

// The same check for points the producer sampled itself (delcert sample, refine without --points):
// a failure means the spec's parametrization (or projection) disagrees with its equations.
// Throws io::InputError naming the spec; the caller has written nothing yet.
void check_sample_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& spec_path);

Command add_sample_command(CLI::App& app);
Command add_tangential_command(CLI::App& app);
Command add_refine_command(CLI::App& app);

}  // namespace delcert::app
