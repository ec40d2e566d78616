#include "exact/max_affine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "exact/interval.hpp"
#include "exact/small_buffer.hpp"

namespace delcert::exact {

double max_affine_upper_bound(std::span<const double> F, std::span<const double> S, int nq) {
  const int nc = static_cast<int>(F.size());
  if (nq < 0 || S.size() != F.size() * static_cast<std::size_t>(nq))
    throw std::invalid_argument("max_affine_upper_bound: S must be #F by num_q");
  constexpr double inf = std::numeric_limits<double>::infinity();
  UpwardRounding up;
  SmallBuffer<double, 16> lambda(nq);
  SmallBuffer<double, 16> A(nc);
  auto value = [&]() -> double {  // max_c (F_c + sum lambda_q S_cq), every operation rounded up
    double best = -inf;
    for (int c = 0; c < nc; ++c) {
      double v = F[c];
      for (int j = 0; j < nq; ++j)
        if (lambda[j] > 0) v += lambda[j] * S[c * nq + j];
      if (std::isnan(v)) return inf;
      best = std::max(best, v);
    }
    return best;
  };
  for (int sweep = 0; sweep < 2; ++sweep)
    for (int j = 0; j < nq; ++j) {
      bool falls = false;  // lambda_j > 0 can lower the maximum only if some S_cj < 0
      for (int c = 0; c < nc; ++c) {
        A[c] = F[c];
        for (int i = 0; i < nq; ++i)
          if (i != j && lambda[i] > 0) A[c] += lambda[i] * S[c * nq + i];
        falls |= S[c * nq + j] < 0;
      }
      if (!falls) continue;
      auto phi = [&](double t) {
        double v = -inf;
        for (int c = 0; c < nc; ++c) v = std::max(v, A[c] + t * S[c * nq + j]);
        return v;
      };
      double best_t = 0, best = phi(0);
      for (int c = 0; c < nc; ++c)
        for (int e = 0; e < nc; ++e) {
          const double sc = S[c * nq + j], se = S[e * nq + j];
          if (!(sc > 0 && se < 0)) continue;
          const double t = (A[e] - A[c]) / (sc - se);
          if (!(t > 0) || !std::isfinite(t)) continue;
          const double v = phi(t);
          if (v < best) best = v, best_t = t;
        }
      lambda[j] = best_t;
    }
  return value();
}

}  // namespace delcert::exact
