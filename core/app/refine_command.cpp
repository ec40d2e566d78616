// delcert refine --manifold SPEC (--points POINTS | --eps E) [--mode practical|paper] [--gamma0 G]
//                [--alpha A] [--beta B] [--delta0 D] [--seed S] [--threads T] --out DIR
//
// Refines a sample of M until its tangential Delaunay complex is thick, protected and (in the
// practical mode) consistent (paper §4, docs/design.md §3.5; see docs/refinement.md for
// the rules; where ε is too coarse for the local geometry the practical mode shrinks it locally).
// Writes DIR/points.txt (the input points first, in order), DIR/complex.txt,
// DIR/report.json and DIR/claims.json. Exit status 0 when converged and (with the Del_M check, on by
// default in practical mode) the output certifies whole: the written files go through the
// certifier in-process (certify::run_certify with claims.json) and every claimed check is
// CERTIFIED, but those the certifier cannot compute on this manifold (refine::certifies_whole).
// 4 when a cap stopped the run (--max-points, default 1000000, or an explicit --max-inserted /
// --max-rounds / --max-repair-rounds; the partial output is written, report.json says
// "converged": false and the summary says which rule stalled where), 5 when it converged but did
// not certify, 2 on bad input.
//
// Defaults (the paper's constants are unusable at any ε one can compute with: H1 asks β >= 2.9
// and H2 Γ0 < 1/(B+1) < 1e-8):
//   Γ0 = 0.15  thickness >= 0.0225 for triangles, 0.0034 for tetrahedra: the knee of the measured
//              trade-off (docs/refinement.md, "Thickness and Γ0": from 10k points of T^3 and
//              SO(3), 0.15 raises the smallest tetrahedron's Υ 1.5x and 2.7x over 0.1 for 8% and 6%
//              more inserted points; from 0.2 on the hitting-set rejections multiply the work 20x);
//   α  = 0.3   the paper's α < 1/2;
//   β  = 1.1   hitting sets of weighted radius < 1.1 R_p: the search grows like β^(m(m+1)) (at
//              β = 1.5 it examines ~15x more simplices per candidate than at 1.2), and at
//              realistic ε candidates are rarely hit at all;
//   δ0 = Γ0^ceil((m+1)/2)   the largest power of Γ0 that satisfies H3 (0.0225 for m = 2, 3);
//              claimed protection δ̌^2 = δ0^2 (ε_min/9)^2, ε_min the smallest local ε (= ε
//              unless the practical mode had to shrink ε locally; docs/refinement.md);
//   ε when only --points is given: two significant digits above the input's largest R_p, so
//              that Rule 1 has nothing to do at the start.
//   --sizing uniform (the paper's single ε; output byte-identical to before the option existed);
//   --sizing curvature: ε(x) = min(ε, max(floor, c / κ_max(x))), --sizing-c c = 1/2 (why:
//              core/refine/parameters.hpp), --eps-floor = ε/10; claims.json is then version 3 with
//              DIR/eps.txt, ε(p) per point (docs/refinement.md, "Sizing field").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/app/command.hpp"
#include "core/manifold/manifold.hpp"
#include "certify/certify.hpp"
#include "core/refine/intrinsic_repair.hpp"
#include "core/refine/refine_output.hpp"
#include "core/refine/refiner.hpp"
#include "core/sampling/sampling.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::app {

namespace {

struct RefineArgs {
  std::string manifold, points, out, mesh_out, mode = "practical";
  std::string eps, gamma0 = "0.15", alpha = "0.3", beta = "1.1", delta0;
  std::string sizing = "uniform", sizing_c, eps_floor;  // sizing_c empty: 0.5 (curvature only)
  std::uint64_t seed = 1;
  int threads = 0;  // one per hardware thread, as in every command
  std::size_t max_points = refine::kDefaultMaxPoints, max_inserted = 0, max_rounds = 0;
  std::size_t max_repair_rounds = refine::kDefaultMaxRepairRounds;
  bool no_restricted_check = false, look_ahead = false;
  bool no_intrinsic_check = false, intrinsic_check = false;  // the second: paper mode only
};

// "round 12: 3456 points (+456); pending 3 big, 40 inconsistent": the rules with configurations
// pending, short enough for the progress line.
std::string round_progress_label(const refine::RefineProgress& p) {
  std::string s = "round " + std::to_string(p.round) + ": " + std::to_string(p.points) + " points (+" +
                  std::to_string(p.inserted) + ")";
  const char* sep = "; pending ";
  for (refine::Rule rule : refine::kRules)
    if (p.pending[rule]) s += sep + std::to_string(p.pending[rule]) + " " + refine::to_string(rule), sep = ", ";
  if (p.checking_del_m) s += "; Del_M check (Del_RM and Del_M by the certifier's engines)";
  return s;
}

// The final certification (with the Del_M check on): the written output through the certifier's
// checks in-process, with the claims written; true when it certifies whole (refine::certifies_whole).
bool certify_output(const RefineArgs& a, int threads) {
  namespace fs = std::filesystem;
  const auto started = std::chrono::steady_clock::now();
  certify::CertifyOptions o;
  o.general_del_m = false;  // the repair rule does not use the general Del_M engine yet (docs/refinement.md)
  o.manifold = a.manifold;
  o.points = (fs::path(a.out) / "points.txt").string();
  o.complex = (fs::path(a.out) / "complex.txt").string();
  o.claims = (fs::path(a.out) / "claims.json").string();
  o.threads = threads;
  io::ProgressLine progress = io::ProgressLine::on_stderr();
  if (progress.terminal()) o.progress = &progress;
  const certify::Certificate C = certify::run_certify(o);
  progress.clear();
  const refine::WholeVerdict v = refine::certifies_whole(C);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("certified          %s (in-process certification of the output with claims.json, %.3f s)\n",
              v.certified ? "yes" : "NO", seconds);
  for (const auto& line : v.not_decidable) std::printf("  not decidable    %s\n", line.c_str());
  for (const auto& line : v.failing) std::printf("  failing          %s\n", line.c_str());
  if (!v.certified)
    std::printf("advice             the output did not certify whole (exit status 5): run delcert-certify on it for the "
                "witnesses\n");
  return v.certified;
}

int run_refine(const RefineArgs& a) {
  const auto started = std::chrono::steady_clock::now();
  // Every output checked before any work (DIR itself may be created at the end).
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(a.out, ec) && !fs::is_directory(a.out, ec))
      throw io::InputError(a.out, 0, "--out: exists and is not a directory; refine writes a directory of four files");
    std::vector<std::string> outs;
    for (const char* f : {"points.txt", "complex.txt", "claims.json", "report.json"}) outs.push_back((fs::path(a.out) / f).string());
    if (a.sizing == "curvature") outs.push_back((fs::path(a.out) / "eps.txt").string());
    for (const auto& o : outs) io::check_output_path(o, "--out", {a.manifold, a.points}, {a.mesh_out}, true);
    if (!a.mesh_out.empty()) check_mesh_out(a.mesh_out, {a.manifold, a.points}, outs);
  }
  manifold::Manifold manifold(io::read_spec(a.manifold));
  const int m = manifold.intrinsic_dimension(), N = manifold.ambient_dimension();
  if (m < 2 || m > 4)
    throw io::InputError(manifold.spec().source, 0,
                         "intrinsic dimension " + std::to_string(m) + ": refinement is implemented for m = 2, 3 and 4");
  if (!a.mesh_out.empty()) check_mesh_dimensions(a.mesh_out, m, N);
  if (a.points.empty() && a.eps.empty())
    throw io::InputError("delcert refine", 0, "give --points POINTS, or --eps E to start from an eps-net of M");

  refine::RefineParameters params;
  params.mode = a.mode == "paper" ? refine::RefineMode::paper : refine::RefineMode::practical;
  refine::ConstantTexts texts;
  if (!a.eps.empty()) texts.eps = a.eps;
  if (!a.delta0.empty()) texts.delta0 = a.delta0;
  texts.gamma0 = a.gamma0, texts.alpha = a.alpha, texts.beta = a.beta;
  params.constants = refine::parse_constants(texts, m);
  if (a.sizing == "curvature") {
    if (params.mode == refine::RefineMode::paper)
      throw io::InputError("delcert refine", 0, "--sizing curvature needs --mode practical (the paper's Algorithm 1 uses one eps)");
    params.sizing.kind = refine::SizingKind::curvature;
    params.sizing.c = refine::parse_rational_option("--sizing-c", a.sizing_c.empty() ? "0.5" : a.sizing_c);
    if (!a.eps_floor.empty()) params.sizing.floor = refine::parse_rational_option("--eps-floor", a.eps_floor);
    if (!params.constants.eps)
      throw io::InputError("delcert refine", 0, "--sizing curvature needs --eps (the field's cap)");
    try {
      refine::SizingField check = params.sizing;
      refine::resolve_sizing(check, *params.constants.eps);
    } catch (const refine::ParameterError& e) {
      throw io::InputError("delcert refine", 0, e.what());
    }
  } else if (!a.eps_floor.empty() || !a.sizing_c.empty()) {
    throw io::InputError("delcert refine", 0, "--sizing-c and --eps-floor need --sizing curvature");
  }
  params.seed = a.seed;
  params.restricted_check = !a.no_restricted_check;
  params.look_ahead = a.look_ahead;
  if (a.no_intrinsic_check && a.intrinsic_check)
    throw io::InputError("delcert refine", 0, "--intrinsic-check and --no-intrinsic-check contradict each other");
  if (a.intrinsic_check && params.mode != refine::RefineMode::paper)
    throw io::InputError("delcert refine", 0, "--intrinsic-check is for --mode paper (practical mode has it on by default)");
  if (a.no_intrinsic_check) params.intrinsic_check = false;
  if (a.intrinsic_check) params.intrinsic_check = true;
  params.max_repair_rounds = a.max_repair_rounds;
  params.threads = a.threads;
  params.max_points = a.max_points;
  params.max_inserted = a.max_inserted;
  params.max_rounds = a.max_rounds;

  io::PointSet input;
  std::string input_text;
  if (!a.points.empty()) {
    io::PointReadOptions ro;
    ro.expected_dimension = N;
    input = io::read_points(a.points, ro);
    manifold::check_on_manifold(manifold, input, a.points);
    input_text = a.points;
  } else {
    sampling::EpsNetOptions eo;
    eo.eps = refine::as_doubles(params.constants).eps;
    eo.seed = a.seed;
    sampling::check_eps_net_size(manifold, eo);
    io::ProgressLine progress = io::ProgressLine::on_stderr();
    eo.progress = eps_net_progress(progress);
    // An ε as coarse as M itself gives a net of fewer than the m + 2 points a star needs: the
    // net is then taken at ε/2, ε/4, ... (the refiner's ε stays the one given).
    int halvings = 0;
    auto net = sampling::eps_net_with_at_least(manifold, eo, static_cast<std::size_t>(m + 2), &halvings);
    std::string net_eps = params.constants.eps.value().text;
    if (halvings > 0) net_eps = "(" + net_eps + ")/" + std::to_string(1L << halvings);
    manifold::check_sample_on_manifold(manifold, net.points, a.manifold);
    input = std::move(net.points);
    input_text = "eps-net of " + manifold.spec().name + " (delcert sample --eps " + net_eps + " --seed " + std::to_string(a.seed) + ")";
  }

  // The progress line: one phase per round (points, and the configurations pending per rule), its
  // count the stars being recomputed.
  io::ProgressLine progress = io::ProgressLine::on_stderr();
  if (progress.terminal()) {
    params.progress = [&progress](const refine::RefineProgress& p) { progress.phase(round_progress_label(p)); };
    params.star_progress = [&progress](std::size_t done, std::size_t total) { progress.update(done, total); };
  }
  progress.phase("stars of the " + std::to_string(input.size()) + " input points");
  refine::RefineResult result;
  try {
    result = refine::refine(manifold, input, params);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(a.points.empty() ? std::string("delcert refine") : a.points, 0, e.what());
  } catch (const std::domain_error& e) {
    throw io::InputError(a.points.empty() ? std::string("delcert refine") : a.points, 0, e.what());
  }
  progress.clear();

  refine::OutputContext ctx;
  ctx.manifold = manifold.spec().name;
  ctx.manifold_source = manifold.spec().source;
  ctx.input = input_text;
  refine::write_refine_output(a.out, result, ctx);
  if (!a.mesh_out.empty()) io::write_file_atomically(a.mesh_out, mesh_out_text(a.mesh_out, result.points, result.complex));

  const auto& f = result.final;
  std::printf("manifold           %s (m = %d, N = %d)\n", manifold.spec().name.c_str(), m, N);
  std::printf("mode               %s\n", refine::to_string(params.mode));
  const refine::Constants& used = result.parameters.constants;
  std::printf("eps                %s%s\n", used.eps.value().text.c_str(),
              result.eps_derived ? " (derived from the input's largest R_p)" : "");
  if (params.sizing.kind == refine::SizingKind::curvature) {
    const auto& sz = result.parameters.sizing;
    double lo = INFINITY, hi = 0;
    for (double e : result.local_eps) lo = std::min(lo, e), hi = std::max(hi, e);
    std::printf("sizing             curvature: eps(x) = min(eps, max(%s, %s / kappa_max(x))); eps(p) in [%.4g, %.4g] -> eps.txt\n",
                sz.floor->text.c_str(), sz.c.text.c_str(), lo, hi);
  }
  std::printf("points             %zu input + %zu inserted = %zu\n", result.input_size, result.points.size() - result.input_size,
              result.points.size());
  for (refine::Rule rule : refine::kRules)
    if (const auto& s = result.rules[rule]; s.inserted || s.failures)
      std::printf("  %-16s %zu inserted (%zu failures, %.3f s)\n", refine::to_string(rule), s.inserted, s.failures, s.seconds);
  std::printf("rounds             %zu\n", result.rounds);
  if (!result.eps_sites.empty()) {
    std::size_t below = 0;
    for (double e : result.local_eps) below += e < refine::as_doubles(used).eps;
    std::printf("local eps          down to eps/2^%d near %zu sites (%zu points below eps; report.json: local_eps)\n",
                result.eps_level, result.eps_sites.size(), below);
  }
  if (result.del_m.checked)
    std::printf("Del_M check        %zu repair rounds, %zu places left (%s; %.3f s)\n", result.repair_rounds, result.del_m.breaks,
                result.del_m.intrinsic_computed ? "Del_TM, Del_RM and Del_M compared"
                                                : ("Del_M not computed: " + result.del_m.intrinsic_reason).c_str(),
                result.del_m.seconds);
  std::printf("converged          %s (%s)\n", result.converged ? "yes" : "NO", refine::to_string(result.stop_reason));
  if (result.stall) std::printf("stalled            %s\n", refine::describe_stall(*result.stall).c_str());
  if (!result.converged) std::printf("advice             %s (exit status 4)\n", refine::advice(result.stop_reason));
  if (params.mode == refine::RefineMode::paper)
    std::printf("assessment         %s\n", refine::paper_mode_assessment(result).c_str());
  std::printf("inconsistent       %zu simplices in %zu stars\n", f.inconsistent_simplices, f.inconsistent_stars);
  std::printf("min thickness      %.4g (min face ratio to Gamma0^j: %.4g)\n", f.min_thickness, f.min_face_thickness_ratio);
  std::printf("min protection     %.4g (ratio to delta-check^2: %.4g)\n", f.min_protection, f.min_protection_ratio);
  // The smallest local ε: ε / 2^eps_level, and under curvature sizing the field's smallest value.
  const bool curvature = params.sizing.kind == refine::SizingKind::curvature;
  double eps_min = std::ldexp(refine::as_doubles(used).eps, -result.eps_level);
  if (curvature) eps_min = std::min(eps_min, f.min_local_eps);
  std::printf("min distance       %.4g (%s/9 = %.4g; %zu sparsity violations)\n", f.min_distance,
              result.eps_level > 0 || curvature ? "eps_min" : "eps", refine::mu0_times(eps_min),
              result.sparsity_violations.size());
  // Wall-clock time of the whole command (printed only; the outputs carry the refiner's own times).
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("time               %.3f s (%.3f s refining) -> %s\n", total, result.total_seconds, a.out.c_str());
  if (!a.mesh_out.empty()) std::printf("mesh               %s\n", a.mesh_out.c_str());
  if (!result.converged) return kExitNotConverged;
  if (!result.parameters.intrinsic_check.value_or(false)) return kExitOk;
  return certify_output(a, result.parameters.threads) ? kExitOk : kExitNotCertified;
}

}  // namespace

Command add_refine_command(CLI::App& app) {
  auto args = std::make_shared<RefineArgs>();
  auto* sub = app.add_subcommand("refine", "refine a sample of M until its tangential complex is thick, protected and consistent");
  sub->add_option("--manifold", args->manifold, manifold_option_help())->required();
  sub->add_option("--points", args->points, "input points on M (delcert-points, OFF or nOFF); without it, an eps-net");
  sub->add_option("--eps", args->eps,
                  "sampling radius eps (exact decimal or fraction); required without --points; with --points, default: "
                  "two significant digits above the input's largest R_p");
  sub->add_option("--mode", args->mode, "practical (default: ends consistent and protected) or paper (Algorithm 1 exactly)")
      ->check(CLI::IsMember({"practical", "paper"}))
      ->capture_default_str();
  sub->add_option("--gamma0", args->gamma0, "thickness bound Gamma0: every j-face needs thickness >= Gamma0^j")->capture_default_str();
  sub->add_option("--alpha", args->alpha, "picking ratio alpha: picking region B(c_p, alpha R_p)")->capture_default_str();
  sub->add_option("--beta", args->beta, "hitting-set radius ratio beta")->capture_default_str();
  sub->add_option("--delta0", args->delta0,
                  "protection ratio delta0: claimed protection delta0^2 (eps_min/9)^2, eps_min the smallest local eps (default: Gamma0^ceil((m+1)/2), "
                  "the largest power of Gamma0 allowed by the paper's H3)");
  sub->add_option("--sizing", args->sizing,
                  "sizing field: uniform (one eps) or curvature: eps(x) = min(eps, max(floor, c / kappa_max(x))), "
                  "claims.json v3 with eps(p) per point in eps.txt")
      ->check(CLI::IsMember({"uniform", "curvature"}))
      ->capture_default_str();
  sub->add_option("--sizing-c", args->sizing_c,
                  "curvature sizing: eps(x) <= c / kappa_max(x) (exact rational; 0.5 keeps a star's tangent planes "
                  "within ~30 degrees; default 0.5)");
  sub->add_option("--eps-floor", args->eps_floor, "curvature sizing: the field's lower bound (exact rational; default eps/10)");
  sub->add_option("--seed", args->seed, "random seed (same inputs and seed, same output bytes)")
      ->capture_default_str()
      ->transform(whole_number("a seed", std::numeric_limits<std::uint64_t>::max()));
  sub->add_option("--threads", args->threads, threads_help())->capture_default_str()->transform(thread_count());
  sub->add_option("--max-points", args->max_points,
                  "cap on the total number of points, input and inserted (0: the default); exit 4 with the partial "
                  "output when hit")
      ->capture_default_str()
      ->transform(whole_number("a point count", std::numeric_limits<std::size_t>::max()));
  sub->add_option("--max-inserted", args->max_inserted,
                  "cap on inserted points (0: none in practical mode, 20 x input + 20000 in paper mode); exit 4 when hit")
      ->capture_default_str()
      ->transform(whole_number("a point count", std::numeric_limits<std::size_t>::max()));
  sub->add_option("--max-rounds", args->max_rounds,
                  "cap on refinement rounds (0: none in practical mode, 2000 in paper mode); exit 4 when hit")
      ->capture_default_str()
      ->transform(whole_number("a round count", std::numeric_limits<std::size_t>::max()));
  sub->add_flag("--no-restricted-check", args->no_restricted_check,
                "practical mode: do not refine the simplices that are not restricted Delaunay with a margin (rule "
                "not_restricted); faster, but Del_TM may then differ from Del_RM (certifier check 13)");
  sub->add_flag("--no-intrinsic-check", args->no_intrinsic_check,
                "practical mode: do not compare the complex with Del_RM and Del_M (rule not_intrinsic) and do not "
                "certify the output at the end; faster, but certifier checks 13-15 may then fail");
  sub->add_flag("--intrinsic-check", args->intrinsic_check,
                "paper mode: also apply rule not_intrinsic (points only inside the paper's picking regions) and "
                "certify the output at the end");
  sub->add_option("--max-repair-rounds", args->max_repair_rounds,
                  "cap on Del_M repair rounds (rule not_intrinsic); exit 4 when the complexes still differ after the "
                  "last one (0: check once, repair nothing)")
      ->capture_default_str()
      ->transform(whole_number("a round count", std::numeric_limits<std::size_t>::max()));
  sub->add_flag("--look-ahead", args->look_ahead,
                "practical mode: Pick_valid also rejects candidates whose own star would be open, big or Gamma0-bad "
                "(computed before inserting them; docs/refinement.md, \"Look-ahead\")");
  sub->add_option("--out", args->out, "output directory (created if missing)")->required();
  sub->add_option("--mesh-out", args->mesh_out, kMeshOutHelp);
  return {sub, [args] { return run_refine(*args); }};
}

}  // namespace delcert::app
