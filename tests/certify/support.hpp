// Helpers for the certifier's tests: deterministic well-spread samples of the built-in manifolds
// (own generators: the tests of certify/ must not depend on the producer), the tangential complex
// computed by the certifier itself, temporary files and running the delcert-certify binary.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "certify/certify.hpp"
#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/tangential/star.hpp"
#include "exact/tangent_space.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/test_paths.hpp"

namespace delcert::certify::test {

inline std::string fixture(const std::string& rel) { return std::string(DELCERT_FIXTURES_DIR) + "/" + rel; }
inline std::string binary() { return std::string(DELCERT_BINARY_DIR) + "/delcert-certify"; }

// A fresh directory under the system temp dir, removed at destruction.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag) {
    path = std::filesystem::temp_directory_path() / ("delcert-certify-test-" + tag + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}
inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// splitmix64: platform-stable pseudo-random numbers.
struct Rng {
  std::uint64_t s;
  explicit Rng(std::uint64_t seed) : s(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1p-53; }  // [0, 1)
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

inline io::PointSet make_points(int dim, const std::vector<std::vector<double>>& pts) {
  io::PointSet P;
  P.dimension = dim;
  for (const auto& p : pts) P.push_back(p);
  return P;
}

// Fibonacci points on the unit sphere S^2.
inline io::PointSet fibonacci_sphere(int n) {
  std::vector<std::vector<double>> pts;
  const double g = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), t = g * i;
    pts.push_back({r * std::cos(t), r * std::sin(t), z});
  }
  return make_points(3, pts);
}

// Well-spread points on the unit sphere S^(d-1) in R^d: dart throwing with a minimum distance.
inline io::PointSet spread_sphere(int d, int n, double min_dist, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts;
  for (int tries = 0; tries < 200000 && static_cast<int>(pts.size()) < n; ++tries) {
    std::vector<double> x(d);
    double s = 0;
    for (auto& v : x) {  // Box-Muller normals
      double u1 = rng.uniform() + 1e-300, u2 = rng.uniform();
      v = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
      s += v * v;
    }
    for (auto& v : x) v /= std::sqrt(s);
    bool ok = true;
    for (const auto& q : pts) {
      double e = 0;
      for (int k = 0; k < d; ++k) e += (x[k] - q[k]) * (x[k] - q[k]);
      ok = ok && e >= min_dist * min_dist;
    }
    if (ok) pts.push_back(x);
  }
  return make_points(d, pts);
}

// A well-spread sample of SO(3) in R^9: random unit quaternions (seeded) kept greedily at least
// `min_dist` apart, as row-major rotation matrices (rounded: off SO(3) by ~1e-16).
// `quaternions` (optional) receives each kept point's unit quaternion (w, x, y, z).
inline io::PointSet so3_net(int candidates, double min_dist, std::uint64_t seed,
                            std::vector<std::array<double, 4>>* quaternions = nullptr) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts;
  for (int c = 0; c < candidates; ++c) {
    double q[4], n = 0;
    do {
      n = 0;
      for (double& x : q) x = 2 * rng.uniform() - 1, n += x * x;
    } while (n > 1 || n < 1e-3);
    for (double& x : q) x /= std::sqrt(n);
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    std::vector<double> R = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                             2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                             2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    bool far = true;
    for (const auto& P : pts) {
      double d = 0;
      for (int i = 0; i < 9; ++i) d += (P[i] - R[i]) * (P[i] - R[i]);
      far = far && d >= min_dist * min_dist;
    }
    if (!far) continue;
    pts.push_back(std::move(R));
    if (quaternions) quaternions->push_back({w, x, y, z});
  }
  return make_points(9, pts);
}

// Del_M (certify/intrinsic.hpp) of P from `candidates` on 2 threads, and its certified m-simplices.
inline IntrinsicDelaunay del_m(const io::ManifoldSpec& spec, const io::PointSet& P,
                               const std::vector<std::vector<int>>& candidates) {
  const detail::PointGrid grid(P, spec.intrinsic_dimension);
  return compute_intrinsic_delaunay(spec, P, grid, candidates, 2);
}
inline std::set<std::vector<int>> simplices(const IntrinsicDelaunay& D) {
  std::set<std::vector<int>> s;
  for (const auto& x : D.simplices) s.insert(x.simplex);
  return s;
}

// A near-equilateral triangular lattice on the flat torus S^1 x S^1 in R^4: `cols` points per
// row, `rows` rows (even), odd rows shifted by half a step; each angle jittered by up to
// `jitter` steps (seeded) so that no three projected points are exactly collinear.
inline io::PointSet torus2_lattice(int cols, int rows, double jitter = 0.02, std::uint64_t seed = 5) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      double a = 2 * M_PI * (i + 0.5 * (j % 2) + jitter * (rng.uniform() - 0.5)) / cols,
             b = 2 * M_PI * (j + jitter * (rng.uniform() - 0.5)) / rows;
      pts.push_back({std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    }
  return make_points(4, pts);
}

// A body-centred cubic lattice on the flat 3-torus in R^6 (2 k^3 points), jittered like
// torus2_lattice.
inline io::PointSet torus3_bcc(int k, double jitter = 0.02, std::uint64_t seed = 6) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts;
  auto angle = [&](int i, int s) { return 2 * M_PI * (i + 0.5 * s + jitter * (rng.uniform() - 0.5)) / k; };
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j)
        for (int l = 0; l < k; ++l) {
          double a = angle(i, s), b = angle(j, s), c = angle(l, s);
          pts.push_back({std::cos(a), std::sin(a), std::cos(b), std::sin(b), std::cos(c), std::sin(c)});
        }
  return make_points(6, pts);
}

// A staggered parameter grid on the torus of revolution R = 2, r = 1 (axis x3), jittered.
inline io::PointSet torus_of_revolution(int ku, int kv, double jitter = 0.02, std::uint64_t seed = 8) {
  Rng rng(seed);
  std::vector<std::vector<double>> pts;
  for (int j = 0; j < kv; ++j)
    for (int i = 0; i < ku; ++i) {
      double u = 2 * M_PI * (i + 0.5 * (j % 2) + jitter * (rng.uniform() - 0.5)) / ku,
             v = 2 * M_PI * (j + jitter * (rng.uniform() - 0.5)) / kv;
      pts.push_back({(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  return make_points(3, pts);
}

// The tangential Delaunay complex of P computed by the certifier itself (union of the stars).
struct Audit {
  io::Complex complex;
  bool all_proven = true;
  bool consistent = true;
};
inline Audit audit(const std::string& spec_source, const io::PointSet& P) {
  io::ManifoldSpec spec = io::read_spec(spec_source);
  exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);
  detail::PointGrid grid(P, spec.intrinsic_dimension);
  StarSettings S{&P, &system, &grid, spec.intrinsic_dimension, std::nullopt, std::nullopt};
  exact::FilterContext ctx;
  Audit A;
  std::vector<std::set<Simplex>> stars(P.size());
  std::set<Simplex> all;
  for (std::size_t p = 0; p < P.size(); ++p) {
    StarReport r = analyse_star(S, static_cast<int>(p), nullptr, ctx);
    A.all_proven = A.all_proven && r.state == StarReport::State::proven;
    for (const auto& c : r.star) stars[p].insert(c.simplex), all.insert(c.simplex);
  }
  for (const auto& s : all)
    for (int v : s) A.consistent = A.consistent && stars[v].count(s);
  A.complex.num_vertices = P.size();
  A.complex.simplices.assign(all.begin(), all.end());
  return A;
}

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};
// Runs a shell command line, capturing stdout and stderr.
inline RunResult run(const std::string& args, const TempDir& dir) {
  std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  int status = std::system((args + " > " + out + " 2> " + err).c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

inline std::string last_line(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  auto p = t.find_last_of('\n');
  return p == std::string::npos ? t : t.substr(p + 1);
}

inline const CheckEntry& check(const Certificate& c, CheckId id) {
  for (const auto& e : c.checks)
    if (e.id == id) return e;
  throw std::runtime_error(std::string("no check ") + check_name(id));
}

}  // namespace delcert::certify::test
