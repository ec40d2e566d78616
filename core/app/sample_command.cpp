// delcert sample --manifold SPEC --eps E [--seed S] --out POINTS
#include <cstdio>
#include <limits>
#include <memory>

#include "core/app/command.hpp"
#include "core/manifold/manifold.hpp"
#include "core/sampling/sampling.hpp"
#include "io/atomic_file.hpp"
#include "io/spec.hpp"

namespace delcert::app {

namespace {

struct SampleArgs {
  std::string manifold, out, eps;
  std::uint64_t seed = 1;
};

int run_sample(const SampleArgs& a) {
  manifold::Manifold manifold(io::read_spec(a.manifold));
  sampling::EpsNetOptions options;
  options.eps = eps_option(a.eps);
  options.seed = a.seed;
  io::check_output_path(a.out, "--out", {a.manifold});
  sampling::check_eps_net_size(manifold, options);
  io::ProgressLine progress = io::ProgressLine::on_stderr();
  options.progress = eps_net_progress(progress);
  auto net = sampling::eps_net(manifold, options);
  progress.clear();
  if (net.dense_capped)
    std::fprintf(stderr,
                 "warning: eps %s: the dense sample stopped at its cap of %zu points, fewer than %.0f per net point; "
                 "the eps-net (%zu points) is eps-sparse but covers M less surely; give eps >= %s to stay within the cap\n",
                 a.eps.c_str(), options.max_dense, options.oversampling, net.points.size(),
                 sampling::smallest_eps_within_cap(manifold, options).c_str());
  manifold::check_sample_on_manifold(manifold, net.points, a.manifold);
  io::write_points(a.out, net.points);
  std::printf("manifold           %s (m = %d, N = %d)\n", manifold.spec().name.c_str(), manifold.intrinsic_dimension(),
              manifold.ambient_dimension());
  std::printf("eps                %s\n", a.eps.c_str());
  std::printf("seed               %llu\n", static_cast<unsigned long long>(a.seed));
  std::printf("dense sample       %zu points\n", net.dense_size);
  std::printf("eps-net            %zu points -> %s\n", net.points.size(), a.out.c_str());
  std::printf("min distance       %.6g  (eps-sparse: %s)\n", net.min_distance, net.min_distance > options.eps ? "yes" : "NO");
  // The farthest dense-sample point from the net is a point of M, so this is a LOWER bound on the
  // covering radius max_{x in M} d(x, P); the true value can be larger (a restricted Voronoi vertex
  // between dense-sample points), so it proves nothing about P being an eps-sample.
  std::printf("covering radius    >= %.6g  (a lower bound, measured on the %zu dense-sample points; not certified)\n",
              net.covering_radius, net.dense_size);
  std::printf("max |F(p)|         %.3g\n", net.max_residual);
  return kExitOk;
}

std::string eps_help() {
  const sampling::EpsNetOptions defaults;
  const auto per_point = static_cast<std::size_t>(defaults.oversampling);
  return "sparsity and sampling radius: a decimal or a fraction (0.1, 1/10, 1e-1), as refine --eps. The net is "
         "selected from a dense sample of about " + std::to_string(per_point) + " points per net point, capped at " +
         std::to_string(defaults.max_dense) + " points (nets of at most about " +
         std::to_string(defaults.max_dense / per_point / 1000) +
         "k points): an eps that needs more is refused, and the message names the smallest eps that fits";
}

}  // namespace

Command add_sample_command(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  auto* sub = app.add_subcommand("sample", "write an eps-net of M (farthest-point selection from a dense sample)");
  sub->add_option("--manifold", args->manifold, manifold_option_help())->required();
  sub->add_option("--eps", args->eps, eps_help())->required();
  sub->add_option("--seed", args->seed, "random seed (same seed, same bytes)")
      ->capture_default_str()
      ->transform(whole_number("a seed", std::numeric_limits<std::uint64_t>::max()));
  sub->add_option("--out", args->out, "output points file (written atomically)")->required();
  return {sub, [args] { return run_sample(*args); }};
}

}  // namespace delcert::app
