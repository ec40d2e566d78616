// Shared helpers for the tangential-complex tests: point sets with their tangent planes, and an
// independent brute-force star.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/sampling/random.hpp"
#include "core/sampling/sampling.hpp"
#include "core/tangential/star.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::tangential::testing {

struct Sample {
  io::PointSet points;
  TangentPlanes planes;
};

// `count` random points of a built-in manifold with T_p from the model.
inline Sample builtin_sample(const std::string& name, std::size_t count, std::uint64_t seed) {
  manifold::Manifold manifold(io::read_spec("builtin:" + name));
  sampling::Random random(seed);
  Sample s;
  sampling::sample_manifold(manifold, count, random, s.points);
  s.planes = compute_tangent_planes(manifold, s.points);
  return s;
}

// Random points of the unit sphere S^m in R^(m+1) (any m; no spec needed), with the tangent
// planes given directly: an orthonormal basis of the orthogonal complement of p.
inline Sample sphere_sample(int m, std::size_t count, std::uint64_t seed) {
  const int N = m + 1;
  sampling::Random random(seed);
  Sample s;
  s.points.dimension = N;
  s.planes = TangentPlanes(N, m);
  for (std::size_t i = 0; i < count; ++i) {
    Eigen::VectorXd p(N);
    for (int j = 0; j < N; ++j) p[j] = random.normal();
    p.normalize();
    s.points.push_back(std::span<const double>(p.data(), N));
    Eigen::MatrixXd column = p;
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(column);
    Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(N, N);
    s.planes.push_back(Eigen::MatrixXd(Q.rightCols(m)));
  }
  return s;
}

// A triangular lattice on the flat torus (angles), C columns and R rows (R even), each point
// moved by at most `jitter` lattice spacings, mapped to the Clifford torus in R^4. The lattice's
// Delaunay triangulation is well protected, so the tangential complex is the lattice's.
inline Sample clifford_lattice(int C, int R, double jitter, std::uint64_t seed) {
  manifold::Manifold manifold(io::read_spec("builtin:clifford-torus-2"));
  sampling::Random random(seed);
  Sample s;
  s.points.dimension = 4;
  const double two_pi = 2 * std::numbers::pi;
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < C; ++i) {
      double a = two_pi * (i + 0.5 * (j % 2) + jitter * random.uniform(-1, 1)) / C;
      double b = two_pi * (j + jitter * random.uniform(-1, 1)) / R;
      const double x[4] = {std::cos(a), std::sin(a), std::cos(b), std::sin(b)};
      s.points.push_back(x);
    }
  s.planes = compute_tangent_planes(manifold, s.points);
  return s;
}

// A K^k grid on the flat torus (k = 2: the Clifford torus in R^4, k = 3: in R^6), each angle
// moved by up to `jitter` radians: exactly cospherical for jitter 0, nearly so for tiny jitter.
inline Sample clifford_grid(int k, int K, double jitter, std::uint64_t seed) {
  manifold::Manifold manifold(io::read_spec(k == 2 ? "builtin:clifford-torus-2" : "builtin:clifford-torus-3"));
  sampling::Random random(seed);
  Sample s;
  s.points.dimension = 2 * k;
  std::vector<int> idx(k, 0);
  for (;;) {
    std::vector<double> x;
    for (int c = 0; c < k; ++c) {
      const double a = 2 * std::numbers::pi * idx[c] / K + jitter * random.uniform(-1, 1);
      x.push_back(std::cos(a));
      x.push_back(std::sin(a));
    }
    s.points.push_back(x);
    int c = 0;
    while (c < k && ++idx[c] == K) idx[c++] = 0;
    if (c == k) break;
  }
  s.planes = compute_tangent_planes(manifold, s.points);
  return s;
}

inline StarOptions with_threads(int threads) {
  StarOptions options;
  options.threads = threads;
  return options;
}

// star(p) by brute force from all points, independently of the library: every m-subset S of the
// other points whose centre c in T_p (2 (q - p) . T v = |q - p|^2 for q in S, c = p + T v) is
// strictly closer to p than every other point is to c. Rows sorted, vertex lists sorted. Sets
// `degenerate` when some decision is within 1e-9 (relative) of a tie.
inline std::vector<std::vector<int>> brute_force_star(const io::PointSet& points, const TangentPlanes& planes,
                                                      std::size_t p, bool* degenerate = nullptr) {
  const int N = points.dimension, m = planes.intrinsic_dimension();
  const std::size_t n = points.size();
  Eigen::Map<const Eigen::VectorXd> pp(points.point(p).data(), N);
  Eigen::MatrixXd T = planes.matrix(p);
  std::vector<std::size_t> others;
  for (std::size_t i = 0; i < n; ++i)
    if (i != p) others.push_back(i);
  std::vector<std::vector<int>> star;
  // Enumerate m-subsets of `others` by index vectors.
  std::vector<std::size_t> idx(m);
  for (int j = 0; j < m; ++j) idx[j] = j;
  if (others.size() < static_cast<std::size_t>(m)) return star;
  for (;;) {
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd b(m);
    for (int r = 0; r < m; ++r) {
      Eigen::Map<const Eigen::VectorXd> q(points.point(others[idx[r]]).data(), N);
      Eigen::VectorXd d = q - pp;
      A.row(r) = 2 * (T.transpose() * d).transpose();
      b[r] = d.squaredNorm();
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (lu.isInvertible()) {
      Eigen::VectorXd v = lu.solve(b);
      Eigen::VectorXd c = pp + T * v;
      const double R2 = (c - pp).squaredNorm();
      std::vector<char> in_cell(n, 0);
      in_cell[p] = 1;
      for (int r = 0; r < m; ++r) in_cell[others[idx[r]]] = 1;
      bool empty = true;
      for (std::size_t i = 0; i < n && empty; ++i) {
        if (in_cell[i]) continue;
        Eigen::Map<const Eigen::VectorXd> q(points.point(i).data(), N);
        const double e2 = (c - q).squaredNorm();
        if (degenerate && std::abs(e2 - R2) <= 1e-9 * R2) *degenerate = true;
        empty = e2 > R2;
      }
      if (empty) {
        std::vector<int> cell{static_cast<int>(p)};
        for (int r = 0; r < m; ++r) cell.push_back(static_cast<int>(others[idx[r]]));
        std::sort(cell.begin(), cell.end());
        star.push_back(cell);
      }
    }
    // next combination
    int j = m - 1;
    while (j >= 0 && idx[j] == others.size() - m + j) --j;
    if (j < 0) break;
    ++idx[j];
    for (int k = j + 1; k < m; ++k) idx[k] = idx[k - 1] + 1;
  }
  std::sort(star.begin(), star.end());
  return star;
}

}  // namespace delcert::tangential::testing
