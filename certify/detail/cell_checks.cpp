#include "certify/detail/cell_checks.hpp"

#include <algorithm>

#include "exact/interval_arithmetic.hpp"

namespace delcert::certify::detail {

bool others_strictly_farther(const io::PointSet& points, const PointGrid& grid, int p, const std::vector<int>& simplex,
                             const exact::Box& X) {
  using IA = exact::IntervalNumber;
  exact::UpwardRounding up;
  const int N = static_cast<int>(X.size());
  const auto pp = points.point(p);
  std::vector<double> c(N);
  IA dp(0), dc(0);
  for (int v = 0; v < N; ++v) {
    c[v] = X[v].midpoint();
    dp += exact::square(exact::to_interval_number(X[v]) - IA(pp[v]));
    dc += exact::square(exact::to_interval_number(X[v]) - IA(c[v]));
  }
  const double R = (exact::sqrt(dp) + exact::sqrt(dc)).sup();
  for (int q : grid.ball(c, R)) {
    if (std::binary_search(simplex.begin(), simplex.end(), q)) continue;
    IA s(0);  // |q - p|^2 - 2 (x - p).(q - p) = d(x, q)^2 - d(x, p)^2
    for (int v = 0; v < N; ++v) {
      const IA d = IA(points.point(q)[v]) - IA(pp[v]);
      s += exact::square(d) - IA(2) * (exact::to_interval_number(X[v]) - IA(pp[v])) * d;
    }
    if (!(s.inf() > 0)) return false;
  }
  return true;
}

bool faces_known(int p, int m, const std::vector<int>& S, const std::vector<RestrictedVoronoiVertex>& vertices,
                 const std::vector<RestrictedVoronoiVertex>& face_points, std::vector<int>& face) {
  const int n = static_cast<int>(S.size());
  if (n > m) return false;  // only resolved boxes are asked (n <= m); 1 << n stays small
  for (int size = std::min(n, m - 1); size >= 0; --size)
    for (int mask = (1 << n) - 1; mask >= 0; --mask) {
      if (__builtin_popcount(mask) != size) continue;
      std::vector<int> C{p};
      for (int i = 0; i < n; ++i)
        if (mask >> i & 1) C.push_back(S[i]);
      std::sort(C.begin(), C.end());
      auto holds = [&](const auto& v) { return std::includes(v.simplex.begin(), v.simplex.end(), C.begin(), C.end()); };
      if (std::none_of(vertices.begin(), vertices.end(), holds) && std::none_of(face_points.begin(), face_points.end(), holds)) {
        face = std::move(C);
        return false;
      }
    }
  return true;
}

}  // namespace delcert::certify::detail
