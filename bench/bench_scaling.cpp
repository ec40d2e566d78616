// The scaling curve of issue 14: wall time, peak memory and µs per point of each program against n.
//
//   bench_scaling [--cases NAME:N,...] [--programs sample,tangential,refine,certify] [--threads T]
//                 [--restricted-up-to N] [--refine-up-to N] [--gudhi-up-to N] [--seed S] [--bin DIR]
//                 [--keep DIR]
//
// Default cases: sphere-2 at 10k, 100k and 1M points and clifford-torus-3 at 10k and 100k (the
// issue's set); programs: all four; threads 2.
//
// Inputs. `delcert sample` builds an eps-net from a dense sample of 30 points per net point, capped
// at 4M dense points (core/sampling), so it cannot give 1M points; the curve therefore runs on one
// generator at every size, a seeded jittered grid (spaced_points below: well spaced like an eps-net
// or a mesher's vertices, in O(n); uniform random points would not do: their largest empty ball,
// hence check 7's neighbourhood of 5 max R_p, grows like log n), written as a delcert-points file.
// Each program is then run as a child process exactly as a user runs it, and wait4's rusage gives
// its CPU time and peak resident size (ru_maxrss):
//   sample      `delcert sample --eps E`, E chosen for about n net points (one guess, n ~ eps^-m);
//               skipped where its dense sample would pass the 4M cap (its own input check);
//   tangential  `delcert tangential --points P --out C` on the generated points;
//   refine      `delcert refine --points S` on the sample's eps-net (its realistic input), only
//               for n <= --refine-up-to (default 10000: its per-point cost grows with the
//               defects it repairs, and the 100k runs take minutes);
//   certify     `delcert-certify --points P --complex C` (the Del_TM checks 1-10; its phase times
//               are copied from the certificate), with
//               --skip-restricted above --restricted-up-to (default 10000: the restricted Voronoi
//               diagram and Del_M, checks 11-15, cost 10-50x the tangential complex).
// GUDHI: for each case with n <= --gudhi-up-to (default 100000) bench_tangential (next to this
// program) runs once with the same n, seed and threads (on its own input: uniform random points and
// the same tangent planes for both sides), and its stars+assembly speed-up over GUDHI and the peak
// memory ratio are reported beside the curve.
//
// --mpi-ranks K (with delcert-certify built with -DDELCERT_MPI=ON; --mpiexec, default mpirun): for
// each certify case also `delcert-certify --threads 1` and `MPIEXEC -n K delcert-certify --threads 1`
// (--no-times both), their wall times, the peak resident size of each rank (every rank runs under
// this program as a wrapper, --wrap-rank-rss, which wait4s it) and whether the two certificates
// are the same bytes.
//
// --keep DIR: write the inputs and outputs (points, complexes, certificates) to DIR and keep them.
//
// Output: one JSON document on standard output; the table (µs per point, MB, bytes per point, and
// the linearity ratio: µs per point at the largest n / µs per point at the smallest n of each
// manifold, against the 1.2; for certify the Del_TM checks alone: each run less the phases of
// checks 11-15, which run only up to --restricted-up-to) and the targets for 1M points at m = 2 (certify < 60 s,
// < 1.5 GB) on standard error, after the progress lines.
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/sampling/sampling.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

extern char** environ;

namespace {

using namespace delcert;
using json = nlohmann::ordered_json;

struct Case {
  std::string manifold;
  std::size_t count = 0;
};

struct Run {
  double wall = 0, cpu = 0, rss_mb = 0;
  int status = -1;
};

// Runs argv as a child process (output to /dev/null, or to `out` if given), returning its wall
// time, CPU time (user + system) and peak resident size, all from this child alone.
Run run(const std::vector<std::string>& args, const std::string& out = "/dev/null") {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  Run r;
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(), environ) != 0) {  // (p: mpirun from PATH)
    posix_spawn_file_actions_destroy(&fa);
    return r;
  }
  posix_spawn_file_actions_destroy(&fa);
  int status = 0;
  rusage u{};
  wait4(pid, &status, 0, &u);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  r.rss_mb = double(u.ru_maxrss) / 1024.0;  // KiB on Linux
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::size_t count_points(const std::string& path) {
  std::ifstream f(path);
  std::string tag;
  std::getline(f, tag);
  int dim = 0;
  std::size_t n = 0;
  f >> dim >> n;
  return n;
}

// Well-spaced points at any n, in O(n) (delcert sample's farthest-point eps-net is capped at
// about 133k points): a jittered grid, each grid point moved uniformly within +-0.3 of its cell, so
// that neighbours stay at least 0.4 cells apart and no hole is wider than 1.6 cells.
//   sphere-2: rings at colatitudes h apart (h^2 = 4 pi / n), each with about 2 pi sin(t) / h points at
//             equal angles;
//   clifford-torus-3 (any product of circles): a k^m grid of angles.
// Other manifolds: n points uniform by volume (sampling::sample_manifold).
io::PointSet spaced_points(const manifold::Manifold& M, const std::string& name, std::size_t n, std::uint64_t seed) {
  sampling::Random random(seed);
  io::PointSet P;
  P.dimension = M.ambient_dimension();
  const double two_pi = 2 * M_PI, jitter = 0.3;
  auto shake = [&] { return random.uniform(-jitter, jitter); };
  if (name == "sphere-2") {
    const double h = std::sqrt(4 * M_PI / double(n));  // cell area h^2 = 4 pi / n
    const auto rings = static_cast<std::size_t>(std::lround(M_PI / h));
    for (std::size_t b = 0; b < rings; ++b) {
      const double t = (double(b) + 0.5) * M_PI / double(rings);  // colatitude of the ring
      const auto k = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(two_pi * std::sin(t) / h)));
      for (std::size_t i = 0; i < k; ++i) {
        const double u = t + shake() * M_PI / double(rings), a = (double(i) + 0.5 + shake()) * two_pi / double(k);
        P.push_back(std::vector<double>{std::sin(u) * std::cos(a), std::sin(u) * std::sin(a), std::cos(u)});
      }
    }
  } else if (name.rfind("clifford-torus-", 0) == 0) {
    const int m = M.intrinsic_dimension();
    const auto k = static_cast<std::size_t>(std::lround(std::pow(double(n), 1.0 / m)));
    std::vector<std::size_t> idx(m, 0);
    std::vector<double> x(2 * m);
    for (bool more = true; more;) {
      for (int c = 0; c < m; ++c) {  // radius 1 on every circle (the built-ins)
        const double a = (double(idx[c]) + 0.5 + shake()) * two_pi / double(k);
        x[2 * c] = std::cos(a), x[2 * c + 1] = std::sin(a);
      }
      P.push_back(x);
      int c = m - 1;
      while (c >= 0 && ++idx[c] == k) idx[c--] = 0;
      more = c >= 0;
    }
  } else {
    sampling::sample_manifold(M, n, random, P);
  }
  return P;
}

json entry(const Run& r, std::size_t n) {
  json e;
  e["exit"] = r.status;
  e["wall_s"] = r.wall;
  e["cpu_s"] = r.cpu;
  e["peak_rss_mb"] = r.rss_mb;
  e["points"] = n;
  e["us_per_point_wall"] = n ? 1e6 * r.wall / double(n) : 0;
  e["us_per_point_cpu"] = n ? 1e6 * r.cpu / double(n) : 0;
  e["bytes_per_point"] = n ? r.rss_mb * 1048576.0 / double(n) : 0;
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases = {{"sphere-2", 10000}, {"sphere-2", 100000}, {"sphere-2", 1000000},
                             {"clifford-torus-3", 10000}, {"clifford-torus-3", 100000}};
  std::vector<std::string> programs = {"sample", "tangential", "refine", "certify"};
  int threads = 2;
  std::size_t restricted_up_to = 10000, refine_up_to = 10000, gudhi_up_to = 100000;
  std::uint64_t seed = 1;
  int mpi_ranks = 0;
  std::string mpiexec = "mpirun";
  std::filesystem::path bin = std::filesystem::canonical("/proc/self/exe").parent_path().parent_path(), keep;
  // One MPI rank, wrapped (see --mpi-ranks): runs the command and writes its peak resident size in
  // MB to PREFIX.RANK (the rank from Open MPI's, PMI's or Slurm's environment); exits with its status.
  if (argc > 3 && std::string(argv[1]) == "--wrap-rank-rss") {
    const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank) rank = std::getenv("PMI_RANK");
    if (!rank) rank = std::getenv("SLURM_PROCID");
    const Run r = run(std::vector<std::string>(argv + 3, argv + argc));
    std::ofstream(std::string(argv[2]) + "." + (rank ? rank : "0")) << r.rss_mb << "\n";
    return r.status < 0 ? 3 : r.status;
  }
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::printf("bench_scaling [--cases NAME:N,...] [--programs sample,tangential,refine,certify] [--threads T]\n"
                    "              [--restricted-up-to N] [--refine-up-to N] [--gudhi-up-to N] [--seed S] [--bin DIR] [--keep DIR]\n");
        return 0;
      }
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--cases") {
        cases.clear();
        for (const auto& item : split(v)) {
          const auto colon = item.find(':');
          if (colon == std::string::npos) throw std::invalid_argument("a case is NAME:N, got '" + item + "'");
          cases.push_back({item.substr(0, colon), std::stoul(item.substr(colon + 1))});
        }
      } else if (a == "--programs") programs = split(v);
      else if (a == "--threads") threads = std::stoi(v);
      else if (a == "--restricted-up-to") restricted_up_to = std::stoul(v);
      else if (a == "--refine-up-to") refine_up_to = std::stoul(v);
      else if (a == "--gudhi-up-to") gudhi_up_to = std::stoul(v);
      else if (a == "--seed") seed = std::stoull(v);
      else if (a == "--bin") bin = v;
      else if (a == "--keep") keep = v;
      else if (a == "--mpi-ranks") mpi_ranks = std::stoi(v);
      else if (a == "--mpiexec") mpiexec = v;
      else throw std::invalid_argument("unknown option " + a);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scaling: %s\n", e.what());
    return 2;
  }
  auto wants = [&](const std::string& p) { return std::find(programs.begin(), programs.end(), p) != programs.end(); };
  const std::string producer = (bin / "delcert").string(), checker = (bin / "delcert-certify").string(),
                    gudhi_bench = (bin / "bench" / "bench_tangential").string();
  const std::string T = std::to_string(threads);
  const auto dir = !keep.empty() ? keep : std::filesystem::temp_directory_path() / ("delcert-bench-scaling-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  json doc;
  doc["benchmark"] = "scaling: sample, tangential, refine, certify against n (issue 14)";
  doc["threads"] = threads;
  doc["seed"] = seed;
  doc["input"] = "a seeded jittered grid (about n points), one generator at every n";
  double load[1] = {0};
  doc["load_average_at_start"] = getloadavg(load, 1) == 1 ? load[0] : -1.0;
  doc["cases"] = json::array();

  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const std::string tag = dir / ("case-" + std::to_string(k));
    const std::string spec = "builtin:" + c.manifold, points = tag + ".points", cx = tag + ".complex",
                      cert = tag + ".json", net = tag + ".net", refined = tag + ".refined";
    manifold::Manifold manifold(io::read_spec(spec));
    const int m = manifold.intrinsic_dimension();
    json e;
    e["manifold"] = c.manifold;
    e["m"] = m;
    const std::size_t n = [&] {
      const io::PointSet p = spaced_points(manifold, c.manifold, c.count, seed);
      io::write_points(points, p);
      return p.size();
    }();
    e["points"] = n;
    if (wants("sample")) {
      // One guess of eps for about n net points (the row reports the count it gave).
      sampling::EpsNetOptions o;
      // Measured: an eps-net of S^2 has about area / (1.74 eps^2) points; of T^3 about volume / (2 eps^3).
      const double volume = c.manifold == "sphere-2" ? 4 * M_PI : c.manifold == "clifford-torus-3" ? 8 * M_PI * M_PI * M_PI : 2 * M_PI * M_PI;
      o.eps = m == 2 ? std::sqrt(volume / (1.74 * double(c.count))) : std::cbrt(volume / (2 * double(c.count)));
      const double dense = o.oversampling * double(c.count);
      if (dense > double(o.max_dense)) {
        e["sample"] = json{{"skipped", "its dense sample (30 points per net point) would pass the 4M cap"}};
      } else {
        std::fprintf(stderr, "bench_scaling: %s %zu: delcert sample\n", c.manifold.c_str(), c.count);
        char eps[64];
        std::snprintf(eps, sizeof eps, "%.6g", o.eps);
        const Run r = run({producer, "sample", "--manifold", spec, "--eps", eps, "--seed", std::to_string(seed), "--out", net});
        e["sample"] = entry(r, count_points(net));
        e["sample"]["eps"] = eps;
      }
    }
    if (wants("tangential")) {
      std::fprintf(stderr, "bench_scaling: %s %zu: delcert tangential\n", c.manifold.c_str(), c.count);
      e["tangential"] = entry(run({producer, "tangential", "--manifold", spec, "--points", points, "--out", cx, "--threads", T}), n);
    }
    if (wants("refine")) {
      if (c.count > refine_up_to) e["refine"] = json{{"skipped", "n > --refine-up-to"}};
      else if (!std::filesystem::exists(net)) e["refine"] = json{{"skipped", "no eps-net from delcert sample"}};
      else {
        std::fprintf(stderr, "bench_scaling: %s %zu: delcert refine\n", c.manifold.c_str(), c.count);
        const Run r = run({producer, "refine", "--manifold", spec, "--points", net, "--out", refined, "--threads", T});
        e["refine"] = entry(r, count_points(net));
        e["refine"]["points_out"] = count_points(refined + "/points.txt");
      }
    }
    if (wants("certify") && std::filesystem::exists(cx)) {
      const bool skip = c.count > restricted_up_to;  // the case size asked for (the grid gives about n)
      std::fprintf(stderr, "bench_scaling: %s %zu: delcert-certify%s\n", c.manifold.c_str(), c.count,
                   skip ? " --skip-restricted" : "");
      std::vector<std::string> args = {checker, "--manifold", spec, "--points", points, "--complex", cx,
                                       "--threads", T, "--out", cert};
      if (skip) args.push_back("--skip-restricted");
      const Run r = run(args);
      e["certify"] = entry(r, n);
      e["certify"]["skip_restricted"] = skip;
      try {
        std::ifstream f(cert);
        const json certificate = json::parse(f);
        e["certify"]["verdict"] = certificate.at("verdict");
        const json& t = certificate.at("times_seconds");
        e["certify"]["phases_s"] = t;
        // The Del_TM checks alone (the run less checks 11-15's phases), for a like-for-like curve.
        const double wall = r.wall - t.value("restricted_delaunay", 0.0) - t.value("intrinsic_delaunay", 0.0),
                     cpu = r.cpu - t.value("restricted_delaunay_cpu", 0.0) - t.value("intrinsic_delaunay_cpu", 0.0);
        e["certify"]["del_tm_us_per_point_wall"] = 1e6 * wall / double(n);
        e["certify"]["del_tm_us_per_point_cpu"] = 1e6 * cpu / double(n);
      } catch (const std::exception& ex) {
        e["certify"]["verdict"] = std::string("no certificate: ") + ex.what();
      }
      if (mpi_ranks > 0) {
        std::fprintf(stderr, "bench_scaling: %s %zu: delcert-certify on 1 process and on %d MPI ranks, 1 thread each\n",
                     c.manifold.c_str(), c.count, mpi_ranks);
        const std::string rss_prefix = cert + ".rss";  // each rank's peak, written by its wrapper (above)
        std::vector<std::string> one = args, many = {mpiexec, "-n", std::to_string(mpi_ranks),
                                                      std::filesystem::canonical("/proc/self/exe").string(),
                                                      "--wrap-rank-rss", rss_prefix};
        one[std::find(one.begin(), one.end(), "--threads") - one.begin() + 1] = "1";
        one.insert(one.begin() + 1, "--no-times");
        many.insert(many.end(), one.begin(), one.end());
        *std::find(many.begin(), many.end(), cert) = cert + ".mpi";
        *std::find(one.begin(), one.end(), cert) = cert + ".one";
        const Run a = run(one), b = run(many);
        const auto bytes = [](const std::string& f) { std::ifstream in(f, std::ios::binary); return std::string(std::istreambuf_iterator<char>(in), {}); };
        json per_rank = json::array();
        for (int r = 0; r < mpi_ranks; ++r) {
          const std::string f = rss_prefix + "." + std::to_string(r);
          double mb = -1;
          std::ifstream(f) >> mb;
          per_rank.push_back(mb);
          std::filesystem::remove(f);
        }
        e["certify_mpi"] = json{{"ranks", mpi_ranks}, {"one_process_wall_s", a.wall}, {"ranks_wall_s", b.wall},
                                {"speedup", b.wall > 0 ? a.wall / b.wall : 0.0}, {"one_process_peak_rss_mb", a.rss_mb},
                                {"rank_peak_rss_mb", per_rank}, {"exit", {a.status, b.status}},
                                {"certificates_identical", a.status == b.status && bytes(cert + ".one") == bytes(cert + ".mpi")}};
        std::filesystem::remove(cert + ".one"), std::filesystem::remove(cert + ".mpi");
      }
    }
    if (c.count <= gudhi_up_to && std::filesystem::exists(gudhi_bench)) {
      std::fprintf(stderr, "bench_scaling: %s %zu: bench_tangential (GUDHI)\n", c.manifold.c_str(), c.count);
      const std::string out = tag + ".gudhi.json";
      run({gudhi_bench, "--cases", c.manifold + ":" + std::to_string(c.count), "--reps", "1", "--threads", T,
           "--seed", std::to_string(seed)},
          out);
      try {
        std::ifstream f(out);
        const json g = json::parse(f).at("cases").at(0);
        e["gudhi"]["speedup_total"] = g.at("speedup_total");
        e["gudhi"]["peak_memory_ratio_gudhi_over_delcert"] = g.at("peak_memory_ratio_gudhi_over_delcert");
      } catch (const std::exception& ex) {
        e["gudhi"] = json{{"error", ex.what()}};
      }
    }
    if (keep.empty()) {
      std::filesystem::remove_all(refined);
      for (const auto& f : {points, cx, cert, net}) std::filesystem::remove(f);
    }
    doc["cases"].push_back(e);
  }
  if (keep.empty()) std::filesystem::remove_all(dir);
  doc["load_average_at_end"] = getloadavg(load, 1) == 1 ? load[0] : -1.0;

  // Linearity: per manifold and program, µs per point (wall) at the largest n over the smallest n.
  json linear = json::object();
  std::map<std::string, std::pair<const json*, const json*>> ends;  // manifold/program -> (smallest, largest)
  for (const auto& e : doc["cases"])
    for (const auto& p : programs) {
      if (!e.contains(p) || !e[p].contains("us_per_point_wall") || e[p]["exit"] == 2 || e[p]["exit"] == -1) continue;
      auto& [lo, hi] = ends[e["manifold"].get<std::string>() + "/" + p];
      if (!lo || e[p]["points"] < (*lo)["points"]) lo = &e[p];
      if (!hi || e[p]["points"] > (*hi)["points"]) hi = &e[p];
    }
  for (const auto& [key, lh] : ends) {
    const json &lo = *lh.first, &hi = *lh.second;
    if (lo["points"] == hi["points"]) continue;
    json r;
    r["from_points"] = lo["points"];
    r["to_points"] = hi["points"];
    const std::string w = lo.contains("del_tm_us_per_point_wall") && hi.contains("del_tm_us_per_point_wall") ? "del_tm_" : "";
    if (!w.empty()) r["measure"] = "the Del_TM checks: each run less its checks 11-15 phases";
    r["ratio_wall"] = hi[w + "us_per_point_wall"].get<double>() / lo[w + "us_per_point_wall"].get<double>();
    r["ratio_cpu"] = hi[w + "us_per_point_cpu"].get<double>() / lo[w + "us_per_point_cpu"].get<double>();
    r["target"] = 1.2;
    r["met_cpu"] = r["ratio_cpu"].get<double>() <= 1.2;
    linear[key] = r;
  }
  doc["linearity"] = linear;

  // The table.
  std::fprintf(stderr, "\n%-17s %8s %-10s %9s %9s %9s %9s %8s %7s  %s\n", "manifold", "n", "program", "wall s", "cpu s",
               "us/pt", "cpu us/pt", "peak MB", "B/pt", "note");
  for (const auto& e : doc["cases"])
    for (const auto& p : programs) {
      if (!e.contains(p)) continue;
      const json& r = e[p];
      if (r.contains("skipped")) {
        std::fprintf(stderr, "%-17s %8zu %-10s %s\n", e["manifold"].get<std::string>().c_str(), e["points"].get<std::size_t>(),
                     p.c_str(), ("skipped: " + r["skipped"].get<std::string>()).c_str());
        continue;
      }
      std::string note = "exit " + std::to_string(r["exit"].get<int>());
      if (p == "certify") note += std::string(r["skip_restricted"].get<bool>() ? ", --skip-restricted" : ", all checks") +
                                  ", " + (r["verdict"].is_string() ? r["verdict"].get<std::string>() : "");
      if (p == "certify" && !r["skip_restricted"].get<bool>() && r.contains("del_tm_us_per_point_cpu"))
        note += ", Del_TM checks alone " + std::to_string(std::lround(r["del_tm_us_per_point_wall"].get<double>())) + " us/pt (" +
                std::to_string(std::lround(r["del_tm_us_per_point_cpu"].get<double>())) + " cpu)";
      if (p == "refine") note += ", " + std::to_string(r["points_out"].get<std::size_t>()) + " points out";
      if (p == "tangential" && e.contains("gudhi") && e["gudhi"].contains("speedup_total"))
        note += ", GUDHI/delcert time " + std::to_string(e["gudhi"]["speedup_total"].get<double>()).substr(0, 4) +
                "x, memory " + std::to_string(e["gudhi"]["peak_memory_ratio_gudhi_over_delcert"].get<double>()).substr(0, 4) + "x";
      std::fprintf(stderr, "%-17s %8zu %-10s %9.2f %9.2f %9.1f %9.1f %8.0f %7.0f  %s\n", e["manifold"].get<std::string>().c_str(),
                   r["points"].get<std::size_t>(), p.c_str(), r["wall_s"].get<double>(), r["cpu_s"].get<double>(),
                   r["us_per_point_wall"].get<double>(), r["us_per_point_cpu"].get<double>(), r["peak_rss_mb"].get<double>(),
                   r["bytes_per_point"].get<double>(), note.c_str());
    }
  std::fprintf(stderr, "\nlinearity (us/pt at the largest n / us/pt at the smallest; target <= 1.2):\n");
  for (const auto& [key, r] : linear.items())
    std::fprintf(stderr, "  %-30s %7zu -> %7zu  wall %.2f  cpu %.2f  %s\n", key.c_str(), r["from_points"].get<std::size_t>(),
                 r["to_points"].get<std::size_t>(), r["ratio_wall"].get<double>(), r["ratio_cpu"].get<double>(),
                 r["met_cpu"].get<bool>() ? "met" : "NOT met");
  for (const auto& e : doc["cases"])
    if (e["m"] == 2 && e["points"].get<std::size_t>() >= 1000000 && e.contains("certify") && e["certify"].contains("wall_s"))
      std::fprintf(stderr, "target at %zu points, m = 2: certify %.1f s (< 60 s on 2 cores: %s), %.0f MB (< 1536 MB: %s)\n",
                   e["points"].get<std::size_t>(), e["certify"]["wall_s"].get<double>(),
                   e["certify"]["wall_s"].get<double>() < 60 ? "met" : "NOT met", e["certify"]["peak_rss_mb"].get<double>(),
                   e["certify"]["peak_rss_mb"].get<double>() < 1536 ? "met" : "NOT met");
  for (const auto& e : doc["cases"])
    if (e.contains("certify_mpi")) {
      const json& r = e["certify_mpi"];
      std::string ranks;
      for (const auto& mb : r["rank_peak_rss_mb"]) ranks += (ranks.empty() ? "" : ", ") + std::to_string(std::lround(mb.get<double>()));
      std::fprintf(stderr, "certify on MPI ranks, %s %zu: 1 process %.1f s, %d ranks %.1f s (%.2fx); peak %.0f MB for the "
                   "process, MB per rank (rank 0 first): %s; certificates %s\n", e["manifold"].get<std::string>().c_str(),
                   e["points"].get<std::size_t>(), r["one_process_wall_s"].get<double>(), r["ranks"].get<int>(),
                   r["ranks_wall_s"].get<double>(), r["speedup"].get<double>(), r["one_process_peak_rss_mb"].get<double>(),
                   ranks.c_str(), r["certificates_identical"].get<bool>() ? "identical" : "DIFFERENT");
    }
  std::printf("%s\n", doc.dump(2).c_str());
  return 0;
}
