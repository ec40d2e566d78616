// Benchmark: Del_M (certify/intrinsic.hpp, check 14) against building the tangential complex, in
// the same run (issue 12: target <= 40x `delcert tangential` on the refined clifford-torus-3).
//
//   bench_intrinsic [--input NAME:SPEC:POINTS]... [--manifolds LIST] [--eps E] [--threads T] [--bin DIR]
//
// For each input (a given point file, e.g. DIR/points.txt of `delcert refine`, or a built-in of
// --manifolds sampled by `delcert sample --eps E --seed 1`), `delcert tangential` runs as a
// subprocess (wall and children's CPU seconds); then, in this process, Del_M is computed from the
// tangential complex's m-simplices as candidates, exactly as delcert-certify computes check 14
// (compute_intrinsic_delaunay; without Del_RM, which on these inputs takes far longer: issue 11),
// timed wall and CPU. The JSON gives both, their ratio, the target, whether Del_M is complete and
// whether it equals Del_TM.
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace {

double children_cpu() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Input {
  std::string name, spec, points;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace delcert;
  std::vector<Input> inputs;
  std::string manifolds, eps = "0.1";
  int threads = 2;
  std::string bin = std::filesystem::path(argv[0]).parent_path().parent_path().string();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--input") {
      const auto c1 = v.find(':'), c2 = v.rfind(':');
      if (c1 == std::string::npos || c2 == c1) {
        std::fprintf(stderr, "--input wants NAME:SPEC:POINTS\n");
        return 2;
      }
      inputs.push_back({v.substr(0, c1), v.substr(c1 + 1, c2 - c1 - 1), v.substr(c2 + 1)});
    } else if (a == "--manifolds") manifolds = v;
    else if (a == "--eps") eps = v;
    else if (a == "--threads") threads = std::stoi(v);
    else if (a == "--bin") bin = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const std::string producer = bin + "/delcert";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("bench-intrinsic-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::stringstream list(manifolds);
  for (std::string name; std::getline(list, name, ',');) {
    if (name.empty()) continue;
    const std::string pts = (dir / (name + ".txt")).string();
    std::fprintf(stderr, "sampling %s\n", name.c_str());
    if (std::system((producer + " sample --manifold builtin:" + name + " --eps " + eps + " --seed 1 --out " + pts +
                     " > /dev/null 2>&1").c_str()) != 0) {
      std::fprintf(stderr, "sampling %s failed\n", name.c_str());
      return 1;
    }
    inputs.push_back({name, "builtin:" + name, pts});
  }
  nlohmann::json out;
  out["benchmark"] = "bench_intrinsic";
  out["threads"] = threads;
  out["results"] = nlohmann::json::array();
  for (const Input& in : inputs) {
    std::fprintf(stderr, "%s: delcert tangential\n", in.name.c_str());
    const std::string cx = (dir / (in.name + ".complex")).string();
    const double c0 = children_cpu();
    const auto w0 = std::chrono::steady_clock::now();
    const int s = std::system((producer + " tangential --manifold " + in.spec + " --points " + in.points + " --out " + cx +
                               " --threads " + std::to_string(threads) + " > /dev/null 2>&1")
                                  .c_str());
    const double tw = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    const double tc = children_cpu() - c0;
    nlohmann::json r{{"input", in.name}, {"spec", in.spec}};
    if (!WIFEXITED(s) || WEXITSTATUS(s) != 0) {
      r["error"] = "delcert tangential failed";
      out["results"].push_back(r);
      continue;
    }
    const io::ManifoldSpec spec = io::read_spec(in.spec);
    const io::PointSet P = io::read_points(in.points);
    const io::Complex K = io::read_complex(cx).complex;
    std::vector<std::vector<int>> candidates;
    for (auto t : K.simplices)
      if (static_cast<int>(t.size()) == spec.intrinsic_dimension + 1) {
        std::sort(t.begin(), t.end());
        candidates.push_back(t);
      }
    std::fprintf(stderr, "%s: Del_M of %zu points from %zu candidates\n", in.name.c_str(), P.size(), candidates.size());
    const std::clock_t cpu0 = std::clock();
    const auto w1 = std::chrono::steady_clock::now();
    const certify::detail::PointGrid grid(P, spec.intrinsic_dimension);
    const certify::IntrinsicDelaunay D = certify::compute_intrinsic_delaunay(spec, P, grid, candidates, threads);
    const double iw = std::chrono::duration<double>(std::chrono::steady_clock::now() - w1).count();
    const double ic = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    std::set<std::vector<int>> tm(candidates.begin(), candidates.end()), m;
    for (const auto& x : D.simplices) m.insert(x.simplex);
    r["points"] = P.size();
    r["tangential_wall_s"] = tw;
    r["tangential_cpu_s"] = tc;
    r["intrinsic_wall_s"] = iw;
    r["intrinsic_cpu_s"] = ic;
    r["ratio_wall"] = tw > 0 ? iw / tw : 0;
    r["ratio_cpu"] = tc > 0 ? ic / tc : 0;
    r["target_ratio"] = 40;
    r["computed"] = D.computed;
    r["complete"] = D.complete;
    r["reason"] = D.reason;
    r["m_simplices"] = D.simplices.size();
    r["rejected"] = D.rejected.size();
    r["undecided"] = D.undecided.size();
    r["equal_to_tangential"] = D.complete && m == tm;
    out["results"].push_back(r);
  }
  std::filesystem::remove_all(dir);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
