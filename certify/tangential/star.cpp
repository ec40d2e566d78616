#include "certify/tangential/star.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "certify/tangential/far_filter.hpp"
#include "certify/detail/grid.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_predicates.hpp"

namespace delcert::certify {

namespace {

// Interval arithmetic for enclosures only (never for a decision: signs come from exact/).
// IntervalNumber assumes upward rounding, which analyse_star holds for its whole body.
using IA = exact::IntervalNumber;
using exact::determinant;
using exact::to_interval;
using exact::to_interval_number;
constexpr int kMaxM = exact::kMaxTangentDimension;
static_assert(kMaxM <= exact::kMaxLinearSize);
using List = std::array<int, kMaxM + 1>;  // local indices of a cell, [0] = p, the rest increasing
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
// Growth when the radius was too small: to a little more than what was needed (a margin over
// the floating-point distances and enclosures it was computed from, so that the next run does
// not ask for the same radius again), and at least by a quarter (so that the number of runs is
// logarithmic in the final radius).
constexpr double kNeededRadiusMargin = 1.0625;
constexpr double kMinRadiusGrowth = 1.25;
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
// Check 7 (Definition 3.1): the points of W = B(p, kSecureNeighbourhoodEps * eps) are tested,
// with bounded work per point: one grid query of the box where a point can matter
// (analyse_secure), at most kMaxSecureNeighbourhood points of W in it, a floating-point bound per
// point (detail/far_filter.hpp) and an interval projection of the few it keeps.
constexpr double kSecureNeighbourhoodEps = 5;
constexpr int kMaxSecureNeighbourhood = 50000;

// The points tested at p: every point within distance `radius` of p (and possibly more).
struct Local {
  int m = 0, N = 0;
  std::vector<int> global;  // local -> global, global[0] = p; the rest increasing
  const io::PointSet* points = nullptr;
  const exact::TangentSpace* space = nullptr;          // null: built on first use from `system`
  const exact::ImplicitSystem* system = nullptr;
  mutable std::optional<exact::TangentSpace> own_space_;
  mutable std::optional<exact::TangentChart> chart_;  // built on first use
  std::vector<IA> rows;       // (m + 1) per local: b = U^T (x - p), s = |x - p|^2 (enclosures)
  std::vector<double> drows;  // midpoints, for the floating-point gift-wrapping
  std::vector<IA> gram;       // m x m enclosure of G = U^T U
  double radius = 0;
  bool all = false;
  bool covered = true;  // the grid held every point within `radius` (false only on an MPI rank's part)

  const IA* row(int l) const { return rows.data() + static_cast<std::size_t>(l) * (m + 1); }
  const double* drow(int l) const { return drows.data() + static_cast<std::size_t>(l) * (m + 1); }
  int size() const { return static_cast<int>(global.size()); }
  const exact::TangentChart& chart() const {
    if (!chart_) {
      std::vector<const double*> ptrs;
      for (std::size_t i = 1; i < global.size(); ++i) ptrs.push_back(points->point(global[i]).data());
      if (!space && !own_space_) own_space_.emplace(*system, points->point(global[0]));
      chart_.emplace(space ? *space : *own_space_, std::span<const double* const>(ptrs));
    }
    return *chart_;
  }
  int local_of(int g) const {
    if (g == global[0]) return 0;
    auto it = std::lower_bound(global.begin() + 1, global.end(), g);
    return it != global.end() && *it == g ? static_cast<int>(it - global.begin()) : -1;
  }
};

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
                    const std::vector<const double*>* coords = nullptr) {
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

namespace {

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
