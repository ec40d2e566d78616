#include "core/refine/hitting_sets.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/refine/simplex_measures.hpp"
#include "core/refine/weight_functions.hpp"

namespace delcert::refine {

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
using Set = std::array<std::uint32_t, kMaxSimplexVertices - 1>;  // candidate-local indices, sorted, kNone-padded

}  // namespace

std::optional<HittingSet> find_hitting_set(std::span<const double> x, const io::PointSet& points, const spatial::NeighbourIndex& index,
                                           const HittingQuery& query, HittingStats* stats) {
  HittingStats local;
  HittingStats& st = stats ? *stats : local;
  const int max_k = std::min(query.max_set_size, kMaxSimplexVertices - 1);
  if (max_k < 2 || !(query.radius_bound > 0)) return std::nullopt;
  const double bound2 = query.radius_bound * query.radius_bound;
  const double shrink = 1 - query.delta0 * query.delta0;
  const double reach = 2 * query.radius_bound / std::max(1e-300, shrink);
  const double reach2 = reach * reach;
  const std::vector<std::size_t> candidates = index.ball(x, reach2);
  st.candidates += candidates.size();
  const std::size_t n = candidates.size();
  if (n < 2) return std::nullopt;

  // Gram matrix of the candidates relative to x: every simplex x * S is read from it, so each
  // one costs O(k^2) instead of O(k^2 N).
  const int N = points.dimension;
  Eigen::MatrixXd E(static_cast<Eigen::Index>(n), N);
  for (std::size_t i = 0; i < n; ++i) {
    const auto q = points.point(candidates[i]);
    for (int j = 0; j < N; ++j) E(static_cast<Eigen::Index>(i), j) = q[j] - x[j];
  }
  const Eigen::MatrixXd G = E * E.transpose();
  auto dist2 = [&](std::uint32_t a, std::uint32_t b) { return std::max(0.0, G(a, a) + G(b, b) - 2 * G(a, b)); };

  auto geometry = [&](const Set& s, int k) {
    SimplexGeometry::SmallMatrix H = SimplexGeometry::SmallMatrix::Zero(k + 1, k + 1);
    for (int u = 0; u < k; ++u)
      for (int v = u; v < k; ++v) H(u + 1, v + 1) = H(v + 1, u + 1) = G(s[u], s[v]);
    return SimplexGeometry::from_gram(H);
  };
  // Necessary for lying under a hitting flake (see the header): the face's smallest weighted
  // radius is below the bound. Lemma 4.1 (2) first, as a cheap test: R >= (1 - δ0^2) Δ / 2.
  auto feasible = [&](const SimplexGeometry& g) {
    const double half = shrink * g.longest_edge() / 2;
    if (half * half >= bound2) return false;
    return min_weighted_radius2(g, query.delta0).radius2 < bound2;
  };

  // Level 1: candidates q whose edge x * q may lie under a hitting flake.
  std::vector<Set> level;
  std::vector<std::uint32_t> singles;
  for (std::uint32_t i = 0; i < n; ++i) {
    Set s;
    s.fill(kNone);
    s[0] = i;
    ++st.simplices;
    if (!(G(i, i) > 0)) continue;  // x on an existing point: a degenerate edge is bad
    if (feasible(geometry(s, 1))) {
      level.push_back(s);
      singles.push_back(i);
    }
  }

  // adjacency[a]: bit set of the b with x * {a, b} a good, radius-feasible triangle (level 2).
  // A set T can only grow from level k-1 to k when every pair in it is adjacent, so the new
  // vertex is drawn from the intersection of its members' rows.
  const std::size_t words = (n + 63) / 64;
  std::vector<std::uint64_t> adjacency;
  std::vector<std::uint64_t> common(words);

  for (int k = 2; k <= max_k && !level.empty(); ++k) {
    std::vector<Set> next;
    for (const Set& S : level) {
      // The candidates for the new vertex q > S[k-2].
      std::vector<std::uint32_t> options;
      if (k == 2) {
        auto from = std::upper_bound(singles.begin(), singles.end(), S[0]);
        for (auto it = from; it != singles.end(); ++it)
          if (dist2(S[0], *it) < reach2) options.push_back(*it);
      } else {
        std::fill(common.begin(), common.end(), ~std::uint64_t{0});
        for (int i = 0; i < k - 1; ++i)
          for (std::size_t w = 0; w < words; ++w) common[w] &= adjacency[S[i] * words + w];
        for (std::size_t w = 0; w < words; ++w)
          for (std::uint64_t bits = common[w]; bits; bits &= bits - 1) {
            const auto q = static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits)));
            if (q > S[k - 2]) options.push_back(q);
          }
      }
      for (const std::uint32_t q : options) {
        Set T = S;
        T[k - 1] = q;
        // Every (k-1)-subset of T must be a good, radius-feasible x * S' (the one without q is S;
        // for k = 3 the pairs are exactly the adjacency).
        bool ok = true;
        for (int drop = 0; k >= 4 && drop + 1 < k && ok; ++drop) {
          Set sub;
          sub.fill(kNone);
          for (int i = 0, j = 0; i < k; ++i)
            if (i != drop) sub[j++] = T[i];
          ok = std::binary_search(level.begin(), level.end(), sub);
        }
        if (!ok) continue;
        SimplexGeometry g = geometry(T, k);
        ++st.simplices;
        const FaceMask all = g.all();
        const FaceMask without_x = all & ~FaceMask{1};
        // The face T itself (not containing x): its own proper faces are faces of the good
        // x * S' above, so only its own thickness is left to check.
        if (!g.face_thick(without_x, query.gamma0)) continue;
        if (g.face_thick(all, query.gamma0)) {
          if (k < max_k && feasible(g)) next.push_back(T);
          continue;
        }
        // x * T is Γ0-bad with every proper face good: a Γ0-flake.
        ++st.flakes;
        MinWeightedRadius mw = min_weighted_radius2(g, query.delta0);
        if (mw.radius2 < bound2) {
          HittingSet h;
          for (int i = 0; i < k; ++i) h.points.push_back(candidates[T[i]]);
          h.radius2 = mw.radius2;
          h.weighted_vertex = mw.vertex;
          h.t = mw.t;
          return h;
        }
      }
    }
    level = std::move(next);  // generated in lexicographic order
    if (k == 2) {
      adjacency.assign(n * words, 0);
      for (const Set& T : level) {
        adjacency[T[0] * words + T[1] / 64] |= std::uint64_t{1} << (T[1] % 64);
        adjacency[T[1] * words + T[0] / 64] |= std::uint64_t{1} << (T[0] % 64);
      }
    }
  }
  return std::nullopt;
}

}  // namespace delcert::refine
