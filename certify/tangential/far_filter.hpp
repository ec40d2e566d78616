// A floating-point proof that a point projects far from p onto T_p (check 7's prefilter).
//
// Check 7 tests delta-protection only against the points of W = B(p, 5 eps) whose projection onto
// T_p lies within 2 eps + delta of p: at m = 3 about 1 in 15 of W. Projecting every point of W in
// interval arithmetic was most of check 7's time; this test discards most of W with a few double
// operations per point and an a-priori error bound (the proof in far_filter.cpp). A discarded point
// is one whose exact projected squared distance exceeds the threshold, so it would have been found
// protected for every cell of the star; the points kept are projected exactly as before.
#pragma once

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <span>
#include <vector>

namespace delcert::certify::detail {

class FarFilter {
 public:
  // p: N coordinates. The exact tangent basis U (N x m, row-major) lies entrywise in
  // [u_lo, u_hi]; the inverse G^-1 of its Gram matrix (m x m, row-major) in [gi_lo, gi_hi].
  // threshold >= 0. Any finite or infinite enclosures are accepted (a NaN or infinite one only
  // makes beyond() always false).
  FarFilter(std::span<const double> p, std::span<const double> u_lo, std::span<const double> u_hi,
            std::span<const double> gi_lo, std::span<const double> gi_hi, int m, double threshold);

  // true proves t(x) = b^T G^-1 b > threshold for the exact b = U^T (x - p) of the exact real
  // x - p (t is |pi_p(x) - p|^2, the squared distance from p of the orthogonal projection of x onto
  // the affine tangent space at p). false proves nothing. Valid in every IEEE rounding mode, for
  // any finite coordinates (N of them).
  bool beyond(std::span<const double> x) const { return beyond_in<0, 0>(x.data()); }
  // The same test with the dimensions fixed at compile time (N == the point's dimension and M ==
  // m, or both 0 for the constructor's): the one implementation, unrolled by the compiler for the
  // hot cases of check 7 (N = 3, m = 2 and N = 4, m = 3). x: N coordinates.
  template <int N, int M>
  bool beyond_in(const double* x) const;

 private:
  int N_ = 0, m_ = 0;
  std::span<const double> p_;
  std::vector<double> u_;  // mid(U), N x m
  std::vector<double> g_;  // mid(G^-1), m x m
  double c_ = 0;           // |e_a| <= c_ * sum_i |d~_i| + 2^-1020 (step 3)
  double c1_ = 0, c2_ = 0, threshold_ = 0;
  static constexpr int kMaxM = 8;
  static constexpr double kInflate = 1 + 0x1p-40;
  static constexpr double kTiny = 0x1p-999;  // 2 * 2^-1000, step 7 of the proof
};

// The proof that a true answer is right (steps 1-8) is in far_filter.cpp.
template <int N, int M>
[[gnu::always_inline]] inline bool FarFilter::beyond_in(const double* x) const {
  if constexpr (N > 0 || M > 0)
    if (N != N_ || M != m_) return false;  // not the constructor's dimensions: proves nothing
  const int n = N > 0 ? N : N_, m = M > 0 ? M : m_;
  std::array<double, kMaxM> b{};
  double S = 0;
  for (int i = 0; i < n; ++i) {
    const double d = x[i] - p_[i];
    S += std::abs(d);
    const double* row = u_.data() + std::size_t(i) * m;
    for (int a = 0; a < m; ++a) b[a] += row[a] * d;
  }
  double beta = 0, Q = 0;
  for (int a = 0; a < m; ++a) beta = std::max(beta, std::abs(b[a]));
  for (int a = 0; a < m; ++a)
    for (int k = 0; k < m; ++k) Q += b[a] * g_[a * m + k] * b[k];
  if (!(Q <= DBL_MAX) || !(S <= DBL_MAX) || !(beta <= DBL_MAX)) return false;  // step 8 (NaN fails too)
  const double E = c_ * S * kInflate + 0x1p-1020;
  const double R = (threshold_ + c1_ * beta * beta + c2_ * E * beta) * kInflate + kTiny * (beta + 1);
  return Q > R;
}

}  // namespace delcert::certify::detail
