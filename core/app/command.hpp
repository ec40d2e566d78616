// Each `delcert` subcommand lives in its own file and registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "core/manifold/on_manifold.hpp"

namespace delcert::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInternalError = 3;  // an exception other than io::InputError
inline constexpr int kExitNotConverged = 4;

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;  // may throw io::InputError (-> exit 2); anything else is a bug (-> exit 3)
};

// Help text for --manifold, listing the built-in names.
std::string manifold_option_help();

Command add_sample_command(CLI::App& app);
Command add_tangential_command(CLI::App& app);
Command add_refine_command(CLI::App& app);

}  // namespace delcert::app
