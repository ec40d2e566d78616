// Benchmark: checks 14-15 on a manifold without a closed-form metric (the general Del_M engine,
// certify/intrinsic/general.hpp) against checks 11-13 (Del_RM and the covering radius) on the same
// input, in the same run (issue 40: target <= 2x).
//
//   bench_general_del_m [--input NAME:SPEC:POINTS]... [--manifolds LIST] [--eps E] [--threads T] [--bin DIR]
//
// Each input (a point file, e.g. DIR/points.txt of `delcert refine`, or a built-in of --manifolds
// refined by `delcert refine --eps E --seed 1`) is certified in this process by run_certify (an
// audit: Del_TM computed from the points), and the certificate's own phase times give the two
// sides: checks 11-13 = restricted_delaunay + coverage + checks_11_13, checks 14-15 =
// intrinsic_delaunay (wall seconds, and CPU seconds where the certificate has them). A spec with a
// closed-form metric uses that engine, not the general one: pass a copy without "metric" to time the
// general engine there. The JSON gives both, their ratio, the target, and what checks 14-15 decided.
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "certify/certify.hpp"

namespace {

struct Input {
  std::string name, spec, points;
};

double phase(const nlohmann::json& times, const std::string& key) { return times.value(key, 0.0); }

}  // namespace

int main(int argc, char** argv) {
  using namespace delcert;
  std::vector<Input> inputs;
  std::string manifolds, eps = "0.15";
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
  if (inputs.empty() && manifolds.empty()) manifolds = "torus-of-revolution";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("bench-general-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::stringstream list(manifolds);
  for (std::string name; std::getline(list, name, ',');) {
    if (name.empty()) continue;
    const std::string out = (dir / name).string();
    std::fprintf(stderr, "refining %s at eps %s\n", name.c_str(), eps.c_str());
    // (exit 0, or 5 when the refiner's own final certificate is not whole: the points are still written)
    const int s = std::system((bin + "/delcert refine --manifold builtin:" + name + " --eps " + eps + " --seed 1 --threads " +
                               std::to_string(threads) + " --out " + out + " > /dev/null 2>&1")
                                  .c_str());
    if (!std::filesystem::exists(out + "/points.txt")) {
      std::fprintf(stderr, "refining %s failed (status %d)\n", name.c_str(), s);
      return 1;
    }
    inputs.push_back({name, "builtin:" + name, out + "/points.txt"});
  }
  nlohmann::json out;
  out["benchmark"] = "bench_general_del_m";
  out["threads"] = threads;
  out["results"] = nlohmann::json::array();
  for (const Input& in : inputs) {
    std::fprintf(stderr, "%s: certifying\n", in.name.c_str());
    certify::CertifyOptions o;
    o.manifold = in.spec, o.points = in.points, o.threads = threads;
    const nlohmann::json C = certify::run_certify(o).to_json(true);
    const nlohmann::json& t = C.at("times_seconds");
    const double rm = phase(t, "restricted_delaunay") + phase(t, "coverage") + phase(t, "checks_11_13");
    const double rm_cpu = phase(t, "restricted_delaunay_cpu") + phase(t, "coverage_cpu") + phase(t, "checks_11_13_cpu");
    const double dm = phase(t, "intrinsic_delaunay"), dm_cpu = phase(t, "intrinsic_delaunay_cpu");
    nlohmann::json r{{"input", in.name}, {"spec", in.spec}, {"points", C.at("inputs").at("points").value("count", 0)}};
    r["checks_11_13_wall_s"] = rm;
    r["checks_11_13_cpu_s"] = rm_cpu;
    r["checks_14_15_wall_s"] = dm;
    r["checks_14_15_cpu_s"] = dm_cpu;
    r["ratio_wall"] = rm > 0 ? dm / rm : 0;
    r["ratio_cpu"] = rm_cpu > 0 ? dm_cpu / rm_cpu : 0;
    r["target_ratio"] = 2;
    for (const auto& check : C.at("checks")) {
      const std::string name = check.at("name");
      if (name == "intrinsic_delaunay" || name == "restricted_equals_intrinsic")
        r[name] = {{"verdict", check.at("verdict")}, {"summary", check.at("summary")}};
      if (name == "intrinsic_delaunay") r["metric"] = check.at("details").value("metric", nlohmann::json(nullptr));
    }
    std::fprintf(stderr, "%s: checks 11-13 %.2f s, checks 14-15 %.2f s (x%.1f; target x2)\n", in.name.c_str(), rm, dm,
                 rm > 0 ? dm / rm : 0.0);
    out["results"].push_back(r);
  }
  std::filesystem::remove_all(dir);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
