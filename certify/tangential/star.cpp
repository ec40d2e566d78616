#include "certify/tangential/star.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "certify/detail/grid.hpp"
#include "certify/tangential/local.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_predicates.hpp"

namespace delcert::certify {

namespace {

using detail::gram_enclosure;
using detail::IA;
using detail::kMaxM;
using detail::kMinRadiusGrowth;
using detail::kNeededRadiusMargin;
using detail::List;
using detail::Local;
using detail::make_local;
using exact::determinant;
using exact::to_interval;
using exact::to_interval_number;
const exact::Interval kUnknown{-INFINITY, INFINITY};

// The search radius r at p (see star.hpp: the tested set holds every point within r of p).
// First guesses; each run verifies whether r was large enough and grows it if not, so these
// values change how often a star is recomputed and the radius reported, never a verdict.
//  * Without a claimed star: a few grid cells, enough for the star of a well-spaced sample.
constexpr double kInitialRadiusGridCells = 3;
//  * With a claimed star: its vertices lie within 2R of p (R the largest cell radius) and 2.25R
//    is needed (test_list), so a multiple of the farthest claimed vertex a little above
//    2.25 / 2 = 1.125 can suffice; 1.6 covers 2.25R whenever the farthest claimed vertex is at
//    distance >= 2.25R / 1.6 (about 1.4R), so that one run usually suffices.
constexpr double kClaimedVertexRadiusFactor = 1.6;
//  * For one cell (test_cell): likewise from its own vertices; 2.5 covers 2.25R whenever the
//    farthest vertex is at distance >= 0.9R.
constexpr double kCellVertexRadiusFactor = 2.5;
// Growth when gift-wrapping found no point beyond a ridge (the star may close farther away).
constexpr double kOpenStarRadiusGrowth = 2;
// Bounds on the work at one point: runs of the search-radius loop, and cells of one gift-wrap
// (far above any real star: a wrap that exceeds it is reported as inconsistent).
constexpr int kMaxRadiusRuns = 64;
constexpr std::size_t kMaxWrapCells = 20000;
// The degree test of check_link places a virtual point x = a weighted mean of p and the first
// cell's vertices, weights 1 + attempt * i * kRayWeightStep for vertex i; an irrational-looking
// step makes a second hit on a cell boundary unlikely. At most kRayAttempts placements.
constexpr int kRayAttempts = 6;
constexpr double kRayWeightStep = 0.37;

// Enclosure of a cell's centre (y = 2z with c = p + U z) and R^2 = z^T G z from the interval rows:
// B y = h with B the rows b(v_i), h_i = s(v_i), by Cramer's rule (when det B excludes 0).
struct CellBox {
  bool ok = false;
  std::array<IA, kMaxM> y{};
  IA R2;
};

CellBox cell_box(const Local& L, const List& c) {
  const int m = L.m;
  CellBox box;
  std::array<IA, kMaxM * kMaxM> B;
  std::array<IA, kMaxM> h;
  B.fill(IA(0));
  h.fill(IA(0));
  for (int i = 0; i < m; ++i) {
    for (int a = 0; a < m; ++a) B[i * m + a] = L.row(c[i + 1])[a];
    h[i] = L.row(c[i + 1])[m];
  }
  IA d = determinant(B.data(), m);
  if (d.inf() <= 0 && d.sup() >= 0) return box;
  exact::cramer_solve(B.data(), h.data(), d, m, box.y.data());
  IA R2(0);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) R2 += box.y[a] * L.gram[a * m + b] * box.y[b];
  box.R2 = R2 / 4;
  box.ok = std::isfinite(box.R2.sup()) && std::isfinite(box.R2.inf());
  return box;
}

// |c - q|^2 - R^2 = s(q) - b(q).y
IA power_box(const Local& L, const CellBox& box, int q) {
  const IA* r = L.row(q);
  IA v = r[L.m];
  for (int a = 0; a < L.m; ++a) v -= r[a] * box.y[a];
  return v;
}

Simplex to_global(const Local& L, const List& c) {
  Simplex s;
  s.reserve(L.m + 1);
  for (int i = 0; i <= L.m; ++i) s.push_back(L.global[c[i]]);
  std::sort(s.begin(), s.end());
  return s;
}

List sorted_list(List c, int m) {  // insertion sort of c[1..m] (p stays first)
  for (int i = 2; i <= m && i < kMaxM + 1; ++i)
    for (int k = i; k > 1 && c[k - 1] > c[k]; --k) std::swap(c[k - 1], c[k]);
  return c;
}

// ---------------------------------------------------------------------------------------------
// Kernels for gift-wrapping: floating point (fast, unverified) and exact (exact/ predicates).
// ---------------------------------------------------------------------------------------------

struct DoubleKernel {
  const Local& L;
  std::array<double, kMaxM> y{};
  bool ok = false;
  int orient(const List& c) const {
    const int m = L.m;
    double a[kMaxM * kMaxM];
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < m; ++k) a[i * m + k] = L.drow(c[i + 1])[k];
    double d = determinant(a, m);
    return (d > 0) - (d < 0);
  }
  void set_cell(const List& c) {
    const int m = L.m;
    double a[kMaxM * kMaxM], h[kMaxM];
    for (int i = 0; i < m; ++i) {
      for (int k = 0; k < m; ++k) a[i * m + k] = L.drow(c[i + 1])[k];
      h[i] = L.drow(c[i + 1])[m];
    }
    double d = determinant(a, m);
    ok = d != 0;
    if (ok) exact::cramer_solve(a, h, d, m, y.data());
  }
  int power(int q) const {
    if (!ok) return 0;
    double v = L.drow(q)[L.m];
    for (int a = 0; a < L.m; ++a) v -= L.drow(q)[a] * y[a];
    return (v > 0) - (v < 0);
  }
};

struct ExactKernel {
  const Local& L;
  exact::FilterContext& ctx;
  std::optional<exact::TangentCell> cell;
  int orient(const List& c) const { return L.chart().orientation(std::span<const int>(c.data(), L.m + 1), ctx); }
  void set_cell(const List& c) { cell = L.chart().cell(std::span<const int>(c.data(), L.m + 1), ctx); }
  int power(int q) const { return cell->power_sign(q, ctx); }
};

struct Wrap {
  std::vector<List> cells;
  bool open = false;          // a ridge with no point beyond it
  bool inconsistent = false;  // a ridge in three cells, or too many cells
  bool tie = false;           // a candidate exactly on a sphere while wrapping
};

// Gift-wrapping around p from `seed`, across every ridge {p} + (m - 1 link vertices).
template <class Kernel>
Wrap gift_wrap(Kernel& K, const Local& L, const List& seed) {
  const int m = L.m;
  Wrap W;
  std::map<std::vector<int>, std::vector<int>> ridges;  // sorted link vertices -> cells
  std::map<List, int> index;
  auto ridge_of = [&](const List& c, int i) {
    std::vector<int> r;
    for (int k = 1; k <= m; ++k)
      if (k != i) r.push_back(c[k]);
    return r;
  };
  auto add = [&](const List& c) {
    auto [it, inserted] = index.emplace(c, static_cast<int>(W.cells.size()));
    if (inserted) {
      W.cells.push_back(c);
      for (int i = 1; i <= m; ++i) {
        auto& v = ridges[ridge_of(c, i)];
        v.push_back(it->second);
        if (v.size() > 2) W.inconsistent = true;
      }
    }
    return it->second;
  };
  add(sorted_list(seed, m));
  for (std::size_t k = 0; k < W.cells.size() && !W.inconsistent; ++k) {
    if (W.cells.size() > kMaxWrapCells) {
      W.inconsistent = true;
      break;
    }
    for (int i = 1; i <= m; ++i) {
      const List c = W.cells[k];
      if (ridges[ridge_of(c, i)].size() >= 2) continue;
      const int o = K.orient(c);
      int best = -1;
      List cand = c;
      for (int q = 1; q < L.size(); ++q) {
        if (std::find(c.begin(), c.begin() + m + 1, q) != c.begin() + m + 1) continue;
        cand[i] = q;
        if (K.orient(cand) != -o) continue;  // not strictly beyond the ridge
        if (best < 0) {
          best = q;
          K.set_cell(cand);
          continue;
        }
        int s = K.power(q);
        if (s == 0) W.tie = true;
        if (s < 0) {
          best = q;
          K.set_cell(cand);
        }
      }
      if (best < 0) {
        W.open = true;
        continue;
      }
      cand[i] = best;
      add(sorted_list(cand, m));
    }
  }
  return W;
}

// A vertex of the power cell {y : 2 b(q).y <= s(q)} of p by successive ray shooting: m steps,
// each moving along a direction orthogonal to the constraints already tight until a new one
// becomes tight. Returns the cell {p} + tight constraints, or nothing if the cell is unbounded.
template <class T, class Row>
std::optional<List> power_cell_vertex(int m, int count, Row row) {
  std::vector<std::vector<T>> R(count);
  for (int q = 1; q < count; ++q) R[q] = row(q);  // m + 1 entries: b, s
  std::vector<T> y(m, T(0));
  std::vector<std::vector<T>> W;  // orthogonalised tight normals
  List cell{};
  auto dot = [&](const std::vector<T>& a, const std::vector<T>& b) {
    T s(0);
    for (int k = 0; k < m; ++k) s += a[k] * b[k];
    return s;
  };
  auto orth = [&](std::vector<T> v) {
    for (const auto& w : W) {
      T f = dot(v, w) / dot(w, w);
      for (int k = 0; k < m; ++k) v[k] -= f * w[k];
    }
    return v;
  };
  for (int step = 0; step < m; ++step) {
    std::vector<T> d;
    T best_norm(0);
    for (int j = 0; j < m; ++j) {
      std::vector<T> e(m, T(0));
      e[j] = T(1);
      e = orth(e);
      T nn = dot(e, e);
      if (nn > best_norm) best_norm = nn, d = e;
    }
    if (d.empty()) return std::nullopt;
    bool found = false;
    for (int sg : {1, -1}) {
      int best = -1;
      T bt(0);
      for (int q = 1; q < count; ++q) {
        if (std::find(cell.begin() + 1, cell.begin() + 1 + step, q) != cell.begin() + 1 + step) continue;
        T dq = dot(R[q], d) * T(sg);
        if (!(dq > T(0))) continue;
        T slack = R[q][m] / T(2) - dot(R[q], y);
        T t = slack / dq;
        if (best < 0 || t < bt) best = q, bt = t;
      }
      if (best < 0) continue;
      for (int k = 0; k < m; ++k) y[k] += T(sg) * bt * d[k];
      cell[1 + step] = best;
      W.push_back(orth(std::vector<T>(R[best].begin(), R[best].begin() + m)));
      found = true;
      break;
    }
    if (!found) return std::nullopt;
  }
  cell[0] = 0;
  return sorted_list(cell, m);
}

// ---------------------------------------------------------------------------------------------
// Verification of a set of cells at p: (a) empty balls, margins, claims; (b) the link closes once.
// ---------------------------------------------------------------------------------------------

struct Verification {
  std::vector<CellReport> cells;
  bool link_ok = false;
  std::string link_problem;
  double need_radius = 0;  // the tested set must contain every point within this distance of p
};

std::string simplex_text(const Simplex& s) {
  std::string t = "[";
  for (std::size_t i = 0; i < s.size(); ++i) t += (i ? " " : "") + std::to_string(s[i]);
  return t + "]";
}

// When every cell has a strictly empty ball (`proven_cells`), closure alone proves the star:
// the cells are then cells of one triangulation (disjoint interiors), the link of an interior
// vertex of a triangulation is strongly connected across ridges, so a ridge-closed subset of
// star(p) is all of it (and p cannot be on the hull). Otherwise the orientation and degree tests
// below explain what is wrong.
bool check_link(const StarSettings& S, const Local& L, const std::vector<List>& cells, bool proven_cells,
                std::string& problem, exact::FilterContext& ctx) {
  const int m = L.m;
  if (cells.empty()) {
    problem = "no cell at p";
    return false;
  }
  // Closure: every ridge in exactly two cells, on opposite sides. A ridge is keyed by its m - 1
  // link vertices (p is in every ridge).
  struct RidgeUse {
    std::array<int, kMaxM> key;
    int cell, pos;  // the cell and the position of the vertex opposite the ridge
  };
  std::vector<RidgeUse> uses;
  for (std::size_t k = 0; k < cells.size(); ++k)
    for (int i = 1; i <= m; ++i) {
      RidgeUse u{{}, static_cast<int>(k), i};
      u.key.fill(-1);
      for (int t = 1, n = 0; t <= m; ++t)
        if (t != i) u.key[n++] = cells[k][t];
      uses.push_back(u);
    }
  std::sort(uses.begin(), uses.end(), [](const RidgeUse& a, const RidgeUse& b) { return a.key < b.key; });
  for (std::size_t a = 0; a < uses.size();) {
    std::size_t b = a;
    while (b < uses.size() && uses[b].key == uses[a].key) ++b;
    if (b - a != 2) {
      Simplex g{L.global[0]};
      for (int t = 0; t < m - 1; ++t) g.push_back(L.global[uses[a].key[t]]);
      std::sort(g.begin(), g.end());
      problem = "the ridge " + simplex_text(g) + " lies in " + std::to_string(b - a) +
                " cell(s) at p instead of 2: the link of p does not close";
      return false;
    }
    if (proven_cells) {
      a = b;
      continue;
    }
    const List& c0 = cells[uses[a].cell];
    List c1 = c0;
    c1[uses[a].pos] = cells[uses[a + 1].cell][uses[a + 1].pos];
    if (L.chart().orientation(std::span<const int>(c1.data(), m + 1), ctx) !=
        -L.chart().orientation(std::span<const int>(c0.data(), m + 1), ctx)) {
      problem = "two cells at p sharing a ridge lie on the same side of it: they overlap in T_p";
      return false;
    }
    a = b;
  }
  if (proven_cells) return true;
  // Degree: a ray from p through an interior point x of the first cell's cone lies in exactly
  // one cell's cone. x is a virtual point (any double point; only its projection matters).
  std::vector<int> verts;
  for (const auto& c : cells) verts.insert(verts.end(), c.begin() + 1, c.begin() + m + 1);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  const int N = L.N;
  auto pp = S.points->point(L.global[0]);
  for (int attempt = 0; attempt < kRayAttempts; ++attempt) {
    std::vector<double> x(N);
    double wsum = 1;
    for (int k = 0; k < N; ++k) x[k] = pp[k];
    for (int i = 1; i <= m; ++i) {
      double w = 1 + attempt * i * kRayWeightStep;
      wsum += w;
      auto v = S.points->point(L.global[cells[0][i]]);
      for (int k = 0; k < N; ++k) x[k] += w * v[k];
    }
    for (int k = 0; k < N; ++k) x[k] /= wsum;
    std::vector<const double*> ptrs;
    for (int l : verts) ptrs.push_back(S.points->point(L.global[l]).data());
    ptrs.push_back(x.data());
    exact::TangentChart small(L.chart().space(), std::span<const double* const>(ptrs));
    const int xl = static_cast<int>(ptrs.size());
    auto sl = [&](int l) { return 1 + static_cast<int>(std::lower_bound(verts.begin(), verts.end(), l) - verts.begin()); };
    int count = 0;
    bool ambiguous = false;
    for (std::size_t k = 0; k < cells.size() && !ambiguous; ++k) {
      List c{};
      for (int i = 1; i <= m; ++i) c[i] = sl(cells[k][i]);
      int o = small.orientation(std::span<const int>(c.data(), m + 1), ctx);
      bool inside = true;
      for (int i = 1; i <= m; ++i) {
        List d = c;
        d[i] = xl;
        int s = small.orientation(std::span<const int>(d.data(), m + 1), ctx);
        if (s == 0) ambiguous = true;
        inside = inside && s == o;
      }
      if (k == 0 && !inside) ambiguous = true;  // x must lie inside the first cone
      count += inside;
    }
    if (ambiguous) continue;
    if (count != 1) {
      problem = "the cells at p cover a neighbourhood of p " + std::to_string(count) + " times, not once";
      return false;
    }
    return true;
  }
  problem = "could not place a generic ray from p (every attempt hit a cell boundary)";
  return false;
}

// The claims a cell at p is tested against, prepared once per star (exact value and enclosure).
struct CellClaims {
  std::optional<exact::RationalConstant> prot, eps2;  // delta-check^2, eps(p)^2
};
CellClaims cell_claims(const StarSettings& S, int p) {
  CellClaims C;
  if (S.power_protection) C.prot.emplace(*S.power_protection);
  if (S.eps) C.eps2.emplace(mpq_class(*S.eps * *S.eps));
  else if (S.eps_per_point) C.eps2.emplace(mpq_class((*S.eps_per_point)[p] * (*S.eps_per_point)[p]));
  return C;
}

// Tests one cell at p against every point of L: emptiness, ties, margin, claims. Raises
// need_radius to the search radius this cell requires.
CellReport test_list(const Local& L, const List& c, double& need_radius, exact::FilterContext& ctx, const CellClaims& claims) {
  const int m = L.m;
  const auto& prot = claims.prot;
  const auto& eps2 = claims.eps2;
  CellReport R;
  R.simplex = to_global(L, c);
  exact::TangentCell tc = L.chart().cell(std::span<const int>(c.data(), m + 1), ctx);
  if (tc.degenerate()) {
    R.degenerate = true;
    return R;
  }
  CellBox box = cell_box(L, c);
  // When the interval centre is too wide, enclose the exact values instead (slow, rare).
  R.radius2 = box.ok ? to_interval(box.R2) : exact::enclose(tc.squared_radius_exact());
  // Radius the tested set must cover: 2R (emptiness), R + sqrt(R^2 + claim) (protection claim)
  // and 2.25R (so that untested points have power > r^2 - 2rR >= 0.5 R^2, normally far above the
  // tested minimum; it enters the reported lower bound otherwise).
  IA Rr = exact::sqrt(IA(R.radius2.lo, R.radius2.hi));
  double need = (IA(2.25) * Rr).sup();
  // With r >= (1 + 2^-20)(R + sqrt(R^2 + claim)), r^2 - 2 r R exceeds the claim by far more than
  // the rounding of its interval evaluation below, so the printed margin stays above the claim.
  if (prot)
    need = std::max(need, (IA(1 + 0x1p-20) * (Rr + exact::sqrt(IA(R.radius2.lo, R.radius2.hi) + to_interval_number(prot->enclosure())))).sup());
  need_radius = std::max(need_radius, need);
  // The points of L farther than rho >= need from p are not evaluated: for them
  // power = |q - c|^2 - R^2 >= (|q - p| - R)^2 - R^2 > rho^2 - 2 rho R (|p - c| = R), which is
  // positive (rho >= 2.25 R) and above the protection claim (rho >= the claim's radius above),
  // so they hold no conflict, tie or protection failure; rho^2 - 2 rho R enters the margin's lower
  // bound when one was left out. rho = 2.5R (when need is below it) keeps that bound, 1.25 R^2,
  // above the tested minimum in practice: a cell's nearest non-vertex point is normally closer.
  const double rho = std::max(need, (IA(2.5) * Rr).sup());
  const double rho2 = rho <= DBL_MAX ? (IA(rho) * IA(rho)).sup() : INFINITY;  // infinite: every point is tested
  bool left_out = false;
  exact::Interval margin{INFINITY, INFINITY};
  for (int q = 1; q < L.size(); ++q) {
    if (L.row(q)[m].inf() > rho2) {  // |q - p|^2 > rho^2
      left_out = true;
      continue;
    }
    if (std::find(c.begin(), c.begin() + m + 1, q) != c.begin() + m + 1) continue;
    exact::Interval pw = box.ok ? to_interval(power_box(L, box, q)) : exact::enclose(tc.power_exact(q));
    // The box (or exact) enclosure contains the exact power: a positive lower bound is its sign.
    int s = pw.lo > 0 ? 1 : tc.power_sign(q, ctx);
    // The printed margin must never contradict an exact sign (the consistency guard in
    // certificate.hpp checks it): where the box enclosure is too loose to show what the exact
    // sign proved, print the enclosure of the exact value instead. enclose() is monotone, so
    // power > 0 gives lo >= 0 and power > claim gives lo >= enclose(claim).lo.
    if (s > 0 && !(pw.lo >= 0)) pw = exact::enclose(tc.power_exact(q));
    if (s < 0 && R.conflict < 0) R.conflict = L.global[q], R.conflict_power = pw;
    if (s == 0 && R.tie < 0) R.tie = L.global[q];
    if (prot && R.protection_point < 0 && !(pw.lo > prot->enclosure().hi)) {
      int t = tc.power_sign(q, *prot, ctx);
      if (t <= 0) R.protection_point = L.global[q], R.protection_sign = t, R.protection_power = pw;
      else if (!(pw.lo >= prot->enclosure().lo)) pw = exact::enclose(tc.power_exact(q));
    }
    if (pw.lo < margin.lo) margin.lo = pw.lo, R.margin_point = L.global[q];
    margin.hi = std::min(margin.hi, pw.hi);
  }
  if (left_out) margin.lo = std::min(margin.lo, (IA(rho) * IA(rho) - IA(2) * IA(rho) * Rr).inf());
  if (!L.all) {  // untested points are farther than r from p: power > r^2 - 2 r R
    IA far = IA(L.radius) * IA(L.radius) - IA(2) * IA(L.radius) * Rr;
    margin.lo = std::min(margin.lo, far.inf());
  }
  R.margin = margin;
  if (eps2) {
    if (R.radius2.hi < eps2->enclosure().lo) R.eps_sign = -1;
    else if (R.radius2.lo > eps2->enclosure().hi) R.eps_sign = 1;
    else R.eps_sign = sgn(tc.squared_radius_exact() - eps2->value());
    // As for the margin: a printed radius must not contradict the exact sign (enclose is monotone).
    if (R.eps_sign < 0 && !(R.radius2.hi <= eps2->enclosure().hi)) R.radius2 = exact::enclose(tc.squared_radius_exact());
  }
  return R;
}

Verification verify(const StarSettings& S, const Local& L, const std::vector<List>& cells, exact::FilterContext& ctx) {
  Verification V;
  bool any_degenerate = false;
  V.cells.reserve(cells.size());  // kept as the star (1M points: 256 bytes a point less than by doubling)
  const CellClaims claims = cell_claims(S, L.global[0]);
  for (const List& c : cells) {
    V.cells.push_back(test_list(L, c, V.need_radius, ctx, claims));
    any_degenerate = any_degenerate || V.cells.back().degenerate;
  }
  const bool proven = std::all_of(V.cells.begin(), V.cells.end(), [](const CellReport& c) { return c.empty(); });
  if (any_degenerate) V.link_problem = "a cell at p is degenerate in T_p (its projection is affinely dependent)";
  else V.link_ok = check_link(S, L, cells, proven, V.link_problem, ctx);
  return V;
}

bool all_empty(const Verification& V) {
  return std::all_of(V.cells.begin(), V.cells.end(), [](const CellReport& c) { return c.empty(); });
}

}  // namespace

StarReport analyse_star(const StarSettings& S, int p, const std::vector<Simplex>* claimed, exact::FilterContext& ctx) {
  const io::PointSet& P = *S.points;
  const int m = S.m, N = P.dimension;
  StarReport out;
  out.p = p;
  exact::UpwardRounding upward;  // for the enclosures computed here
  exact::TangentSpace T(*S.system, P.point(p));
  std::vector<IA> U(N * m);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < m; ++a) U[i * m + a] = to_interval_number(T.basis_enclosure(i, a));
  const std::vector<IA> G = gram_enclosure(T, m);
  out.basis_enclosure.reserve(U.size()), out.gram_enclosure.reserve(G.size());
  for (const IA& x : U) out.basis_enclosure.push_back(to_interval(x));  // for check 7 (no second exact basis)
  for (const IA& x : G) out.gram_enclosure.push_back(to_interval(x));
  auto dist = [&](int g) {
    double s = 0;
    for (int k = 0; k < N; ++k) s += (P.point(g)[k] - P.point(p)[k]) * (P.point(g)[k] - P.point(p)[k]);
    return std::sqrt(s);
  };
  // A first guess; the verification proves whether it was large enough and grows it if not.
  double r = kInitialRadiusGridCells * S.grid->spacing();
  if (claimed && !claimed->empty()) {
    r = 0;
    for (const auto& s : *claimed)
      for (int v : s) r = std::max(r, kClaimedVertexRadiusFactor * dist(v));
  }
  for (int iter = 0; iter < kMaxRadiusRuns; ++iter) {
    Local L = make_local(S, &T, U, G, p, r);
    if (!L.covered) {  // an MPI rank: the ball is not all held here (never in one process)
      out.state = StarReport::State::incomplete, out.halo_needed = r;
      out.reason = "this MPI rank's halo does not hold the points within " + std::to_string(r) +
                   " of p, which the star search needs: rerun with a larger --halo, or without --halo (automatic)";
      return out;
    }
    out.search_radius = r;
    out.searched_all = L.all;
    auto grow = [&](double need) {
      r = std::max(need * kNeededRadiusMargin, r * kMinRadiusGrowth);
      return !L.all;
    };
    std::optional<List> seed;
    if (claimed) {
      std::vector<List> lists;
      bool missing_vertex = false;
      for (const auto& s : *claimed) {
        List c{};
        int k = 1;
        for (int v : s)
          if (v != p) c[k++] = L.local_of(v), missing_vertex = missing_vertex || c[k - 1] < 0;
        lists.push_back(sorted_list(c, m));
      }
      if (missing_vertex && grow(kOpenStarRadiusGrowth * r)) continue;  // cannot happen with r >= kClaimedVertexRadiusFactor |v - p|; kept as a guard
      Verification V = verify(S, L, lists, ctx);
      if (V.need_radius > r && grow(V.need_radius)) continue;
      out.link_problem = V.link_problem;
      if (all_empty(V) && V.link_ok) {  // one copy of the cells: `claimed` is read only for stars not verified
        out.claimed_verified = true;
        out.star = std::move(V.cells), out.claimed.clear();
        out.state = StarReport::State::proven;
        return out;
      }
      out.claimed = V.cells;
      for (std::size_t k = 0; k < lists.size() && !seed; ++k)
        if (V.cells[k].empty()) seed = lists[k];  // a strictly empty ball: a true cell of star(p)
    }
    // Floating-point gift-wrapping, then exact verification.
    if (!seed)
      seed = power_cell_vertex<double>(m, L.size(), [&](int q) { return std::vector<double>(L.drow(q), L.drow(q) + m + 1); });
    if (seed) {
      DoubleKernel K{L};
      Wrap W = gift_wrap(K, L, *seed);
      if (W.open && !W.inconsistent && grow(kOpenStarRadiusGrowth * r)) continue;
      if (!W.open && !W.inconsistent) {
        Verification V = verify(S, L, W.cells, ctx);
        if (V.need_radius > r && grow(V.need_radius)) continue;
        if (all_empty(V) && V.link_ok) {
          out.star = V.cells;
          out.state = StarReport::State::proven;
          return out;
        }
      }
    }
    // Exact gift-wrapping from an exact vertex of the power cell.
    std::optional<List> exact_seed = power_cell_vertex<mpq_class>(m, L.size(), [&](int q) { return L.chart().row_exact(q); });
    if (!exact_seed) {
      if (grow(kOpenStarRadiusGrowth * r)) continue;
      out.reason = "the power cell of p is unbounded even with every sample point: p has no complete star";
      return out;
    }
    ExactKernel K{L, ctx, std::nullopt};
    Wrap W = gift_wrap(K, L, *exact_seed);
    if (W.open && !W.inconsistent && grow(kOpenStarRadiusGrowth * r)) continue;
    std::vector<List> cells = W.cells;
    Verification V = verify(S, L, cells, ctx);
    if (V.need_radius > r && grow(V.need_radius)) continue;
    out.star = V.cells;
    bool ties = W.tie || std::any_of(V.cells.begin(), V.cells.end(), [](const CellReport& c) { return c.tie >= 0; });
    if (all_empty(V) && V.link_ok && !W.open && !W.inconsistent) {
      out.state = StarReport::State::proven;
    } else if (ties) {
      out.state = StarReport::State::degenerate;
      out.reason = "exactly degenerate: a sample point lies exactly on the sphere of a cell at p, so star(p) is not unique";
    } else {
      out.state = StarReport::State::incomplete;
      out.reason = W.open ? "the star of p does not close even with every sample point"
                          : (V.link_problem.empty() ? "exact gift-wrapping did not produce a star" : V.link_problem);
    }
    return out;
  }
  out.reason = "search radius did not converge";
  return out;
}

CellReport test_cell(const StarSettings& S, int p, const Simplex& s, exact::FilterContext& ctx) {
  const io::PointSet& P = *S.points;
  const int m = S.m, N = P.dimension;
  exact::UpwardRounding upward;
  exact::TangentSpace T(*S.system, P.point(p));
  std::vector<IA> U(N * m);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < m; ++a) U[i * m + a] = to_interval_number(T.basis_enclosure(i, a));
  const std::vector<IA> G = gram_enclosure(T, m);
  double r = kInitialRadiusGridCells * S.grid->spacing();
  for (int v : s) {
    double d2 = 0;
    for (int k = 0; k < N; ++k) d2 += (P.point(v)[k] - P.point(p)[k]) * (P.point(v)[k] - P.point(p)[k]);
    r = std::max(r, kCellVertexRadiusFactor * std::sqrt(d2));
  }
  for (;;) {
    Local L = make_local(S, &T, U, G, p, r);
    if (!L.covered) throw std::logic_error("test_cell: the grid does not hold every point (run on rank 0 only)");
    List c{};
    for (int i = 0, k = 1; i <= m; ++i)
      if (s[i] != p) c[k++] = L.local_of(s[i]);
    double need = 0;
    CellReport R = test_list(L, sorted_list(c, m), need, ctx, cell_claims(S, p));
    if (need <= r || L.all) return R;
    r = std::max(need * kNeededRadiusMargin, r * kMinRadiusGrowth);
  }
}

}  // namespace delcert::certify
