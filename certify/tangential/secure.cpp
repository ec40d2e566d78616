// Check 7 at one sample point p (analyse_secure, star.hpp): are the simplices of star(p) secure (paper
// Definition 3.1)? The tangential star itself is star.cpp's.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

#include "certify/detail/grid.hpp"
#include "certify/tangential/far_filter.hpp"
#include "certify/tangential/local.hpp"
#include "certify/tangential/star.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_predicates.hpp"

namespace delcert::certify {

using detail::gram_enclosure;
using detail::IA;
using detail::kMaxM;
using detail::kNeededRadiusMargin;
using detail::List;
using detail::Local;
using detail::make_local_of_near;
using exact::determinant;
using exact::to_interval_number;

namespace {

// Check 7 (Definition 3.1): the points of W = B(p, kSecureNeighbourhoodEps * eps) are tested,
// with bounded work per point: one grid query of the box where a point can matter
// (analyse_secure), at most kMaxSecureNeighbourhood points of W in it, a floating-point bound per
// point (detail/far_filter.hpp) and an interval projection of the few it keeps.
constexpr double kSecureNeighbourhoodEps = 5;
constexpr int kMaxSecureNeighbourhood = 50000;

// Three-valued comparison a > b: 1 certainly, 0 certainly not, -1 undecided (intervals only).
int greater(const IA& a, const IA& b) {
  if (a.inf() > b.sup()) return 1;
  if (a.sup() <= b.inf()) return 0;
  return -1;
}
int greater(const mpq_class& a, const mpq_class& b) { return a > b ? 1 : 0; }
IA lower_max(const IA& a, const IA& b) { return exact::interval_max(a, b); }
mpq_class lower_max(const mpq_class& a, const mpq_class& b) { return a > b ? a : b; }

// The projected circumcentre c' = p + U w of the cell c (local indices, c[0] = p) from the rows
// b(x) and t(x) = |pi_p(x) - p|^2 of its vertices: y = 2w solves B y = h (B the rows b(v_i), h_i =
// t(v_i)) by Cramer's rule, and r^2 = w^T G w. Returns 1 with y and r2 set, 0 when det B = 0,
// -1 when an interval determinant does not exclude 0.
template <class T>
int projected_circumcentre(const List& c, const std::vector<T>& b, const std::vector<T>& t, const std::vector<T>& G, int m,
                           std::array<T, kMaxM>& y, T& r2) {
  std::array<T, kMaxM * kMaxM> A;
  std::array<T, kMaxM> h;
  A.fill(T(0));
  h.fill(T(0));
  for (int i = 0; i < m; ++i) {
    for (int a = 0; a < m; ++a) A[i * m + a] = b[c[i + 1] * m + a];
    h[i] = t[c[i + 1]];
  }
  T d = determinant(A.data(), m);
  if (greater(d, T(0)) != 1 && greater(T(0), d) != 1) return greater(d, T(0)) == 0 && greater(T(0), d) == 0 ? 0 : -1;
  y.fill(T(0));
  exact::cramer_solve(A.data(), h.data(), d, m, y.data());
  r2 = T(0);
  for (int a = 0; a < m; ++a)
    for (int k = 0; k < m; ++k) r2 += y[a] * G[a * m + k] * y[k];
  r2 = r2 / T(4);
  return 1;
}

// The conditions of Definition 3.1 for one cell, in number type T (IA: enclosures; mpq_class:
// exact). rows: b(x) (m entries) per local point; t: |pi_p(x) - p|^2 = b^T G^-1 b per local
// point. Returns "" when secure, else the first failed condition; `undecided` when an interval
// comparison could not decide. The points tested for delta-protection are those of by_t (every
// point that can matter, by increasing projected distance), in that order for both number types,
// so that the named point does not depend on the filter.
template <class T>
std::string secure_cell(const Local& L, const List& c, const std::vector<int>& by_t, const std::vector<T>& b, const std::vector<T>& t,
                        const std::vector<T>& G, const std::vector<T>& Ginv, const T& eps2, const T& delta,
                        const T& ups2, const T& short2, bool& undecided) {
  const int m = L.m;
  auto fail_or = [&](int g, const char* what) -> std::string {
    if (g < 0) undecided = true;
    return g == 1 ? what : "";
  };
  std::array<T, kMaxM> y;  // y = 2w, the projected circumcentre c' = p + U w
  T r2(0);
  const int centre = projected_circumcentre(c, b, t, G, m, y, r2);
  if (centre != 1) {
    if (centre == 0) return "degenerate projection";
    undecided = true;
    return "";
  }
  std::string f;
  if (!(f = fail_or(greater(r2, eps2) == 1 ? 1 : greater(eps2, r2) == 1 ? 0 : -1, "circumradius >= eps")).empty()) return f;
  // Squared distances between the projected vertices (vertex 0 is p: b = 0, t = 0).
  const int V = m + 1;
  std::array<T, (kMaxM + 1) * (kMaxM + 1)> dm;
  dm.fill(T(0));
  auto inner = [&](int u, int v) {
    T s(0);
    for (int a = 0; a < m; ++a)
      for (int k = 0; k < m; ++k) s += b[u * m + a] * Ginv[a * m + k] * b[v * m + k];
    return s;
  };
  T longest(0);
  int short_fail = 0;
  for (int i = 0; i < V; ++i)
    for (int j = i + 1; j < V; ++j) {
      T dij = (i == 0) ? t[c[j]] : T(t[c[i]] + t[c[j]] - T(2) * inner(c[i], c[j]));
      dm[i * V + j] = dm[j * V + i] = dij;
      longest = lower_max(longest, dij);
      int g = greater(short2, dij);
      if (g == 1) short_fail = 1;
      else if (g < 0 && short_fail == 0) short_fail = -1;
    }
  if (!(f = fail_or(short_fail, "shortest edge < mu0 eps")).empty()) return f;
  // Thickness (paper §2.2) by Gram determinants: D(v_l)^2 = det G(s) / det G(facet_l), so
  // Upsilon >= u  <=>  det(2G(s)) >= 2 u^2 m^2 Delta^2 det(2G(facet_l)) for every l.
  auto gram_det = [&](const int* idx, int j) {  // idx: j + 1 vertex positions
    if (j == 0) return T(1);
    std::array<T, kMaxM * kMaxM> g;
    g.fill(T(0));
    for (int a = 0; a < j; ++a)
      for (int k = 0; k < j; ++k)
        g[a * j + k] = dm[idx[0] * V + idx[a + 1]] + dm[idx[0] * V + idx[k + 1]] - dm[idx[a + 1] * V + idx[k + 1]];
    return determinant(g.data(), j);
  };
  std::array<int, kMaxM + 1> all;
  for (int i = 0; i < V; ++i) all[i] = i;
  T gt = gram_det(all.data(), m);
  int thick_fail = 0;
  for (int l = 0; l < V; ++l) {
    std::array<int, kMaxM + 1> facet;
    for (int i = 0, n = 0; i < V; ++i)
      if (i != l) facet[n++] = i;
    int g = greater(T(2) * ups2 * T(m * m) * longest * gram_det(facet.data(), m - 1), gt);
    if (g == 1) thick_fail = 1;
    else if (g < 0 && thick_fail == 0) thick_fail = -1;
  }
  if (!(f = fail_or(thick_fail, "thickness < upsilon0")).empty()) return f;
  // delta-protection: |c' - q'| > r + delta  <=>  e = |c' - q'|^2 - r^2 - delta^2 > 0 and e^2 > 4 delta^2 r^2.
  int prot_fail = 0;
  const T delta2 = delta * delta, four_delta2_r2 = T(4) * delta * delta * r2;  // the same operations as per point
  // Points projected beyond 2r + delta from p are certainly protected (interval instantiation
  // only; the exact one tests every point). Not IA(INFINITY): a point interval must be finite.
  IA reach2(0);
  if constexpr (std::is_same_v<T, IA>) reach2 = exact::square(IA(2) * exact::sqrt(r2) + delta);
  for (int k = 1; k < L.size(); ++k) {
    const int q = by_t.empty() ? k : by_t[k - 1];
    if (q < 0) break;  // end of the relevant points
    if constexpr (std::is_same_v<T, IA>)  // |c' - q'| >= |q'| - r > r + delta; by_t is increasing
      if (t[q].inf() > reach2.sup()) break;
    if (std::find(c.begin(), c.begin() + m + 1, q) != c.begin() + m + 1) continue;
    T e = t[q] - delta2;
    for (int a = 0; a < m; ++a) e -= b[q * m + a] * y[a];
    int g1 = greater(e, T(0));
    int g2 = g1 == 1 ? greater(e * e, four_delta2_r2) : g1;
    if (g1 == 0 || g2 == 0) {
      // The witness is the first failing point in by_t order, whichever path decides: when an
      // earlier point was undecided, leave the naming to the exact evaluation.
      if (prot_fail < 0) {
        undecided = true;
        return "";
      }
      return "not delta-protected (point " + std::to_string(L.global[q]) + ")";
    }
    if (g1 < 0 || g2 < 0) prot_fail = -1;
  }
  if (prot_fail < 0) undecided = true;
  return "";
}

}  // namespace

void SecureParams::prepare() {
  eps2_enclosure = exact::enclose(eps * eps);
  delta_enclosure = exact::enclose(delta);
  upsilon0_2_enclosure = exact::enclose(upsilon0 * upsilon0);
  shortest2_enclosure = exact::enclose(shortest * shortest);
}

SecureReport analyse_secure(const StarSettings& S, int p, const std::vector<Simplex>& star, const SecureParams& sp,
                            exact::FilterContext& ctx, const StarReport* report) {
  const io::PointSet& P = *S.points;
  const int m = S.m, N = P.dimension;
  SecureReport out;
  if (star.empty()) return out;
  exact::UpwardRounding upward;
  // The enclosures of the exact basis and Gram matrix from the star analysis of p when given
  // (the same values: enclose() of the same rationals); the exact tangent space itself is then
  // built only for an exact fallback (Local::chart()).
  std::optional<exact::TangentSpace> T;
  std::vector<IA> U(N * m), Gram(m * m);
  if (report && report->basis_enclosure.size() == U.size() && report->gram_enclosure.size() == Gram.size()) {
    for (std::size_t i = 0; i < U.size(); ++i) U[i] = to_interval_number(report->basis_enclosure[i]);
    for (std::size_t i = 0; i < Gram.size(); ++i) Gram[i] = to_interval_number(report->gram_enclosure[i]);
  } else {
    T.emplace(*S.system, P.point(p));
    for (int i = 0; i < N; ++i)
      for (int a = 0; a < m; ++a) U[i * m + a] = to_interval_number(exact::enclose(T->basis(i, a)));
    Gram = gram_enclosure(*T, m);
  }
  // The points of W = B(p, 5 eps): a superset from the grid (testing more points is stricter),
  // grown if needed to contain the cells' vertices.
  double r = kSecureNeighbourhoodEps * exact::enclose(sp.eps).hi;
  for (const auto& s : star)
    for (int v : s) {
      double d2 = 0;
      for (int k = 0; k < N; ++k) d2 += (P.point(v)[k] - P.point(p)[k]) * (P.point(v)[k] - P.point(p)[k]);
      r = std::max(r, std::sqrt(d2) * kNeededRadiusMargin);
    }
  // Enclosure of G^-1 by the adjugate: (G^-1)_ak = (-1)^(a+k) det(G without row k, column a) / det G.
  std::vector<IA> G(Gram), Gi(m * m);
  {
    const IA d = determinant(G.data(), m);
    exact::adjugate(G.data(), m, Gi.data());
    for (IA& x : Gi) x = x / d;  // G is positive definite: d > 0
  }
  // The points that can matter for delta-protection are those projected within 2r + delta of p,
  // r the cell's projected circumradius: a point projected farther is at distance > r + delta from
  // the projected circumcentre (|c' - p| = r), protected. Only cells with r <= eps reach that test
  // (the circumradius condition comes first), so 2 r_max + delta bounds every cell's reach, with
  // r_max the largest r over the star (from its vertices alone; eps where an interval determinant
  // leaves a cell's centre open), capped at eps.
  double r_max = exact::sqrt(IA(sp.eps2_enclosure.lo, sp.eps2_enclosure.hi)).sup();
  {
    std::vector<int> vs;
    for (const auto& s : star)
      for (int v : s)
        if (v != p) vs.push_back(v);
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    std::vector<IA> bv((vs.size() + 1) * m, IA(0)), tv(vs.size() + 1, IA(0));  // row 0: p itself
    for (std::size_t k = 0; k < vs.size(); ++k) {
      IA* row = bv.data() + (k + 1) * m;
      for (int i = 0; i < N; ++i) {
        const IA d = IA(P.point(vs[k])[i]) - IA(P.point(p)[i]);
        for (int a = 0; a < m; ++a) row[a] += U[i * m + a] * d;
      }
      for (int a = 0; a < m; ++a)
        for (int l = 0; l < m; ++l) tv[k + 1] += row[a] * Gi[a * m + l] * row[l];
    }
    double r_cells = 0;
    for (const auto& s : star) {
      List c{};
      for (int i = 0, k = 1; i <= m && k <= m; ++i)
        if (s[i] != p) c[k++] = 1 + static_cast<int>(std::lower_bound(vs.begin(), vs.end(), s[i]) - vs.begin());
      std::array<IA, kMaxM> y;
      IA r2(0);
      if (projected_circumcentre(c, bv, tv, G, m, y, r2) != 1 || !(r2.sup() <= DBL_MAX)) {
        r_cells = INFINITY;
        break;
      }
      r_cells = std::max(r_cells, exact::sqrt(IA(std::max(0.0, r2.sup()))).sup());
    }
    r_max = std::min(r_max, r_cells);
  }
  const double reach_all =
      r_max <= DBL_MAX ? exact::square(IA(2) * IA(r_max) + IA(sp.delta_enclosure.lo, sp.delta_enclosure.hi)).sup() : INFINITY;
  // W: every grid point of the ball. Its points that FarFilter proves projected beyond reach_all
  // are left out of L (they are protected for every cell, so testing them could only confirm it);
  // the star's vertices are always in. The rest are projected in interval arithmetic as before.
  // Scratch reused across the points of this thread (check 7 runs once per point).
  thread_local std::vector<std::pair<int, const double*>> kept;  // (index, coordinates)
  kept.clear();
  for (const auto& s : star)  // the star's vertices (in the ball: r covers them)
    for (int v : s)
      if (v != p) kept.emplace_back(v, P.point(v).data());
  std::vector<double> ulo(U.size()), uhi(U.size()), glo(Gi.size()), ghi(Gi.size());
  for (std::size_t i = 0; i < U.size(); ++i) ulo[i] = U[i].inf(), uhi[i] = U[i].sup();
  for (std::size_t i = 0; i < Gi.size(); ++i) glo[i] = Gi[i].inf(), ghi[i] = Gi[i].sup();
  const detail::FarFilter far(P.point(p), ulo, uhi, glo, ghi, m, reach_all);
  // Only the box of W where a point can be projected within reach_all is scanned: for v = x - p
  // with |v| <= r and |P_T v| <= a (P_T the orthogonal projector onto T_p, a^2 >= reach_all),
  //   |v_i| = |(P_T e_i).(P_T v) + (P_N e_i).(P_N v)| <= alpha_i a + beta_i r =: w_i,
  // alpha_i = |P_T e_i|, beta_i = |P_N e_i| = sqrt(1 - alpha_i^2), alpha_i^2 = e_i^T P_T e_i =
  // u_i^T G^-1 u_i (u_i the i-th row of the exact basis U: P_T = U G^-1 U^T). So every point of
  // the ball outside the box |v_i| <= w_i is projected beyond reach_all, protected for every cell
  // like those FarFilter discards. Upper bounds of alpha_i, beta_i, a and w_i: interval
  // arithmetic on the enclosures (upward rounding is on); a NaN or infinite bound keeps w_i = r.
  std::vector<double> half(N, r);
  if (reach_all >= 0 && reach_all <= DBL_MAX && r <= DBL_MAX) {
    const IA a = exact::sqrt(IA(reach_all));
    for (int i = 0; i < N; ++i) {
      IA alpha2(0);
      for (int k = 0; k < m; ++k)
        for (int l = 0; l < m; ++l) alpha2 += U[i * m + k] * Gi[k * m + l] * U[i * m + l];
      if (!(alpha2.sup() <= DBL_MAX) || !(alpha2.inf() >= -DBL_MAX)) continue;  // keeps w_i = r
      const IA alpha = exact::sqrt(IA(std::max(0.0, alpha2.sup()))),
               beta = exact::sqrt(IA(std::max(0.0, (IA(1) - alpha2).sup())));
      const double w = (alpha * a + beta * IA(r)).sup();
      if (w < r) half[i] = w;
    }
  }
  if (!S.grid->covers(P.point(p), r)) {  // an MPI rank whose halo does not hold W (never in one process)
    out.undecided = static_cast<long>(star.size()), out.halo_needed = r;
    return out;
  }
  std::size_t w_size = 1;  // p and the points of W in the box
  // The coordinates are the grid's copy, read in sequence; the filter unrolled for the common
  // dimensions (the same test: FarFilter::beyond_in).
  auto scan = [&]<int NN, int MM>() {
    S.grid->visit_ball(P.point(p), r, half, [&](int q, const double* x) {
      if (q == p) return;
      ++w_size;
      if (!far.beyond_in<NN, MM>(x)) kept.emplace_back(q, x);
    });
  };
  if (N == 3 && m == 2) scan.template operator()<3, 2>();
  else if (N == 4 && m == 3) scan.template operator()<4, 3>();
  else scan.template operator()<0, 0>();
  if (w_size > static_cast<std::size_t>(kMaxSecureNeighbourhood)) {  // bounded work per point
    out.undecided = static_cast<long>(star.size());
    return out;
  }
  Local L = make_local_of_near(S, T ? &*T : nullptr, U, Gram, p, kept, r, /*tangent_only=*/true);
  std::vector<mpq_class> Gq, Giq;  // exact G = U^T U and its inverse, only when needed
  std::vector<IA> b(L.size() * m, IA(0));  // b(x) = U^T (x - p) per local point, row-major
  std::vector<IA> t(L.size(), IA(0));
  for (int l = 1; l < L.size(); ++l) {
    for (int a = 0; a < m; ++a) b[l * m + a] = L.row(l)[a];
    for (int a = 0; a < m; ++a)
      for (int k = 0; k < m; ++k) t[l] += b[l * m + a] * Gi[a * m + k] * b[l * m + k];
  }
  // The local points projected possibly within reach_all, by increasing lower bound of their
  // projected squared distance to p (ties by index).
  std::vector<int> by_t;
  for (int l = 1; l < L.size(); ++l)
    if (!(t[l].inf() > reach_all)) by_t.push_back(l);
  std::sort(by_t.begin(), by_t.end(), [&](int a, int b2) { return t[a].inf() < t[b2].inf() || (t[a].inf() == t[b2].inf() && a < b2); });
  by_t.push_back(-1);  // end marker
  const IA eps2 = to_interval_number(sp.eps2_enclosure), delta = to_interval_number(sp.delta_enclosure),
           ups2 = to_interval_number(sp.upsilon0_2_enclosure), short2 = to_interval_number(sp.shortest2_enclosure);
  std::vector<mpq_class> bq;  // exact rows, filled on first need
  std::vector<mpq_class> tq;
  for (const auto& s : star) {
    List c{};
    for (int i = 0, k = 1; i <= m; ++i)
      if (s[i] != p) c[k++] = L.local_of(s[i]);
    bool undecided = ctx.force_exact;  // force_exact: straight to the exact rationals
    std::string why;
    if (!ctx.force_exact) why = secure_cell<IA>(L, c, by_t, b, t, G, Gi, eps2, delta, ups2, short2, undecided);
    if (undecided) {  // decide exactly
      ++out.exact_fallbacks;
      if (bq.empty()) {
        const exact::TangentSpace& Tq = L.chart().space();
        Gq.assign(m * m, mpq_class(0));
        for (int a = 0; a < m; ++a)
          for (int k = 0; k < m; ++k) Gq[a * m + k] = Tq.gram(a, k);
        auto inv = exact::inverse(Gq, m);
        if (!inv) throw std::logic_error("check 7: singular Gram matrix (the exact basis has full rank)");
        Giq = std::move(*inv);
        bq.assign(L.size() * m, mpq_class(0));
        tq.assign(L.size(), mpq_class(0));
        for (int l = 1; l < L.size(); ++l) {
          auto row = L.chart().row_exact(l);
          for (int a = 0; a < m; ++a) bq[l * m + a] = row[a];
          for (int a = 0; a < m; ++a)
            for (int k = 0; k < m; ++k) tq[l] += bq[l * m + a] * Giq[a * m + k] * bq[l * m + k];
        }
      }
      undecided = false;
      why = secure_cell<mpq_class>(L, c, by_t, bq, tq, Gq, Giq, sp.eps * sp.eps, sp.delta, sp.upsilon0 * sp.upsilon0,
                                   sp.shortest * sp.shortest, undecided);
    }
    if (why.empty()) {
      ++out.secure;
    } else {
      ++out.insecure;
      if (out.failures.size() < 5) out.failures.emplace_back(s, why);
    }
  }
  return out;
}

}  // namespace delcert::certify
