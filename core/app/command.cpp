#include "core/app/command.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <limits>

#include "core/refine/parameters.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/mesh.hpp"
#include "io/spec.hpp"

namespace delcert::app {

std::string manifold_option_help() {
  std::string s = "manifold spec: a JSON file or builtin:NAME (";
  auto names = io::builtin_spec_names();
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + ")";
}

void check_mesh_out(const std::string& path, const std::vector<std::string>& inputs,
                    const std::vector<std::string>& other_outputs, bool directory_may_be_created) {
  io::mesh_output_format(path, "--mesh-out");
  io::check_output_path(path, "--mesh-out", inputs, other_outputs, directory_may_be_created);
}

void check_mesh_dimensions(const std::string& path, int m, int N) {
  if (m != 2 || N != 3)
    throw io::InputError(path, 0,
                         "--mesh-out writes a surface mesh in R^3, but the manifold has m = " + std::to_string(m) +
                             ", N = " + std::to_string(N) + "; leave out --mesh-out (the complex file holds the result)");
}

std::string mesh_out_text(const std::string& path, const io::PointSet& points, const io::Complex& complex) {
  io::Complex triangles;
  triangles.num_vertices = complex.num_vertices;
  for (const auto& s : complex.simplices)
    if (s.size() == 3) triangles.simplices.push_back(s);
  if (const std::size_t left_out = complex.simplices.size() - triangles.simplices.size())
    std::fprintf(stderr, "warning: %s: %zu maximal simplices that are not triangles left out of the mesh\n", path.c_str(),
                 left_out);
  return io::format_mesh(points, triangles, io::mesh_output_format(path, "--mesh-out"));
}

namespace {

// The input as the message shows it: a long one is cut (the user typed it; no need to echo 300 digits).
std::string shown(const std::string& input) {
  if (input.empty()) return "''";
  return input.size() <= 24 ? input : input.substr(0, 20) + "... (" + std::to_string(input.size()) + " characters)";
}

std::string g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// "" when `input` is decimal digits naming a number <= max (then made canonical: no leading zeros,
// which CLI11 would read as octal); else why not, followed by `give`.
std::string check_whole(std::string& input, std::uint64_t max, const std::string& give) {
  const bool digits_after_minus =
      input.size() > 1 && input[0] == '-' && input.find_first_not_of("0123456789", 1) == std::string::npos;
  if (digits_after_minus) return shown(input) + " is negative" + give;
  if (input.empty() || input.find_first_not_of("0123456789") != std::string::npos)
    return shown(input) + " is not a whole number" + give;
  const std::size_t first = input.find_first_not_of('0');
  const std::string digits = first == std::string::npos ? "0" : input.substr(first);
  const std::string limit = std::to_string(max);
  if (digits.size() > limit.size() || (digits.size() == limit.size() && digits > limit))
    return shown(input) + " is above " + limit + give;
  input = digits;
  return {};
}

}  // namespace

CLI::Validator whole_number(const std::string& what, std::uint64_t max) {
  const std::string give = "; give " + what + " from 0 to " + std::to_string(max);
  return CLI::Validator([max, give](std::string& input) { return check_whole(input, max, give); },
                        "0.." + std::to_string(max), "WHOLE_NUMBER");
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        const std::string give = "; give a number > 0, e.g. 0.25";
        const char* begin = input.c_str();
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(begin, &end);
        if (input.empty() || end != begin + input.size() || std::isnan(x)) return shown(input) + " is not a number" + give;
        if (std::isinf(x) || (errno == ERANGE && std::fabs(x) > 1))
          return shown(input) + " is too large (the largest double is " + g(std::numeric_limits<double>::max()) + ")" + give;
        if (std::signbit(x) || (x == 0 && errno != ERANGE)) return shown(input) + " is not positive" + give;
        if (errno == ERANGE || x < std::numeric_limits<double>::min())
          return shown(input) + " is too small (the smallest normal double is " + g(std::numeric_limits<double>::min()) +
                 ")" + give;
        return {};
      },
      "> 0", "POSITIVE");
}

std::string threads_help() {
  return "worker threads: 0 (the default) = one per hardware thread, or 1 to " + std::to_string(kMaxThreads) +
         "; the output does not depend on it";
}

CLI::Validator thread_count() {
  const std::string give =
      "; give 0 (one thread per hardware thread) or a thread count from 1 to " + std::to_string(kMaxThreads);
  return CLI::Validator([give](std::string& input) { return check_whole(input, kMaxThreads, give); },
                        "0.." + std::to_string(kMaxThreads), "THREADS");
}

std::function<void(const char*, int, std::size_t, std::size_t)> eps_net_progress(io::ProgressLine& line) {
  if (!line.terminal()) return {};
  auto last = std::make_shared<std::pair<std::string, int>>();
  return [&line, last](const char* phase, int pass, std::size_t done, std::size_t total) {
    if (last->first != phase || last->second != pass) {
      *last = {phase, pass};
      line.phase(std::string(phase) + ", pass " + std::to_string(pass), total);
    }
    line.update(done);
  };
}

double eps_option(const std::string& text) { return refine::parse_eps_option(text).value.get_d(); }


}  // namespace delcert::app
