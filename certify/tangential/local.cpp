#include "certify/tangential/local.hpp"

#include "certify/detail/grid.hpp"

namespace delcert::certify::detail {

using exact::to_interval_number;

// Enclosure of the Gram matrix G = U^T U of the exact basis (m x m).
std::vector<IA> gram_enclosure(const exact::TangentSpace& T, int m) {
  std::vector<IA> g(m * m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) g[a * m + b] = to_interval_number(T.gram_enclosure(a, b));
  return g;
}

// The Local of the points `glob` (glob[0] = p, the rest increasing). T may be null (the exact
// tangent space is then built only if the chart is needed). tangent_only: only the enclosures of
// b(x) (check 7); s(x) is left 0 and drows empty. coords: when given, coords[l] holds the
// coordinates of glob[l] (equal to the points', e.g. the grid's copy, read in sequence).
Local make_local_of(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                    std::vector<int> glob, double radius, bool tangent_only,
                    const std::vector<const double*>* coords) {
  const io::PointSet& P = *S.points;
  Local L{S.m, P.dimension, std::move(glob), &P, T, S.system, std::nullopt, std::nullopt, {}, {}, {}, radius, false};
  L.all = L.global.size() == P.size();
  const int m = S.m, N = P.dimension;
  L.rows.assign(L.global.size() * (m + 1), IA(0));
  if (!tangent_only) L.drows.assign(L.global.size() * (m + 1), 0);
  const auto pp = P.point(L.global[0]);
  for (std::size_t l = 1; l < L.global.size(); ++l) {
    const double* x = coords ? (*coords)[l] : P.point(L.global[l]).data();
    IA* r = L.rows.data() + l * (m + 1);
    for (int i = 0; i < N; ++i) {
      IA d = IA(x[i]) - IA(pp[i]);
      for (int a = 0; a < m; ++a) r[a] += U[i * m + a] * d;
      if (!tangent_only) r[m] += exact::square(d);
    }
    if (!tangent_only)
      for (int a = 0; a <= m; ++a) L.drows[l * (m + 1) + a] = 0.5 * (r[a].inf() + r[a].sup());
  }
  L.gram = gram;
  return L;
}

// The Local of p and the points `near` ((index, coordinates) pairs, in any order, possibly with
// repeats; p itself left out): sorted by index, each once. Clears `near`.
Local make_local_of_near(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                         int p, std::vector<std::pair<int, const double*>>& near, double radius, bool tangent_only) {
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first == b.first; }), near.end());
  std::vector<int> glob(near.size() + 1);
  std::vector<const double*> coords(near.size() + 1, S.points->point(p).data());
  glob[0] = p;
  for (std::size_t k = 0; k < near.size(); ++k) glob[k + 1] = near[k].first, coords[k + 1] = near[k].second;
  near.clear();
  return make_local_of(S, T, U, gram, std::move(glob), radius, tangent_only, &coords);
}

// The Local of every point within `radius` of p (and possibly more: the grid's superset).
Local make_local(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                 int p, double radius) {
  thread_local std::vector<std::pair<int, const double*>> near;  // scratch (capacity reused)
  near.clear();
  S.grid->visit_ball(S.points->point(p), radius, [&](int q, const double* x) {
    if (q != p) near.emplace_back(q, x);
  });
  Local L = make_local_of_near(S, T, U, gram, p, near, radius, false);
  L.covered = S.grid->covers(S.points->point(p), radius);
  return L;
}

}  // namespace delcert::certify::detail
