// The tangential complex, side by side with GUDHI 3.7's Tangential_complex (docs/design.md §11).
//
// Both sides get the same points (sample_manifold, seeded) and the same tangent planes
// (Manifold::frame; GUDHI through set_tangent_planes), and the same thread count (ours:
// StarOptions::threads; GUDHI: TBB limited by tbb::global_control). Each measurement runs in its
// own forked child, so that getrusage's peak resident size belongs to one side only; the child
// first builds the input (reported as input_rss_mb) and then times one side.
//
// Times are wall-clock medians (stars_s, finish_s) with the process CPU time beside them
// (stars_cpu_s: all threads; less sensitive to other load on the machine).
//
//   stars:     ours = neighbour index + every star;  GUDHI = constructor (kd-tree),
//              set_tangent_planes, compute_tangential_complex
//   finish:    ours = assemble (union of the stars and the consistency check);
//              GUDHI = number_of_inconsistent_simplices (its consistency check)
//
// Usage: bench_tangential [--cases NAME:COUNT,...] [--all] [--threads T] [--reps R] [--seed S]
// Default: sphere-2:10000,sphere-3:10000. --all: the five manifolds at 10000 and 50000 points.
// Prints one JSON document on stdout (medians over the repetitions); progress on stderr.
#include "bench/gudhi_input.hpp"

#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/sampling/sampling.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "io/spec.hpp"

namespace {

using namespace delcert;
using json = nlohmann::ordered_json;

struct Case {
  std::string manifold;
  std::size_t count = 0;
};

struct Input {
  io::PointSet points;
  tangential::TangentPlanes planes;
  int m = 0, N = 0;
};

Input make_input(const Case& c, std::uint64_t seed) {
  manifold::Manifold manifold(io::read_spec("builtin:" + c.manifold));
  sampling::Random random(seed);
  Input in;
  sampling::sample_manifold(manifold, c.count, random, in.points);
  in.planes = tangential::compute_tangent_planes(manifold, in.points, 1);
  in.m = manifold.intrinsic_dimension();
  in.N = manifold.ambient_dimension();
  return in;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU time of the whole process (all threads): less sensitive than wall time to other load.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // KiB on Linux
}

json run_delcert(const Input& in, int threads) {
  json r;
  r["input_rss_mb"] = peak_rss_mb();
  tangential::StarOptions options;
  options.threads = threads;
  auto t0 = std::chrono::steady_clock::now();
  double c0 = cpu_seconds();
  tangential::StarStats stats;
  tangential::TangentialComplex tc(in.points, in.planes, options, &stats);
  r["stars_s"] = seconds_since(t0);
  r["stars_cpu_s"] = cpu_seconds() - c0;
  auto t1 = std::chrono::steady_clock::now();
  double c1 = cpu_seconds();
  tangential::Assembly a = tc.assemble(threads);
  r["finish_s"] = seconds_since(t1);
  r["finish_cpu_s"] = cpu_seconds() - c1;
  r["peak_rss_mb"] = peak_rss_mb();
  // Cross-check figures, counted like GUDHI's number_of_inconsistent_simplices (with repetition).
  std::size_t inconsistent_in_stars = 0;
  for (const auto& star : tc.stars())
    for (std::size_t c = 0; c < star.size(); ++c) {
      std::vector<int> cell(star.cell(c).begin(), star.cell(c).end());
      inconsistent_in_stars += std::binary_search(a.inconsistent.begin(), a.inconsistent.end(), cell);
    }
  r["star_simplices"] = a.star_cells;
  r["inconsistent_in_stars"] = inconsistent_in_stars;
  r["fallback_stars"] = stats.fallbacks;
  return r;
}

template <int M>
json run_gudhi_m(const Input& in, int threads) {
  using TC = typename bench::GudhiInput<M>::TC;
  const bench::GudhiInput<M> gudhi(in.points, in.planes);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  json r;
  r["input_rss_mb"] = peak_rss_mb();
  auto t0 = std::chrono::steady_clock::now();
  double c0 = cpu_seconds();
  TC tc(gudhi.points, M, gudhi.kernel);
  tc.set_tangent_planes(gudhi.bases);
  tc.compute_tangential_complex();
  r["stars_s"] = seconds_since(t0);
  r["stars_cpu_s"] = cpu_seconds() - c0;
  auto t1 = std::chrono::steady_clock::now();
  double c1 = cpu_seconds();
  auto inc = tc.number_of_inconsistent_simplices();
  r["finish_s"] = seconds_since(t1);
  r["finish_cpu_s"] = cpu_seconds() - c1;
  r["peak_rss_mb"] = peak_rss_mb();
  r["star_simplices"] = inc.num_simplices;
  r["inconsistent_in_stars"] = inc.num_inconsistent_simplices;
  return r;
}

json run_gudhi(const Input& in, int threads) {
  switch (in.m) {
    case 2: return run_gudhi_m<2>(in, threads);
    case 3: return run_gudhi_m<3>(in, threads);
    default: throw std::runtime_error("the benchmark runs GUDHI for m = 2 and 3 only");
  }
}

// Runs one side in a forked child; returns its JSON (or {"error": ...}).
json measure(const Case& c, const std::string& side, int threads, std::uint64_t seed) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fd[0]);
    std::string out;
    try {
      Input in = make_input(c, seed);
      json r = side == "delcert" ? run_delcert(in, threads) : run_gudhi(in, threads);
      out = r.dump();
    } catch (const std::exception& e) {
      out = json{{"error", e.what()}}.dump();
    }
    const char* p = out.data();
    std::size_t left = out.size();
    while (left) {
      ssize_t w = write(fd[1], p, left);
      if (w <= 0) break;
      p += w, left -= static_cast<std::size_t>(w);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buf[4096];
  for (ssize_t r; (r = read(fd[0], buf, sizeof buf)) > 0;) text.append(buf, static_cast<std::size_t>(r));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || text.empty()) return json{{"error", "the child process failed (status " + std::to_string(status) + ")"}};
  return json::parse(text);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Medians over the repetitions of every numeric field.
json summarize(const std::vector<json>& reps, std::size_t count) {
  json out;
  if (reps.empty()) return out;
  for (const auto& r : reps)
    if (r.contains("error")) return r;
  for (auto it = reps[0].begin(); it != reps[0].end(); ++it) {
    if (!it.value().is_number()) continue;
    std::vector<double> v;
    for (const auto& r : reps) v.push_back(r[it.key()].get<double>());
    if (it.value().is_number_integer()) out[it.key()] = static_cast<long long>(median(v));
    else out[it.key()] = median(v);
  }
  out["total_s"] = out["stars_s"].get<double>() + out["finish_s"].get<double>();
  out["stars_us_per_point"] = 1e6 * out["stars_s"].get<double>() / count;
  out["total_us_per_point"] = 1e6 * out["total_s"].get<double>() / count;
  return out;
}

std::vector<Case> parse_cases(const std::string& text) {
  std::vector<Case> cases;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    auto colon = item.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("a case is NAME:COUNT, got '" + item + "'");
    cases.push_back({item.substr(0, colon), std::stoul(item.substr(colon + 1))});
  }
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases = {{"sphere-2", 10000}, {"sphere-3", 10000}};
  int threads = 2, reps = 3;
  std::uint64_t seed = 1;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--cases") cases = parse_cases(value());
      else if (a == "--all") {
        cases.clear();
        for (std::size_t n : {10000, 50000})
          for (const char* name : {"sphere-2", "clifford-torus-2", "sphere-3", "clifford-torus-3", "so3"})
            cases.push_back({name, n});
      } else if (a == "--threads") threads = std::stoi(value());
      else if (a == "--reps") reps = std::stoi(value());
      else if (a == "--seed") seed = std::stoull(value());
      else if (a == "--help" || a == "-h") {
        std::cout << "bench_tangential [--cases NAME:COUNT,...] [--all] [--threads T] [--reps R] [--seed S]\n";
        return 0;
      } else throw std::invalid_argument("unknown option " + a);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_tangential: " << e.what() << "\n";
    return 2;
  }
  json doc;
  doc["benchmark"] = "tangential complex: delcert vs GUDHI Tangential_complex";
  doc["gudhi"] = "Tangential_complex from Debian libgudhi-dev 3.7 (header-only), TBB";
  doc["threads"] = threads;
  doc["repetitions"] = reps;
  doc["seed"] = seed;
  auto load = [] {
    double l[1] = {0};
    return getloadavg(l, 1) == 1 ? l[0] : -1.0;
  };
  doc["load_average_at_start"] = load();  // other work on the machine skews wall times
  doc["cases"] = json::array();
  for (const Case& c : cases) {
    std::vector<json> ours, theirs;
    for (int r = 0; r < reps; ++r) {
      std::cerr << c.manifold << " " << c.count << " rep " << r + 1 << "/" << reps << ": delcert" << std::flush;
      ours.push_back(measure(c, "delcert", threads, seed));
      std::cerr << ", gudhi" << std::flush;
      theirs.push_back(measure(c, "gudhi", threads, seed));
      std::cerr << "\n";
    }
    json e;
    e["manifold"] = c.manifold;
    e["points"] = c.count;
    e["delcert"] = summarize(ours, c.count);
    e["gudhi"] = summarize(theirs, c.count);
    const json d = e["delcert"], g = e["gudhi"];  // copies: adding keys to e moves its members
    if (!d.contains("error") && !g.contains("error")) {
      e["speedup_stars"] = g["stars_s"].get<double>() / d["stars_s"].get<double>();
      e["speedup_total"] = g["total_s"].get<double>() / d["total_s"].get<double>();
      e["speedup_stars_cpu"] = g["stars_cpu_s"].get<double>() / d["stars_cpu_s"].get<double>();
      e["peak_memory_ratio_gudhi_over_delcert"] = g["peak_rss_mb"].get<double>() / d["peak_rss_mb"].get<double>();
      e["same_star_simplices"] = g["star_simplices"] == d["star_simplices"];
      e["same_inconsistent_in_stars"] = g["inconsistent_in_stars"] == d["inconsistent_in_stars"];
    }
    doc["cases"].push_back(e);
  }
  doc["load_average_at_end"] = load();
  std::cout << doc.dump(2) << std::endl;
  return 0;
}
