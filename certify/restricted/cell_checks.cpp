#include "certify/restricted/cell_checks.hpp"

#include <algorithm>
#include <string>

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

double farthest_vertex(const RestrictedCellReport& report, const io::PointSet& points, int p) {
  using IA = exact::IntervalNumber;
  exact::UpwardRounding up;
  double far = 0;
  for (const auto& v : report.vertices) {
    IA d(0);
    for (std::size_t i = 0; i < v.x.size(); ++i) d += exact::square(exact::to_interval_number(v.x[i]) - IA(points.point(p)[i]));
    far = std::max(far, exact::sqrt(d).inf());
  }
  return far;
}

void finish_report(RestrictedCellReport& report, int p, double r) {
  auto& V = report.vertices;
  std::sort(V.begin(), V.end(), [](const auto& x, const auto& y) {
    if (x.simplex != y.simplex) return x.simplex < y.simplex;
    for (std::size_t i = 0; i < x.x.size(); ++i)
      if (x.x[i].lo != y.x[i].lo) return x.x[i].lo < y.x[i].lo;
    return false;
  });
  std::vector<RestrictedVoronoiVertex> out;
  for (auto& v : V) {
    auto same = [&](const RestrictedVoronoiVertex& o) {  // the same simplex, overlapping enclosures
      for (std::size_t i = 0; i < v.x.size(); ++i)
        if (o.x[i].hi < v.x[i].lo || v.x[i].hi < o.x[i].lo) return false;
      return o.simplex == v.simplex;
    };
    if (std::none_of(out.begin(), out.end(), same)) out.push_back(std::move(v));
  }
  V = std::move(out);
  std::sort(report.face_points.begin(), report.face_points.end(),
            [](const auto& x, const auto& y) { return x.simplex < y.simplex; });
  if (V.empty() && report.face_points.empty() && report.kept > 0)
    report.unresolved_faces.push_back({report.covering_location, {p},
                                       "the cell of p may hold points of M but has no restricted Voronoi vertex"});
  if (!report.undecided.empty())
    report.reason = std::to_string(report.undecided.size()) + " undecided boxes";
  else if (!(report.covering_bound < r))
    report.reason = "cell reaches the chart boundary";
  report.complete = report.reason.empty();
}

}  // namespace delcert::certify::detail
