// delcert tangential --manifold SPEC --points POINTS --out COMPLEX [--stats STATS.json] [--mesh-out MESH.off|MESH.ply]
//                    [--threads T]
//
// Builds the tangential Delaunay complex of the points (docs/design.md §3.2) with T_p = p + ker J_F(p),
// writes the union of the stars (maximal simplices, sorted) and, on request, a JSON summary.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/app/command.hpp"
#include "core/manifold/manifold.hpp"
#include "core/tangential/complex_topology.hpp"
#include "core/support/parallel.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::app {

namespace {

struct TangentialArgs {
  std::string manifold, points, out, stats, mesh_out;
  int threads = 0;
};

class Stopwatch {
 public:
  double lap() {
    auto now = std::chrono::steady_clock::now();
    double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

int run_tangential(const TangentialArgs& a) {
  Stopwatch clock;
  nlohmann::ordered_json times;
  // Every output path is checked before any work, and every output is written at the end, all
  // or nothing: a bad --stats must not leave a fresh --out behind.
  io::check_output_path(a.out, "--out", {a.manifold, a.points}, {a.stats, a.mesh_out});
  if (!a.stats.empty()) io::check_output_path(a.stats, "--stats", {a.manifold, a.points}, {a.out, a.mesh_out});
  if (!a.mesh_out.empty()) check_mesh_out(a.mesh_out, {a.manifold, a.points}, {a.out, a.stats});
  manifold::Manifold manifold(io::read_spec(a.manifold));
  const int m = manifold.intrinsic_dimension(), N = manifold.ambient_dimension();
  if (m < 2 || m > 4)
    throw io::InputError(manifold.spec().source, 0,
                         "intrinsic dimension " + std::to_string(m) +
                             ": the tangential complex is implemented for m = 2, 3 and 4");
  if (!a.mesh_out.empty()) check_mesh_dimensions(a.mesh_out, m, N);
  io::PointReadOptions read_options;
  read_options.expected_dimension = N;
  io::PointSet points = io::read_points(a.points, read_options);
  manifold::check_on_manifold(manifold, points, a.points);
  times["read"] = clock.lap();

  const int threads = support::resolve_threads(a.threads);
  io::ProgressLine progress = io::ProgressLine::on_stderr();
  progress.phase("tangent planes");
  tangential::TangentPlanes planes;
  try {
    planes = tangential::compute_tangent_planes(manifold, points, threads);
  } catch (const std::domain_error& e) {
    throw io::InputError(a.points, 0, e.what());
  }
  times["tangent_planes"] = clock.lap();

  tangential::StarOptions options;
  options.threads = threads;
  if (progress.terminal()) options.progress = [&progress](std::size_t done, std::size_t total) { progress.update(done, total); };
  progress.phase("stars", points.size());
  tangential::StarStats star_stats;
  tangential::TangentialComplex complex;
  try {
    complex = tangential::TangentialComplex(points, planes, options, &star_stats);
  } catch (const std::invalid_argument& e) {  // e.g. two identical points
    throw io::InputError(a.points, 0, e.what());
  }
  times["stars"] = clock.lap();

  progress.phase("assembling the complex");
  tangential::Assembly assembly = complex.assemble(threads);
  times["assemble"] = clock.lap();
  progress.phase("topology");
  tangential::ComplexTopology topology = tangential::analyze_complex(assembly.complex);
  times["analyze"] = clock.lap();
  progress.clear();

  std::vector<std::pair<std::string, std::string>> outputs{{a.out, io::format_complex(assembly.complex)}};
  if (!a.mesh_out.empty()) outputs.emplace_back(a.mesh_out, mesh_out_text(a.mesh_out, points, assembly.complex));
  times["write_complex"] = clock.lap();  // formatting; the files are written together below

  const double max_radius = std::sqrt(star_stats.max_radius2);
  const bool consistent = assembly.inconsistent.empty();
  if (!a.stats.empty()) {
    nlohmann::ordered_json j;
    j["format"] = "delcert-tangential-stats v1";
    j["manifold"] = manifold.spec().name;
    j["points_file"] = a.points;
    j["points"] = points.size();
    j["intrinsic_dimension"] = m;
    j["ambient_dimension"] = N;
    j["threads"] = threads;
    j["star_simplices"] = assembly.star_cells;
    j["stars"] = {{"power_cell", star_stats.stars - star_stats.fallbacks},
                  {"regular_triangulation_fallback", star_stats.fallbacks},
                  {"not_closed", star_stats.open},
                  {"neighbours_mean", points.size() ? double(star_stats.neighbours_total) / points.size() : 0.0},
                  {"neighbours_max", star_stats.neighbours_max}};
    j["maximal_simplices"] = {{"total", assembly.complex.simplices.size()},
                              {"by_dimension", topology.maximal_by_dimension}};
    j["faces_by_dimension"] = topology.faces_by_dimension;
    j["euler_characteristic"] = topology.euler_characteristic;
    if (manifold.spec().expected.euler_characteristic)
      j["expected_euler_characteristic"] = *manifold.spec().expected.euler_characteristic;
    j["consistent"] = consistent;
    j["inconsistent_simplices"] = {{"count", assembly.inconsistent.size()}, {"simplices", assembly.inconsistent}};
    j["pure"] = topology.pure;
    j["pseudomanifold"] = topology.pseudomanifold;
    j["ridges"] = {{"total", topology.ridges},
                   {"in_one_simplex", topology.boundary_ridges},
                   {"in_three_or_more", topology.singular_ridges}};
    j["strongly_connected_components"] = topology.components;
    j["max_radius"] = max_radius;
    times["write_stats"] = clock.lap();
    j["time_seconds"] = times;
    outputs.emplace_back(a.stats, j.dump(2) + "\n");
  }
  io::write_files_atomically(outputs);

  std::printf("manifold           %s (m = %d, N = %d)\n", manifold.spec().name.c_str(), m, N);
  std::printf("points             %zu\n", points.size());
  std::printf("star simplices     %zu (%zu stars by the regular-triangulation fallback, %zu not closed)\n",
              assembly.star_cells, star_stats.fallbacks, star_stats.open);
  std::printf("maximal simplices  %zu -> %s\n", assembly.complex.simplices.size(), a.out.c_str());
  if (!a.mesh_out.empty()) std::printf("mesh               %s\n", a.mesh_out.c_str());
  std::printf("inconsistent       %zu\n", assembly.inconsistent.size());
  std::printf("pseudomanifold     %s (pure: %s)\n", topology.pseudomanifold ? "yes" : "no", topology.pure ? "yes" : "no");
  std::printf("Euler char.        %ld\n", topology.euler_characteristic);
  std::printf("max R_p            %.6g\n", max_radius);
  return kExitOk;
}

}  // namespace

Command add_tangential_command(CLI::App& app) {
  auto args = std::make_shared<TangentialArgs>();
  auto* sub = app.add_subcommand("tangential", "build the tangential Delaunay complex of a point set on M");
  sub->add_option("--manifold", args->manifold, manifold_option_help())->required();
  sub->add_option("--points", args->points, "input points (delcert-points, OFF or nOFF), on M")->required();
  sub->add_option("--out", args->out, "output complex: maximal simplices, sorted (written atomically)")->required();
  sub->add_option("--mesh-out", args->mesh_out, kMeshOutHelp);
  sub->add_option("--stats", args->stats, "also write a JSON summary (counts, consistency, topology, timings)");
  sub->add_option("--threads", args->threads, threads_help())->capture_default_str()->transform(thread_count());
  return {sub, [args] { return run_tangential(*args); }};
}

}  // namespace delcert::app
