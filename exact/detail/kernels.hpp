// The predicate formulas of exact/, each written once and templated on the number type.
//
// Private to exact/*.cpp, to tests and to bench/ (which evaluates the same expressions in
// double as a baseline). CGAL-free. Every formula uses only +, - and * (division-free), so:
//  * with an exact ring type (CGAL::Mpzf on dyadic inputs) the value is exact;
//  * with interval arithmetic under upward rounding the value is an enclosure of the exact
//    value, so a sign read from an interval that excludes 0 is the exact sign;
//  * with double it is the plain floating-point evaluation (benchmarks only).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "exact/linear_algebra.hpp"  // minor_table, determinant

namespace delcert::exact::detail {

inline constexpr int kMaxIntrinsicDim = 6;  // largest m the tangential predicates accept
inline constexpr int kMaxSimplexDim = 7;    // largest j the thickness predicate accepts
inline constexpr int kMaxCodim = 8;         // largest N - m for exact tangent bases

// Calls f(std::integral_constant<int, n>) for n in [Lo, Hi]; throws std::invalid_argument otherwise.
template <int Lo, int Hi, class F>
decltype(auto) dispatch(int n, F&& f) {
  if constexpr (Lo == Hi) {
    if (n != Lo)
      throw std::invalid_argument("dimension " + std::to_string(n) + " is not supported by exact/ (supported: up to " +
                                  std::to_string(Hi) + ")");
    return f(std::integral_constant<int, Lo>{});
  } else {
    if (n == Lo) return f(std::integral_constant<int, Lo>{});
    return dispatch<Lo + 1, Hi>(n, static_cast<F&&>(f));
  }
}

// ---------------------------------------------------------------------------------------------
// Tangential predicates (docs/design.md §3.2), in chart coordinates at a point p with basis U of T_p - p
// (N x m, any basis, not orthonormal). The chart row of an ambient point x is
//   r(x) = (b(x), s(x)),  b(x) = U^T (x - p) in R^m,  s(x) = |x - p|^2,
// so r(p) = 0. For c = p + U z in T_p: |c - x|^2 = s(x) - 2 b(x).z + |U z|^2.
// ---------------------------------------------------------------------------------------------

// Chart row of x from diff(i) = x_i - p_i (i < N) and U (N x M row-major): M + 1 entries.
template <int M, class NT, class Diff>
void chart_row(const NT* U, Diff&& diff, int N, NT* row) {
  for (int a = 0; a <= M; ++a) row[a] = NT(0);
  for (int i = 0; i < N; ++i) {
    const NT di = diff(i);
    for (int a = 0; a < M; ++a) row[a] = row[a] + U[i * M + a] * di;
    row[M] = row[M] + di * di;
  }
}

// Orientation of m + 1 points v0..vm in T_p with respect to the basis U:
//   det [b(v1) - b(v0); ...; b(vm) - b(v0)]  (rows).
// rows[i] points at r(v_i); when origin_ref, r(v0) = 0 (v0 = p) and the subtraction is skipped.
template <int M, class NT>
NT orientation_det(const NT* const* rows, bool origin_ref) {
  NT a[M * M];
  for (int i = 0; i < M; ++i)
    for (int k = 0; k < M; ++k)
      a[i * M + k] = origin_ref ? rows[i + 1][k] : rows[i + 1][k] - rows[0][k];
  return determinant<M, NT>(a);
}

// Power test of a cell s = (v0..vm) in T_p. The centre c = p + U z of s is the point of T_p at
// equal ambient distance from all vertices: |c - v_i|^2 = |c - v0|^2 for i = 1..m, i.e.
//   2 (b(v_i) - b(v0)).z = s(v_i) - s(v0),   a linear system  B (2z) = h,
// with B the m x m matrix of rows b(v_i) - b(v0) and h_i = s(v_i) - s(v0). For any x,
//   |c - x|^2 - |c - v0|^2 = (s(x) - s(v0)) - (b(x) - b(v0)).(2z) = det[[B, h], [r(x) - r(v0)]] / det B
// (Schur complement of B in the bordered matrix). Hence
//   sign(|c - x|^2 - |c - v0|^2)         = sign(det B) * sign(det M(x)),
//   sign(|c - x|^2 - |c - v0|^2 - delta) = sign(det B) * sign(det M(x) - delta det B),
// both division-free; det B = 0 means s projects to a degenerate simplex (no unique centre).
// Expanding det M(x) along its last row: det M(x) = sum_j coef_j (r(x) - r(v0))_j with
// coef_j = (-1)^(m+j) det(A without column j), A = [B | h] (m x (m+1)); coef_m = det B.
// power_cell computes coef and k0 = sum_j coef_j r(v0)_j, so that det M(x) = coef.r(x) - k0.
template <int M, class NT>
void power_cell(const NT* const* rows, bool origin_ref, NT* coef, NT& k0) {
  constexpr int C = M + 1;
  NT a[M * C];
  for (int i = 0; i < M; ++i)
    for (int k = 0; k < C; ++k) a[i * C + k] = origin_ref ? rows[i + 1][k] : rows[i + 1][k] - rows[0][k];
  NT table[1u << C];
  minor_table<M, C>(a, table);
  const unsigned full = (1u << C) - 1;
  for (int j = 0; j < C; ++j) {
    const NT& minor = table[full ^ (1u << j)];
    coef[j] = ((M + j) % 2 == 0) ? minor : NT(0) - minor;
  }
  k0 = NT(0);
  if (!origin_ref)
    for (int j = 0; j < C; ++j) k0 = k0 + coef[j] * rows[0][j];
}

// det M(x) = coef . r(x) - k0 (see power_cell).
template <int M, class NT>
NT power_value(const NT* coef, const NT& k0, const NT* rx, bool origin_ref) {
  NT v = coef[0] * rx[0];
  for (int j = 1; j <= M; ++j) v = v + coef[j] * rx[j];
  return origin_ref ? v : v - k0;
}

// ---------------------------------------------------------------------------------------------
// Thickness (docs/design.md §3.1, paper §2.2) via Gram determinants of edge vectors.
// For a j-simplex t = (v0..vj) with squared-distance matrix d, the Gram matrix of the edges
// from a base vertex b satisfies 2 G_ik = d_bi + d_bk - d_ik (polarisation), so
//   det(2G(t)) = 2^j det G(t),   det(2G(t_l)) = 2^(j-1) det G(t_l)  (t_l: facet opposite v_l),
// and D(v_l, t)^2 = det G(t) / det G(t_l) = gt / (2 gf_l). With Delta^2 the longest squared edge,
//   D(v_l, t) >= Gamma j Delta   <=>   gt >= 2 Gamma^2 j^2 Delta^2 gf_l   (when gf_l > 0),
// division-free. gt = 0 exactly iff t is affinely dependent.
// ---------------------------------------------------------------------------------------------

// d: (J+1) x (J+1) squared distances (row-major, symmetric, zero diagonal).
// Outputs gt = det(2G(t)) and gf[l] = det(2G(t_l)) for l = 0..J (gf = 1 when J = 1).
template <int J, class NT>
void thickness_terms(const NT* d, NT& gt, NT* gf) {
  constexpr int V = J + 1;
  // Full simplex, base v0, edges to v1..vJ.
  {
    NT g[J * J];
    for (int i = 0; i < J; ++i)
      for (int k = 0; k < J; ++k) g[i * J + k] = d[0 * V + (i + 1)] + d[0 * V + (k + 1)] - d[(i + 1) * V + (k + 1)];
    gt = determinant<J, NT>(g);
  }
  for (int l = 0; l < V; ++l) {
    if constexpr (J == 1) {
      gf[l] = NT(1);  // a facet of an edge is a vertex: the empty Gram determinant is 1
    } else {
      int idx[J];  // the vertices of the facet opposite v_l
      for (int v = 0, n = 0; v < V; ++v)
        if (v != l) idx[n++] = v;
      NT g[(J - 1) * (J - 1)];
      const int b = idx[0];
      for (int i = 0; i < J - 1; ++i)
        for (int k = 0; k < J - 1; ++k) {
          const int vi = idx[i + 1], vk = idx[k + 1];
          g[i * (J - 1) + k] = d[b * V + vi] + d[b * V + vk] - d[vi * V + vk];
        }
      gf[l] = determinant<J - 1, NT>(g);
    }
  }
}

// Squared distance between two points given by their coordinate differences d (n entries).
template <class NT>
NT squared_norm(const NT* d, int n) {
  NT s(0);
  for (int i = 0; i < n; ++i) s = s + d[i] * d[i];
  return s;
}

}  // namespace delcert::exact::detail
