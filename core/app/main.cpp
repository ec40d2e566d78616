// delcert: the producer's command-line tool (DESIGN §5b).
//   delcert sample     --manifold SPEC --eps E [--seed S] --out POINTS
// Exit status: 0 success, 2 bad input or usage.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "core/io/input_error.hpp"
#include "core/io/spec.hpp"
#include "core/manifold/manifold.hpp"
#include "core/sampling/sampling.hpp"

namespace {

constexpr int kExitBadInput = 2;

std::string spec_help() {
  std::string s = "manifold spec: a JSON file or builtin:NAME (";
  auto names = delcert::io::builtin_spec_names();
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + ")";
}

int run_sample(const std::string& manifold_source, double eps, std::uint64_t seed, const std::string& out) {
  delcert::Manifold manifold(delcert::io::read_spec(manifold_source));
  delcert::EpsNetOptions options;
  options.eps = eps;
  options.seed = seed;
  auto net = delcert::eps_net(manifold, options);
  delcert::io::write_points(out, net.points);
  std::printf("manifold           %s (m = %d, N = %d)\n", manifold.spec().name.c_str(), manifold.intrinsic_dimension(),
              manifold.ambient_dimension());
  std::printf("eps                %s\n", delcert::io::format_double(eps).c_str());
  std::printf("seed               %llu\n", static_cast<unsigned long long>(seed));
  std::printf("dense sample       %zu points\n", net.dense_size);
  std::printf("eps-net            %zu points -> %s\n", net.points.size(), out.c_str());
  std::printf("min distance       %.6g  (eps-sparse: %s)\n", net.min_distance, net.min_distance >= eps ? "yes" : "NO");
  std::printf("covering radius    %.6g  (estimated on the dense sample; < eps: %s)\n", net.covering_radius,
              net.covering_radius < eps ? "yes" : "NO");
  std::printf("max |F(p)|         %.3g\n", net.max_residual);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"delcert: tangential Delaunay complexes of manifolds, refined until they are provably correct."};
  app.require_subcommand(1);

  std::string manifold, out;
  double eps = 0;
  std::uint64_t seed = 1;
  auto* sample = app.add_subcommand("sample", "write an eps-net of M (farthest-point selection from a dense sample)");
  sample->add_option("--manifold", manifold, spec_help())->required();
  sample->add_option("--eps", eps, "sparsity / sampling radius")->required()->check(CLI::PositiveNumber);
  sample->add_option("--seed", seed, "random seed (same seed, same bytes)")->capture_default_str();
  sample->add_option("--out", out, "output points file (written atomically)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  try {
    if (*sample) return run_sample(manifold, eps, seed, out);
  } catch (const delcert::io::InputError& e) {
    std::cerr << "delcert: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "delcert: error: " << e.what() << "\n";
    return kExitBadInput;
  }
  return kExitBadInput;
}
