// Benchmark: certifying a tangential complex vs building it, in the same run (issue 5).
//
//   bench_certify [--points N] [--repeat R] [--threads T] [--manifolds sphere-2,sphere-3] [--bin DIR]
//
// For each manifold: `delcert sample` an eps-net of about N points, then R times each
// `delcert tangential` (the producer) and `delcert-certify --complex` (the checker) on it, and
// report medians of wall-clock and CPU seconds (children's user + system time), their ratio, the
// certificate's verdict and the fraction of predicate calls the interval filter decided.
// The programs run as subprocesses, exactly as a user runs them; DIR defaults to the directory
// above this executable (the build tree). Prints one JSON document.
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Timing {
  double wall = 0, cpu = 0;
  int status = -1;
};

double children_cpu() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

Timing run(const std::string& cmd) {
  Timing t;
  double c0 = children_cpu();
  auto w0 = std::chrono::steady_clock::now();
  int s = std::system((cmd + " > /dev/null 2>&1").c_str());
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  t.cpu = children_cpu() - c0;
  t.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return t;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::size_t count_points(const std::string& path) {
  std::ifstream f(path);
  std::string tag, line;
  std::getline(f, tag);
  int dim = 0;
  std::size_t n = 0;
  f >> dim >> n;
  return n;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t target = 50000;
  int repeat = 3, threads = 1;
  std::string manifolds = "sphere-2,sphere-3";
  std::filesystem::path bin = std::filesystem::canonical("/proc/self/exe").parent_path().parent_path();
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i], v = argv[i + 1];
    if (a == "--points") target = std::stoul(v);
    else if (a == "--repeat") repeat = std::stoi(v);
    else if (a == "--threads") threads = std::stoi(v);
    else if (a == "--manifolds") manifolds = v;
    else if (a == "--bin") bin = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const std::string producer = (bin / "delcert").string(), checker = (bin / "delcert-certify").string();
  auto dir = std::filesystem::temp_directory_path() / ("delcert-bench-certify-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  nlohmann::json out;
  out["benchmark"] = "certify_vs_tangential";
  out["target_points"] = target;
  out["repeat"] = repeat;
  out["threads"] = threads;
  out["results"] = nlohmann::json::array();
  for (const auto& name : split(manifolds)) {
    const int m = name == "sphere-2" || name == "clifford-torus-2" || name == "torus-of-revolution" ? 2 : 3;
    const std::string pts = (dir / (name + ".txt")).string(), cx = (dir / (name + ".complex")).string(),
                      cert = (dir / (name + ".json")).string(), spec = "builtin:" + name;
    // An eps-net of about `target` points: one guess, one correction (n ~ eps^-m).
    double eps = name == "sphere-2" ? std::sqrt(4 * M_PI / (0.87 * double(target))) : std::cbrt(20.0 / double(target));
    std::size_t n = 0;
    for (int round = 0; round < 3; ++round) {
      run(producer + " sample --manifold " + spec + " --eps " + std::to_string(eps) + " --seed 1 --out " + pts);
      n = count_points(pts);
      if (n == 0) break;
      double ratio = double(n) / double(target);
      if (std::abs(ratio - 1) < 0.05) break;
      eps *= std::pow(ratio, 1.0 / m);
    }
    std::vector<double> pw, pc, cw, cc;
    int verdict_status = -1, producer_status = -1;
    for (int r = 0; r < repeat; ++r) {
      Timing p = run(producer + " tangential --manifold " + spec + " --points " + pts + " --out " + cx +
                     " --threads " + std::to_string(threads));
      Timing c = run(checker + " --manifold " + spec + " --points " + pts + " --complex " + cx + " --threads " +
                     std::to_string(threads) + " --out " + cert);
      producer_status = p.status, verdict_status = c.status;
      pw.push_back(p.wall), pc.push_back(p.cpu), cw.push_back(c.wall), cc.push_back(c.cpu);
    }
    nlohmann::json r;
    r["manifold"] = name;
    r["points"] = n;
    r["eps"] = eps;
    r["producer_exit"] = producer_status;
    r["certify_exit"] = verdict_status;
    r["tangential_wall_s"] = median(pw);
    r["tangential_cpu_s"] = median(pc);
    r["certify_wall_s"] = median(cw);
    r["certify_cpu_s"] = median(cc);
    r["ratio_wall"] = median(pw) > 0 ? median(cw) / median(pw) : 0;
    r["ratio_cpu"] = median(pc) > 0 ? median(cc) / median(pc) : 0;
    try {
      std::ifstream f(cert);
      nlohmann::json c = nlohmann::json::parse(f);
      r["verdict"] = c["verdict"];
      r["filter_calls"] = c["filter"]["calls"];
      r["filter_fraction_decided"] = c["filter"]["fraction_decided_by_filter"];
      r["certify_phases_s"] = c["times_seconds"];
    } catch (const std::exception& e) {
      r["verdict"] = std::string("no certificate: ") + e.what();
    }
    out["results"].push_back(r);
  }
  std::filesystem::remove_all(dir);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
