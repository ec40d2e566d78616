// Each `delcert` subcommand lives in its own file and registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/manifold/on_manifold.hpp"
#include "core/sampling/sampling.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/progress.hpp"

namespace delcert::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInternalError = 3;  // an exception other than io::InputError
inline constexpr int kExitNotConverged = 4;
// delcert refine: converged, but the final in-process certification of the output did not certify it whole.
inline constexpr int kExitNotCertified = 5;

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;  // may throw io::InputError (-> exit 2); anything else is a bug (-> exit 3)
};

// Help text for --manifold, listing the built-in names.
std::string manifold_option_help();

// Option validators (issue 13 §5). Each refuses a value with one short line, "--OPTION: what is
// wrong; what to give" (exit status 2): numbers in the message are %g-style or named, never a
// 300-digit bound, and a long input is shortened.

// A whole number from 0 to `max`, decimal digits only (no sign, no hex or octal: CLI11 2.1 would
// read "-1" as 2^64-1 and "010" as 8). Transforms the input to its canonical spelling.
CLI::Validator whole_number(const std::string& what, std::uint64_t max);

// A finite double > 0 (not NaN, not infinite, not out of double's range).
CLI::Validator positive_number();

// --threads: 0 (one per hardware thread, the default of every command) or 1 to kMaxThreads.
inline constexpr int kMaxThreads = 256;
CLI::Validator thread_count();
std::string threads_help();

// --eps as `sample` and `refine` take it: a decimal or a fraction (refine::parse_rational_option),
// > 0, with a positive finite double; returns that double. Throws io::InputError naming --eps.
double eps_option(const std::string& text);
// --mesh-out FILE.off|FILE.ply of `tangential` and `refine`: the complex as a surface mesh that any
// mesh viewer (and delcert-certify) opens. check_mesh_out runs before any work: the extension
// names the format, the path must be writable and no input; check_mesh_dimensions refuses
// (exit 2) a manifold other than a surface in R^3 (m = 2, N = 3).
void check_mesh_out(const std::string& path, const std::vector<std::string>& inputs,
                    const std::vector<std::string>& other_outputs, bool directory_may_be_created = false);
void check_mesh_dimensions(const std::string& path, int m, int N);
// The mesh text: the points and the complex's triangles. A maximal simplex that is not a triangle
// (an edge or a vertex left over by an inconsistent complex) is not a face of a surface mesh: it
// is left out, and a warning on stderr says how many.
std::string mesh_out_text(const std::string& path, const io::PointSet& points, const io::Complex& complex);
inline constexpr const char* kMeshOutHelp =
    "also write the complex as a surface mesh, OFF or PLY by the extension (.off, .ply); m = 2, N = 3 only (written atomically)";

// Progress lines (issue 13 §5): each command draws one on stderr when it is a terminal
// (io::ProgressLine::on_stderr(), silent otherwise; outputs never depend on it). This feeds it the
// phases of sampling::eps_net (EpsNetOptions::progress); empty when the line is not shown.
std::function<void(const char*, int, std::size_t, std::size_t)> eps_net_progress(io::ProgressLine& line);

Command add_sample_command(CLI::App& app);
Command add_tangential_command(CLI::App& app);
Command add_refine_command(CLI::App& app);

}  // namespace delcert::app
