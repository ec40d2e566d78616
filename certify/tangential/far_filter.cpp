#include "certify/tangential/far_filter.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <stdexcept>

// Why beyond(x) == true proves t(x) > threshold, in every rounding mode and at every magnitude.
//
// Model. u = 2^-52. Every basic operation on doubles, in any IEEE rounding mode and without
// overflow, returns fl(z) = z (1 + delta) + eta with |delta| <= u and |eta| <= 2^-1074 (eta is the
// loss in the subnormal range; eta = 0 for additions and subtractions, whose subnormal results are
// exact). gamma_n = n u / (1 - n u). No -ffast-math, no flush-to-zero (the project never enables them).
//
// Notation: d = x - p exactly (reals), b = U^T d, t = b^T G^-1 b (G = U^T U, positive definite).
// U~, M~ are the double midpoints used below, rho_ia >= |U_ia - U~_ia|, dM_ak >= |G^-1_ak - M~_ak|.
//
// 1. d~_i = fl(x_i - p_i) = d_i (1 + delta_i): |d_i| <= |d~_i| / (1 - u) and
//    |d_i - d~_i| <= u |d~_i| / (1 - u).
// 2. b~_a = fl(sum_i U~_ia d~_i) (any order): |b~_a - sum_i U~_ia d~_i| <= gamma_N sum_i |U~_ia| |d~_i|
//    + N 2^-1074 (1 + gamma_N) (each product may lose eta; the additions only scale it).
// 3. e_a = b_a - b~_a = sum_i (U_ia - U~_ia) d_i + sum_i U~_ia (d_i - d~_i) + (sum_i U~_ia d~_i - b~_a), so
//    |e_a| <= sum_i [rho_ia / (1 - u) + (u / (1 - u) + gamma_N) |U~_ia|] |d~_i| + 2N 2^-1074
//          <= c * S + 2^-1020,  with c >= max_ia [...] and S >= sum_i |d~_i| (N <= 2^11).
// 4. G^-1 is positive definite, so with b = b~ + e:
//    t = b~^T G^-1 b~ + 2 e^T G^-1 b~ + e^T G^-1 e >= b~^T G^-1 b~ - 2 E beta sum_ak |G^-1_ak|
//      >= b~^T M~ b~ - beta^2 sum_ak dM_ak - 2 E beta sum_ak |G^-1_ak|,
//    where beta = max_a |b~_a| and E >= max_a |e_a|.
// 5. Q = fl(sum_ak (b~_a M~_ak) b~_k) (any order) satisfies
//    Q <= b~^T M~ b~ + gamma_(m^2+2) beta^2 sum_ak |M~_ak| + m^2 2^-1073 (beta + 1)
//    (two products and at most m^2 additions per term; the first product's eta is multiplied by
//    b~_k, |b~_k| <= beta; the second adds its own). Fused multiply-adds, where the compiler
//    contracts, only remove roundings: every bound above still holds.
// 6. Hence t >= Q - c1 beta^2 - c2 E beta - 2^-1000 (beta + 1) whenever c1 >= sum_ak (dM_ak +
//    gamma_(m^2+2) |M~_ak|), c2 >= 2 sum_ak |G^-1_ak| and m <= 8 (m^2 2^-1073 < 2^-1000). So
//    Q > R with R >= threshold + c1 beta^2 + c2 E beta + 2^-1000 (beta + 1) proves t > threshold.
// 7. The constants and R are sums and products of nonnegative doubles. Computed in any rounding
//    mode, k such operations return at least the exact value times (1 - u)^k minus the subnormal
//    losses (at most 2^-1074 per operation, times the factors applied after it): multiplying by
//    1 + 2^-40 covers (1 - u)^-k for k <= 2^11 (E: S has N - 1 roundings, c S two more), and
//    the additive 2^-1000 (beta + 1) of step 6 is doubled below to cover the losses. The additive
//    constants are normal doubles (2^-1020 is an upper bound of every subnormal term they cover):
//    subnormal operands are slow on x86. Each enclosure's midpoint lo/2 + hi/2 cannot overflow, and
//    its radius max(hi - mid, mid - lo) is covered by the same factor plus 2^-1020.
// 8. Overflow and NaN. beyond() answers true only if Q > R with Q finite, and b~, S, beta finite
//    (checked): then none of their operations overflowed (an overflow yields +-inf, or +-DBL_MAX
//    under a directed mode, and inf - inf = NaN; a finite Q <= DBL_MAX cannot exceed an R that
//    overflowed to DBL_MAX or inf). A NaN or infinite constant makes R NaN or inf: Q > R is false.

namespace delcert::certify::detail {

FarFilter::FarFilter(std::span<const double> p, std::span<const double> u_lo, std::span<const double> u_hi,
                     std::span<const double> gi_lo, std::span<const double> gi_hi, int m, double threshold)
    : N_(static_cast<int>(p.size())), m_(m), p_(p), threshold_(threshold) {
  if (m < 1 || m > kMaxM || N_ > 2040 || u_lo.size() != std::size_t(N_ * m) || u_hi.size() != u_lo.size() ||
      gi_lo.size() != std::size_t(m * m) || gi_hi.size() != gi_lo.size())
    throw std::invalid_argument("FarFilter: dimensions do not match");
  const double u = 0x1p-52;
  const double gammaN = (N_ * u) / (1 - N_ * u), gammaM = ((m * m + 2) * u) / (1 - (m * m + 2) * u);
  u_.resize(u_lo.size());
  g_.resize(gi_lo.size());
  auto mid_rad = [](double lo, double hi, double& mid) {  // step 7
    mid = lo / 2 + hi / 2;
    return std::max(hi - mid, mid - lo) * kInflate + 0x1p-1020;
  };
  c_ = 0;
  for (std::size_t k = 0; k < u_.size(); ++k) {
    const double rho = mid_rad(u_lo[k], u_hi[k], u_[k]);
    c_ = std::max(c_, (rho / (1 - u) + (u / (1 - u) + gammaN) * std::abs(u_[k])) * kInflate);
    if (std::isnan(rho)) c_ = NAN;
  }
  c1_ = 0, c2_ = 0;
  for (std::size_t k = 0; k < g_.size(); ++k) {
    const double dm = mid_rad(gi_lo[k], gi_hi[k], g_[k]);
    c1_ += dm + gammaM * std::abs(g_[k]);
    c2_ += 2 * std::max(std::abs(gi_lo[k]), std::abs(gi_hi[k]));
  }
  c1_ *= kInflate, c2_ *= kInflate;
  if (!(threshold_ >= 0)) threshold_ = NAN;  // never discard
}

}  // namespace delcert::certify::detail
