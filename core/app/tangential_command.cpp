// delcert tangential --manifold SPEC --points POINTS --out COMPLEX [--stats STATS.json] [--threads T]
// (issue 4: not built yet; registered so that --help lists it and any use is a clear error.)
#include <memory>
#include <stdexcept>

#include "core/app/command.hpp"

namespace delcert::app {

Command add_tangential_command(CLI::App& app) {
  auto* sub = app.add_subcommand("tangential", "build the tangential Delaunay complex (not available yet)");
  sub->allow_extras();
  return {sub, [] () -> int { throw std::runtime_error("'delcert tangential' is not available in this build yet"); }};
}

}  // namespace delcert::app
