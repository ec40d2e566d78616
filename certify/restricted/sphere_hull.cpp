#include "certify/restricted/sphere_hull.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "certify/detail/parallel.hpp"
#include "exact/interval.hpp"

namespace delcert::certify::detail {

using exact::IntervalNumber;

double circumradius_upper(const std::vector<std::vector<IntervalNumber>>& a) {
  const int k = static_cast<int>(a.size()) - 1, D = static_cast<int>(a[0].size());  // k: the simplex's dimension
  std::vector<std::vector<IntervalNumber>> e(k, std::vector<IntervalNumber>(D));
  for (int j = 0; j < k; ++j)
    for (int v = 0; v < D; ++v) e[j][v] = a[j + 1][v] - a[0][v];
  std::vector<std::vector<IntervalNumber>> G(k, std::vector<IntervalNumber>(k));
  std::vector<IntervalNumber> b(k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      IntervalNumber d(0);
      for (int v = 0; v < D; ++v) d += e[i][v] * e[j][v];
      G[i][j] = d;
    }
    b[i] = G[i][i] / 2;
  }
  std::vector<const IntervalNumber*> rows;
  for (auto& g : G) rows.push_back(g.data());
  const IntervalNumber det = laplace(rows, 0, k);
  if (!(det.inf() > 0)) return INFINITY;  // a Gram determinant is >= 0; not bounded away from 0
  std::vector<IntervalNumber> o(D, IntervalNumber(0));
  for (int j = 0; j < k; ++j) {  // Cramer: lambda_j = det(G with column j replaced by b) / det
    std::vector<std::vector<IntervalNumber>> Gj = G;
    for (int i = 0; i < k; ++i) Gj[i][j] = b[i];
    std::vector<const IntervalNumber*> rj;
    for (auto& g : Gj) rj.push_back(g.data());
    const IntervalNumber lambda = laplace(rj, 0, k) / det;
    for (int v = 0; v < D; ++v) o[v] += lambda * e[j][v];
  }
  IntervalNumber r2(0);
  for (int v = 0; v < D; ++v) r2 += exact::square(o[v]);
  const double bound = exact::sqrt(r2).sup();
  return std::isfinite(bound) ? bound : INFINITY;
}

std::vector<int> canonical(const LiftedSphere& S, const std::vector<int>& ids) {
  std::vector<int> a(ids);
  std::sort(a.begin(), a.end());
  if (!S.antipode) return a;
  std::vector<int> b;
  for (int i : a) b.push_back(S.antipode(i));
  std::sort(b.begin(), b.end());
  return std::min(a, b);
}

HullDecision decide_facet(const LiftedSphere& S, const std::vector<int>& facet) {
  HullDecision d;
  d.centre_side = S.centre_side(facet);
  std::vector<int> tested;
  if (d.centre_side != 0) {
    LiftedSphere::Cap cap = S.cap(facet);
    d.radius = cap.radius;
    if (std::isfinite(cap.radius)) tested = std::move(cap.ids);
  }
  const bool all = !std::isfinite(d.radius);
  if (all)
    for (std::size_t q = 0; q < S.count; ++q) tested.push_back(static_cast<int>(q));
  const std::set<int> in_facet(facet.begin(), facet.end());
  int& tie = d.tie;
  int& unknown = d.unknown;
  std::vector<int> rows(facet);
  rows.push_back(-1);
  for (int q : tested) {
    if (in_facet.count(q)) continue;
    ++d.tested;
    rows[S.D] = q;
    const HullSide side = S.orient(rows);
    if (side == HullSide::positive && d.both_sides[0] < 0) d.both_sides[0] = q;
    if (side == HullSide::negative && d.both_sides[1] < 0) d.both_sides[1] = q;
    if (side == HullSide::zero && tie < 0) tie = q;
    if (side == HullSide::unknown && unknown < 0) unknown = q;
    if (d.both_sides[0] >= 0 && d.both_sides[1] >= 0) break;  // rejected, whatever the rest
  }
  if (!all && tested.size() < S.count) {  // an id not tested: strictly on the origin's side (header)
    std::size_t t = 0;
    for (int q = 0; q < static_cast<int>(S.count); ++q) {
      while (t < tested.size() && tested[t] < q) ++t;
      if ((t < tested.size() && tested[t] == q) || in_facet.count(q)) continue;
      d.untested = q;
      break;
    }
    int& slot = d.both_sides[d.centre_side > 0 ? 0 : 1];
    if (d.untested >= 0 && slot < 0) slot = d.untested;
  }
  if (d.both_sides[0] >= 0 && d.both_sides[1] >= 0) {
    d.kind = HullDecision::Kind::rejected;
  } else if (tie < 0 && unknown < 0 && d.tested + (d.untested >= 0 ? 1 : 0) > 0) {
    d.kind = HullDecision::Kind::certified;
    d.empty_cap_small = d.centre_side != 0 && ((d.centre_side > 0) == (d.both_sides[0] >= 0));
  }
  return d;
}

void decide_facets(const LiftedSphere& S, const std::vector<std::vector<int>>& batch,
                   std::map<std::vector<int>, HullDecision>& decided, int threads) {
  std::set<std::vector<int>> fresh;
  for (const auto& f : batch) {
    std::vector<int> c = canonical(S, f);
    if (!decided.count(c)) fresh.insert(std::move(c));
  }
  const std::vector<std::vector<int>> todo(fresh.begin(), fresh.end());
  std::vector<HullDecision> out(todo.size());
  parallel_for(todo.size(), threads, [&](std::size_t k, int) { out[k] = decide_facet(S, todo[k]); });
  for (std::size_t k = 0; k < todo.size(); ++k) decided.emplace(todo[k], std::move(out[k]));
}

namespace {

// canonical ridge -> the opposite id of each certified facet through it, in the ridge's frame
std::map<std::vector<int>, std::vector<int>> ridges_of(const LiftedSphere& S,
                                                       const std::map<std::vector<int>, HullDecision>& decided) {
  std::map<std::vector<int>, std::vector<int>> count;
  for (const auto& [facet, d] : decided) {
    if (d.kind != HullDecision::Kind::certified) continue;
    for (std::size_t drop = 0; drop < facet.size(); ++drop) {
      std::vector<int> r;
      for (std::size_t i = 0; i < facet.size(); ++i)
        if (i != drop) r.push_back(facet[i]);
      std::vector<int> key = canonical(S, r);
      count[key].push_back(key == r ? facet[drop] : S.antipode(facet[drop]));
    }
  }
  return count;
}

}  // namespace

std::optional<OpenRidge> wrap_and_count(const LiftedSphere& S, std::map<std::vector<int>, HullDecision>& decided,
                                        int threads) {
  // GIFT WRAPPING. The candidates may miss facets (their sources are other complexes). Across a
  // ridge that lies in one certified facet f = ridge + {a} only, K's other facet is ridge + {q}
  // for the q whose hyperplane leaves every point on a's side: found in floating point (Jarvis's
  // rule on the approximate unit vectors near the ridge), then DECIDED like any candidate. Rounds
  // until no new candidate appears (each round decides at most one new candidate per open ridge).
  const int D = S.D;
  if (D > 7) throw std::invalid_argument("wrap_and_count: dimension above 7");
  auto orient_f = [&](const std::vector<int>& rows) {  // sign of det [[1, x_j]] in doubles (a guess)
    double a[8][8];  // D <= 7: Gaussian elimination with partial pivoting, no allocation
    for (int j = 0; j <= D; ++j) {
      a[j][0] = 1;
      for (int v = 0; v < D; ++v) a[j][v + 1] = S.approx[rows[j]][v];
    }
    int sign = 1;
    for (int c = 0; c <= D; ++c) {
      int p = c;
      for (int r = c + 1; r <= D; ++r)
        if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
      if (a[p][c] == 0) return 0;
      if (p != c) std::swap(a[p], a[c]), sign = -sign;
      if (a[c][c] < 0) sign = -sign;
      for (int r = c + 1; r <= D; ++r) {
        const double f = a[r][c] / a[c][c];
        for (int v = c; v <= D; ++v) a[r][v] -= f * a[c][v];
      }
    }
    return sign;
  };
  for (int round = 0; round < 64; ++round) {
    std::vector<std::vector<int>> fresh;
    for (const auto& [ridge, opposite] : ridges_of(S, decided)) {
      if (opposite.size() != 1) continue;
      const int a = opposite[0];
      double reach = 0;  // the facet's diameter on the unit sphere (approximate: it only sizes the search)
      std::vector<int> facet(ridge);
      facet.push_back(a);
      for (int i : facet)
        for (int j : facet) {
          double d2 = 0;
          for (int v = 0; v < D; ++v) d2 += (S.approx[i][v] - S.approx[j][v]) * (S.approx[i][v] - S.approx[j][v]);
          reach = std::max(reach, std::sqrt(d2));
        }
      int q = -1;
      for (double chord = 2 * reach; q < 0 && chord < 8; chord *= 2) {
        std::vector<int> rows(ridge);
        rows.push_back(-1), rows.push_back(-1);
        for (int r : S.near(ridge, chord)) {
          if (r == a || std::count(ridge.begin(), ridge.end(), r)) continue;
          if (q < 0) {
            q = r;
            continue;
          }
          rows[D - 1] = q, rows[D] = a;
          const int sa = orient_f(rows);
          rows[D] = r;
          if (sa != 0 && orient_f(rows) == -sa) q = r;  // r beyond the plane through ridge + q: turn to it
        }
        if (q >= 0) {
          std::vector<int> rows2(ridge);
          rows2.push_back(q), rows2.push_back(a);
          if (orient_f(rows2) == 0) q = -1;
        }
        if (chord == 0) break;
      }
      if (q < 0) continue;
      std::vector<int> candidate(ridge);
      candidate.push_back(q);
      if (!decided.count(canonical(S, candidate))) fresh.push_back(candidate);
    }
    if (fresh.empty()) break;
    decide_facets(S, fresh, decided, threads);
  }
  for (const auto& [ridge, opposite] : ridges_of(S, decided))
    if (opposite.size() != 2) return OpenRidge{ridge, static_cast<int>(opposite.size())};
  return std::nullopt;
}

}  // namespace delcert::certify::detail
