// delcert: the producer's command-line tool (docs/design.md §9). One file per subcommand.
// Exit status: 0 success, 2 bad input or usage, 3 internal error (a bug: every input problem is
// reported as io::InputError), 4 refinement did not converge.
#include <cstdio>
#include <iostream>
#include <vector>

#include "core/app/command.hpp"
#include "io/input_error.hpp"

int main(int argc, char** argv) {
  using namespace delcert::app;
  CLI::App app{"delcert: tangential Delaunay complexes of manifolds, refined until they are provably correct."};
  app.set_version_flag("--version", "delcert " DELCERT_VERSION, "print \"delcert VERSION\" and exit");
  app.require_subcommand(1);
  std::vector<Command> commands{add_sample_command(app), add_tangential_command(app), add_refine_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version: exit 0
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
    std::cerr << "delcert: internal error: " << e.what()
              << "\nThis is a bug in delcert, not a problem with the input; please report it with the command line and "
                 "the input files.\n";
    return kExitInternalError;
  }
  return kExitBadInput;
}
