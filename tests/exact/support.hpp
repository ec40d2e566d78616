// Test helpers for exact/: a seeded generator, the test manifolds, and brute-force mpq
// reference implementations written independently of exact/'s division-free formulas
// (projections, weights and linear solves, as the definitions in docs/design.md §3.2 read).
#pragma once

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "exact/number_types.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::exact::testing {

using Q = mpq_class;

// Deterministic on every platform (mt19937_64 is fully specified; distributions are ours).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : e_(seed) {}
  double uniform() { return static_cast<double>(e_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  int integer(int lo, int hi) { return lo + static_cast<int>(e_() % static_cast<std::uint64_t>(hi - lo + 1)); }
  std::uint64_t bits() { return e_(); }

 private:
  std::mt19937_64 e_;
};

struct TestManifold {
  std::string name;
  int N = 0, m = 0;
  std::vector<std::string> equations;
  bool quadratic_form = false;  // F_i = x^T A_i x - c_i: ker J(lambda p) = ker J(p)
};

// The built-in manifolds of fixtures/manifolds (equations copied verbatim).
inline std::vector<TestManifold> test_manifolds() {
  return {
      {"sphere-2", 3, 2, {"x1^2 + x2^2 + x3^2 - 1"}, true},
      {"sphere-3", 4, 3, {"x1^2 + x2^2 + x3^2 + x4^2 - 1"}, true},
      {"clifford-torus-2", 4, 2, {"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, true},
      {"clifford-torus-3", 6, 3, {"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5^2 + x6^2 - 1"}, true},
      {"torus-of-revolution", 3, 2, {"(x1^2 + x2^2 + x3^2 + 3)^2 - 16*(x1^2 + x2^2)"}, false},
      {"so3",
       9,
       3,
       {"x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 + x6^2 - 1", "x7^2 + x8^2 + x9^2 - 1", "x1*x4 + x2*x5 + x3*x6",
        "x1*x7 + x2*x8 + x3*x9", "x4*x7 + x5*x8 + x6*x9"},
       true},
  };
}

// A point near the manifold (exactly on it up to rounding for the parametrised ones).
inline std::vector<double> sample_near(const TestManifold& M, Rng& rng) {
  std::vector<double> x(M.N);
  const double two_pi = 6.283185307179586;
  if (M.name.rfind("sphere", 0) == 0) {
    double n = 0;
    for (auto& v : x) {
      v = rng.normal();
      n += v * v;
    }
    for (auto& v : x) v /= std::sqrt(n);
  } else if (M.name.rfind("clifford", 0) == 0) {
    for (int i = 0; i < M.N / 2; ++i) {
      const double a = rng.uniform(0, two_pi);
      x[2 * i] = std::cos(a);
      x[2 * i + 1] = std::sin(a);
    }
  } else if (M.name == "torus-of-revolution") {
    const double a = rng.uniform(0, two_pi), b = rng.uniform(0, two_pi);
    x = {(2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a), std::sin(b)};
  } else {  // so3: unit quaternion -> rotation matrix, row-major
    double q[4], n = 0;
    for (double& v : q) {
      v = rng.normal();
      n += v * v;
    }
    for (double& v : q) v /= std::sqrt(n);
    const double w = q[0], a = q[1], b = q[2], c = q[3];
    x = {1 - 2 * (b * b + c * c), 2 * (a * b - c * w), 2 * (a * c + b * w),
         2 * (a * b + c * w),     1 - 2 * (a * a + c * c), 2 * (b * c - a * w),
         2 * (a * c - b * w),     2 * (b * c + a * w), 1 - 2 * (a * a + b * b)};
  }
  return x;
}

// ---- dense rational linear algebra (Gaussian elimination) ----

inline Q det(std::vector<Q> a, int n) {
  Q d = 1;
  for (int c = 0; c < n; ++c) {
    int piv = c;
    while (piv < n && a[piv * n + c] == 0) ++piv;
    if (piv == n) return 0;
    if (piv != c) {
      for (int j = 0; j < n; ++j) std::swap(a[c * n + j], a[piv * n + j]);
      d = -d;
    }
    d *= a[c * n + c];
    for (int i = c + 1; i < n; ++i) {
      if (a[i * n + c] == 0) continue;
      Q f = a[i * n + c] / a[c * n + c];
      for (int j = c; j < n; ++j) a[i * n + j] -= f * a[c * n + j];
    }
  }
  return d;
}

// Rank of a rows x cols matrix.
inline int rank(std::vector<Q> a, int rows, int cols) {
  int r = 0;
  for (int c = 0; c < cols && r < rows; ++c) {
    int piv = r;
    while (piv < rows && a[piv * cols + c] == 0) ++piv;
    if (piv == rows) continue;
    for (int j = 0; j < cols; ++j) std::swap(a[r * cols + j], a[piv * cols + j]);
    for (int i = r + 1; i < rows; ++i) {
      if (a[i * cols + c] == 0) continue;
      Q f = a[i * cols + c] / a[r * cols + c];
      for (int j = c; j < cols; ++j) a[i * cols + j] -= f * a[r * cols + j];
    }
    ++r;
  }
  return r;
}

// Solves A x = b (n x n); nullopt when A is singular.
inline std::optional<std::vector<Q>> solve(std::vector<Q> A, std::vector<Q> b, int n) {
  for (int c = 0; c < n; ++c) {
    int piv = c;
    while (piv < n && A[piv * n + c] == 0) ++piv;
    if (piv == n) return std::nullopt;
    if (piv != c) {
      for (int j = 0; j < n; ++j) std::swap(A[c * n + j], A[piv * n + j]);
      std::swap(b[c], b[piv]);
    }
    for (int i = c + 1; i < n; ++i) {
      if (A[i * n + c] == 0) continue;
      Q f = A[i * n + c] / A[c * n + c];
      for (int j = c; j < n; ++j) A[i * n + j] -= f * A[c * n + j];
      b[i] -= f * b[c];
    }
  }
  std::vector<Q> x(n);
  for (int i = n - 1; i >= 0; --i) {
    Q acc = b[i];
    for (int j = i + 1; j < n; ++j) acc -= A[i * n + j] * x[j];
    x[i] = acc / A[i * n + i];
  }
  return x;
}

inline int sign(const Q& q) { return sgn(q); }

inline std::vector<Q> rational(const double* x, int n) {
  std::vector<Q> out(n);
  for (int i = 0; i < n; ++i) out[i] = to_rational(x[i]);
  return out;
}

// ---- reference tangential geometry by projections (docs/design.md §3.2 as written) ----

// Coordinates z of the orthogonal projection of x onto T_p in the basis U: x' = p + U z,
// z = G^{-1} U^T (x - p); and the squared normal distance n(x) = |x - x'|^2 = -w(x).
struct Projected {
  std::vector<Q> z;
  Q normal2;
};

inline Projected project(const TangentSpace& T, const double* x) {
  const int N = T.ambient_dimension(), m = T.intrinsic_dimension();
  const auto p = T.point();
  std::vector<Q> d(N), r(m, Q(0)), G(m * m);
  for (int i = 0; i < N; ++i) d[i] = to_rational(x[i]) - to_rational(p[i]);
  for (int a = 0; a < m; ++a)
    for (int i = 0; i < N; ++i) r[a] += T.basis(i, a) * d[i];
  // Gram computed here from U, not taken from TangentSpace::gram.
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      Q g = 0;
      for (int i = 0; i < N; ++i) g += T.basis(i, a) * T.basis(i, b);
      G[a * m + b] = g;
    }
  Projected out;
  out.z = *solve(G, r, m);
  out.normal2 = 0;
  for (int i = 0; i < N; ++i) {
    Q xi = d[i];
    for (int a = 0; a < m; ++a) xi -= T.basis(i, a) * out.z[a];
    out.normal2 += xi * xi;
  }
  return out;
}

// |U v|^2 for a coordinate vector v.
inline Q tangent_norm2(const TangentSpace& T, const std::vector<Q>& v) {
  const int N = T.ambient_dimension(), m = T.intrinsic_dimension();
  Q s = 0;
  for (int i = 0; i < N; ++i) {
    Q c = 0;
    for (int a = 0; a < m; ++a) c += T.basis(i, a) * v[a];
    s += c * c;
  }
  return s;
}

// Orientation of the projected points in U-coordinates: sign det [z_i - z_0].
inline int ref_orientation(const TangentSpace& T, const std::vector<const double*>& pts) {
  const int m = T.intrinsic_dimension();
  auto z0 = project(T, pts[0]).z;
  std::vector<Q> a(m * m);
  for (int i = 1; i <= m; ++i) {
    auto zi = project(T, pts[i]).z;
    for (int k = 0; k < m; ++k) a[(i - 1) * m + k] = zi[k] - z0[k];
  }
  return sign(det(a, m));
}

// Weighted power of the projection of x, weight w(x) = -n(x), seen from c = p + U zc:
// |c - x'|^2 - w(x) = |U (zc - z)|^2 + n(x).
inline Q weighted_power(const TangentSpace& T, const std::vector<Q>& zc, const Projected& x) {
  std::vector<Q> d(zc.size());
  for (std::size_t a = 0; a < zc.size(); ++a) d[a] = zc[a] - x.z[a];
  return tangent_norm2(T, d) + x.normal2;
}

// The power centre (coordinates zc) of the weighted projections of the cell; nullopt when the
// projected cell is degenerate.
inline std::optional<std::vector<Q>> ref_centre(const TangentSpace& T, const std::vector<const double*>& cell) {
  const int m = T.intrinsic_dimension();
  std::vector<Projected> pr;
  for (auto* v : cell) pr.push_back(project(T, v));
  // Equal powers: |U(zc - z_i)|^2 + n_i = |U(zc - z_0)|^2 + n_0 is linear in zc:
  // 2 (z_i - z_0)^T G zc = z_i^T G z_i + n_i - z_0^T G z_0 - n_0.
  std::vector<Q> G(m * m);
  const int N = T.ambient_dimension();
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      Q g = 0;
      for (int i = 0; i < N; ++i) g += T.basis(i, a) * T.basis(i, b);
      G[a * m + b] = g;
    }
  std::vector<Q> A(m * m), rhs(m);
  for (int i = 1; i <= m; ++i) {
    for (int b = 0; b < m; ++b) {
      Q s = 0;
      for (int a = 0; a < m; ++a) s += (pr[i].z[a] - pr[0].z[a]) * G[a * m + b];
      A[(i - 1) * m + b] = 2 * s;
    }
    rhs[i - 1] = tangent_norm2(T, pr[i].z) + pr[i].normal2 - tangent_norm2(T, pr[0].z) - pr[0].normal2;
  }
  return solve(A, rhs, m);
}

// power(c, q) - power(c, v0) for the weighted projections; nullopt when degenerate.
inline std::optional<Q> ref_power(const TangentSpace& T, const std::vector<const double*>& cell, const double* q) {
  auto zc = ref_centre(T, cell);
  if (!zc) return std::nullopt;
  return weighted_power(T, *zc, project(T, q)) - weighted_power(T, *zc, project(T, cell[0]));
}

// A face (v0..vk), k <= m: its centre is the point of the affine hull of the projected vertices
// with equal weighted power to all of them. Returns power(c, q) - power(c, v0), nullopt when the
// projected face is degenerate. Written in U-coordinates z with the metric G.
inline std::optional<Q> ref_face_power(const TangentSpace& T, const std::vector<const double*>& face,
                                       const double* q) {
  const int m = T.intrinsic_dimension(), N = T.ambient_dimension();
  const int k = static_cast<int>(face.size()) - 1;
  std::vector<Projected> pr;
  for (auto* v : face) pr.push_back(project(T, v));
  std::vector<Q> G(m * m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      Q g = 0;
      for (int i = 0; i < N; ++i) g += T.basis(i, a) * T.basis(i, b);
      G[a * m + b] = g;
    }
  auto Gdot = [&](const std::vector<Q>& x, const std::vector<Q>& y) {
    Q s = 0;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) s += x[a] * G[a * m + b] * y[b];
    return s;
  };
  // z = z0 + sum_i l_i e_i, e_i = z_i - z0; equal powers:
  // 2 e_i^T G (z0 + E^T l) = c_i, c_i = (z_i^T G z_i + n_i) - (z0^T G z0 + n0).
  std::vector<std::vector<Q>> e(k, std::vector<Q>(m));
  for (int i = 0; i < k; ++i)
    for (int a = 0; a < m; ++a) e[i][a] = pr[i + 1].z[a] - pr[0].z[a];
  std::vector<Q> A(k * k), rhs(k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) A[i * k + j] = 2 * Gdot(e[i], e[j]);
    rhs[i] = Gdot(pr[i + 1].z, pr[i + 1].z) + pr[i + 1].normal2 - Gdot(pr[0].z, pr[0].z) - pr[0].normal2 -
             2 * Gdot(e[i], pr[0].z);
  }
  auto l = solve(A, rhs, k);
  if (!l) return std::nullopt;
  std::vector<Q> zc = pr[0].z;
  for (int i = 0; i < k; ++i)
    for (int a = 0; a < m; ++a) zc[a] += (*l)[i] * e[i][a];
  return weighted_power(T, zc, project(T, q)) - weighted_power(T, zc, pr[0]);
}

// ---- reference thickness by distances to affine hulls ----

// Squared distance from x to the affine hull of `pts` (affinely independent), by least squares.
inline Q distance2_to_hull(const std::vector<std::vector<Q>>& pts, const std::vector<Q>& x) {
  const int N = static_cast<int>(x.size());
  const int k = static_cast<int>(pts.size()) - 1;
  std::vector<Q> d(N);
  for (int i = 0; i < N; ++i) d[i] = x[i] - pts[0][i];
  if (k == 0) {
    Q s = 0;
    for (auto& v : d) s += v * v;
    return s;
  }
  std::vector<Q> G(k * k), r(k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) {
      Q g = 0;
      for (int i = 0; i < N; ++i) g += (pts[a + 1][i] - pts[0][i]) * (pts[b + 1][i] - pts[0][i]);
      G[a * k + b] = g;
    }
    Q s = 0;
    for (int i = 0; i < N; ++i) s += (pts[a + 1][i] - pts[0][i]) * d[i];
    r[a] = s;
  }
  auto y = *solve(G, r, k);
  Q s = 0;
  for (int i = 0; i < N; ++i) {
    Q e = d[i];
    for (int a = 0; a < k; ++a) e -= (pts[a + 1][i] - pts[0][i]) * y[a];
    s += e * e;
  }
  return s;
}

// Upsilon(t)^2 with the conventions of exact/simplex_predicates.hpp.
inline Q ref_thickness2(const std::vector<const double*>& v, int N) {
  const int j = static_cast<int>(v.size()) - 1;
  if (j == 0) return 1;
  std::vector<std::vector<Q>> pts;
  for (auto* x : v) pts.push_back(rational(x, N));
  std::vector<Q> E(j * N);
  for (int a = 0; a < j; ++a)
    for (int i = 0; i < N; ++i) E[a * N + i] = pts[a + 1][i] - pts[0][i];
  if (rank(E, j, N) < j) return 0;  // affinely dependent
  Q delta2 = 0;
  for (int a = 0; a <= j; ++a)
    for (int b = a + 1; b <= j; ++b) {
      Q s = 0;
      for (int i = 0; i < N; ++i) s += (pts[a][i] - pts[b][i]) * (pts[a][i] - pts[b][i]);
      if (s > delta2) delta2 = s;
    }
  Q best;
  for (int l = 0; l <= j; ++l) {
    std::vector<std::vector<Q>> facet;
    for (int a = 0; a <= j; ++a)
      if (a != l) facet.push_back(pts[a]);
    Q d2 = distance2_to_hull(facet, pts[l]);
    if (l == 0 || d2 < best) best = d2;
  }
  return best / (j * j * delta2);
}

}  // namespace delcert::exact::testing
