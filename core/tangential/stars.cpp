#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/tangential/detail/local_problem.hpp"
#include "core/support/parallel.hpp"
#include "core/tangential/detail/power_cell.hpp"
#include "core/tangential/star.hpp"

namespace delcert::tangential {

using support::parallel_chunks;

long Star::find(std::span<const int> v) const {
  const std::size_t w = static_cast<std::size_t>(m + 1);
  if (v.size() != w) return -1;
  const int* key = v.data();
  auto less = [w](const int* a, const int* b) {
    for (std::size_t i = 0; i < w; ++i)
      if (a[i] != b[i]) return a[i] < b[i];
    return false;
  };
  std::size_t lo = 0, hi = size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (less(cells.data() + mid * w, key)) lo = mid + 1;
    else hi = mid;
  }
  if (lo < size() && std::equal(key, key + w, cells.data() + lo * w)) return static_cast<long>(lo);
  return -1;
}

namespace detail {

void project_neighbour(const double* p, const double* q, const double* basis, int N, int m, double scale,
                       LocalPoint& out) {
  double diff[io::kMaxAmbientDimension];
  double d2 = 0;
  for (int k = 0; k < N; ++k) {
    diff[k] = (q[k] - p[k]) * scale;  // exact scaling by a power of two
    d2 += diff[k] * diff[k];
  }
  for (int j = 0; j < m; ++j) {
    const double* t = basis + j * N;
    double s = 0;
    for (int k = 0; k < N; ++k) s += t[k] * diff[k];
    out.u[j] = s;
  }
  // Normal part by subtracting the tangential part (accurate even when it is tiny).
  double h2 = 0;
  for (int k = 0; k < N; ++k) {
    double r = diff[k];
    for (int j = 0; j < m; ++j) r -= basis[j * N + k] * out.u[j];
    h2 += r * r;
  }
  out.w = -h2;
  double a = 0;
  for (int j = 0; j < m; ++j) a += out.u[j] * out.u[j];
  out.a = a - out.w;
  out.d2 = d2;
}

double scale_for(double d2) {
  if (!(d2 > 0) || !std::isfinite(d2)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(std::sqrt(d2)));
}

Neighbourhood::Neighbourhood(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                             std::size_t initial_k)
    : points_(points), planes_(planes), index_(index), N_(points.dimension), m_(planes.intrinsic_dimension()),
      initial_k_(std::max<std::size_t>(initial_k, 1)) {}

void Neighbourhood::reset(std::size_t p) { restart(p, false, points_.point(p).data(), planes_.basis(p).data()); }

void Neighbourhood::reset_external(std::span<const double> x, std::span<const double> basis) {
  restart(points_.size(), true, x.data(), basis.data());
}

void Neighbourhood::restart(std::size_t p, bool external, const double* centre, const double* basis) {
  p_ = p;
  external_ = external;
  centre_ = centre;
  basis_ = basis;
  k_ = 0;
  exhausted_ = false;
  local_.clear();
  fetch(initial_k_);
}

void Neighbourhood::fetch(std::size_t k) {
  const std::size_t others = external_ ? points_.size() : points_.size() - 1;  // the points other than p
  k = std::min(k, others);
  k_ = k;
  exhausted_ = k >= others;
  // p itself comes first among its own k + 1 nearest; an external point is not in the index.
  index_.nearest(std::span<const double>(centre_, static_cast<std::size_t>(N_)), external_ ? k : k + 1, found_);
  const double* pp = centre_;
  const double* basis = basis_;
  std::size_t have = local_.size(), seen = 0;
  for (const auto& [d2, id] : found_) {
    if (id == p_) continue;
    if (seen++ < have) continue;  // same order as the previous batch: (distance, index)
    if (!(d2 > 0))
      throw std::invalid_argument("points " + std::to_string(std::min(p_, id)) + " and " +
                                  std::to_string(std::max(p_, id)) + " are identical; remove duplicates");
    if (local_.empty()) scale_ = scale_for(d2);
    LocalPoint lp;
    project_neighbour(pp, points_.point(id).data(), basis, N_, m_, scale_, lp);
    lp.global = static_cast<int>(id);
    local_.push_back(lp);
  }
}

bool Neighbourhood::ensure(std::size_t count) {
  while (local_.size() < count) {
    if (exhausted_) return false;
    fetch(std::max<std::size_t>(2 * k_, initial_k_));
  }
  return true;
}

namespace {

// Cramer's rule in exact rationals (the doubles' own values): for systems that Gaussian
// elimination in long double finds singular although the cell is not (extremely flat cells).
bool solve_centre_exact(int m, const LocalPoint* const* rows, double* v) {
  mpq_class A[kMaxM][kMaxM], b[kMaxM];
  for (int i = 0; i < m; ++i) {
    mpq_class a = 0;
    for (int j = 0; j < m; ++j) {
      A[i][j] = mpq_class(rows[i]->u[j]) * 2;
      a += mpq_class(rows[i]->u[j]) * mpq_class(rows[i]->u[j]);
    }
    b[i] = a - mpq_class(rows[i]->w);
  }
  // Fraction-free elimination would be faster; m <= 4 and this path is rare.
  auto det = [&](auto&& self, std::vector<int> cols, int row) -> mpq_class {
    if (cols.empty() || row >= kMaxM) return mpq_class(1);
    mpq_class s = 0;
    for (std::size_t k = 0; k < cols.size(); ++k) {
      std::vector<int> rest = cols;
      rest.erase(rest.begin() + static_cast<long>(k));
      const int c = cols[k];
      mpq_class x = (c < 0 ? b[row] : A[row][c]) * self(self, rest, row + 1);
      if (k % 2) s -= x;
      else s += x;
    }
    return s;
  };
  std::vector<int> cols(m);
  for (int j = 0; j < m; ++j) cols[j] = j;
  const mpq_class d = det(det, cols, 0);
  if (d == 0) return false;
  for (int j = 0; j < m; ++j) {
    std::vector<int> cj = cols;
    cj[j] = -1;  // column j replaced by the right-hand side
    v[j] = mpq_class(det(det, cj, 0) / d).get_d();
  }
  return true;
}

}  // namespace

bool solve_centre(int m, const LocalPoint* const* rows, double* v) {
  long double A[kMaxM][kMaxM + 1];
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) A[i][j] = 2.0L * rows[i]->u[j];
    // The exact right-hand side ||u||^2 - w, in long double (one rounding less than a).
    long double a = 0;
    for (int j = 0; j < m; ++j) a += static_cast<long double>(rows[i]->u[j]) * rows[i]->u[j];
    A[i][m] = a - rows[i]->w;
  }
  for (int c = 0; c < m; ++c) {
    int piv = c;
    for (int r = c + 1; r < m; ++r)
      if (std::abs(A[r][c]) > std::abs(A[piv][c])) piv = r;
    if (!(A[piv][c] != 0)) return solve_centre_exact(m, rows, v);
    if (piv != c)
      for (int j = 0; j <= m; ++j) std::swap(A[c][j], A[piv][j]);
    for (int r = c + 1; r < m; ++r) {
      long double f = A[r][c] / A[c][c];
      for (int j = c; j <= m; ++j) A[r][j] -= f * A[c][j];
    }
  }
  for (int c = m - 1; c >= 0; --c) {
    long double s = A[c][m];
    for (int j = c + 1; j < m; ++j) s -= A[c][j] * v[j];
    v[c] = static_cast<double>(s / A[c][c]);
    if (!std::isfinite(v[c])) return solve_centre_exact(m, rows, v);
  }
  return true;
}

}  // namespace detail

namespace {

using detail::LocalPoint;
using detail::LocalStar;
using detail::Neighbourhood;

enum class Outcome { done, fallback };

// Box half-width for a batch whose farthest neighbour is at squared distance d2 (scaled): a
// power of two (so the box halfspaces are exact) well beyond any cell radius the batch can
// certify (a complete star has R <= sqrt(d2) / 2).
double box_half_width(double d2) { return std::ldexp(1.0, std::ilogb(std::sqrt(d2)) + 4); }

// Clips p's power cell by its neighbours in (distance, index) order until the next neighbour is
// beyond 2 max R (then it cannot enter any ball: star complete) or every point was used.
template <int M>
Outcome power_cell_star(Neighbourhood& nb, detail::PowerCell<M>& cell, LocalStar& out) {
  using PC = detail::PowerCell<M>;
  out.cells.clear();
  out.closed = true;
  if (!nb.ensure(1)) return Outcome::fallback;  // a single point: no cells, let the reference say so
  std::size_t i = 0;
  bool complete = false;
  while (!complete) {
    // One attempt per box: the box must contain the final cell, so when a larger batch of
    // neighbours is needed while a box facet is still active, start over with a larger box.
    if (cell.reset(box_half_width(nb[nb.available() - 1].d2)) != PC::Status::ok) return Outcome::fallback;
    for (i = 0;; ++i) {
      if (i == nb.available()) {
        const bool bounded = cell.bounded();
        if (!nb.ensure(i + 1)) {
          if (!bounded) return Outcome::fallback;  // unbounded with every point: an open star
          complete = true;                         // every point considered
          break;
        }
        if (!bounded) break;  // retry with the larger batch and a larger box
      }
      const LocalPoint& q = nb[i];
      if (cell.bounded() && q.d2 > 4 * cell.max_radius2() * (1 + detail::kCompletenessMargin)) {
        complete = true;
        break;
      }
      if (cell.clip(q.u, q.a) != PC::Status::ok) return Outcome::fallback;
    }
  }
  out.considered = i;
  for (const auto& v : cell.vertices()) {
    if (!v.alive) continue;
    for (int j = 0; j < M; ++j) out.cells.push_back(v.f[j] - PC::kBoxFacets);
  }
  return Outcome::done;
}

struct FinishScratch {
  std::vector<std::array<int, detail::kMaxM>> local;
  std::vector<std::array<int, detail::kMaxM + 1>> rows;
  std::vector<std::size_t> order;
};

// Turns a local star into a Star: global sorted cells, sorted rows, canonical centres.
void finish_star(const Neighbourhood& nb, const LocalStar& ls, StarMethod method, FinishScratch& scratch, Star& star) {
  const int m = nb.m(), N = nb.N();
  const std::size_t p = nb.centre();
  const std::size_t count = ls.cells.size() / m;
  star.m = m;
  star.N = N;
  star.closed = ls.closed;
  star.method = method;
  star.neighbours = static_cast<std::uint32_t>(ls.considered);
  // Per cell: the local ids of the non-p vertices ordered by global index.
  auto& local = scratch.local;
  local.resize(count);
  for (std::size_t c = 0; c < count; ++c) {
    auto& l = local[c];
    for (int j = 0; j < m; ++j) l[j] = ls.cells[c * m + j];
    std::sort(l.begin(), l.begin() + m, [&](int x, int y) { return nb[x].global < nb[y].global; });
  }
  auto& rows = scratch.rows;
  rows.resize(count);
  for (std::size_t c = 0; c < count; ++c) {
    auto& r = rows[c];
    for (int j = 0; j < m; ++j) r[j] = nb[local[c][j]].global;
    r[m] = static_cast<int>(p);
    std::sort(r.begin(), r.begin() + m + 1);
  }
  auto& order = scratch.order;
  order.resize(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return std::lexicographical_compare(rows[x].begin(), rows[x].begin() + m + 1, rows[y].begin(),
                                        rows[y].begin() + m + 1);
  });
  star.cells.resize(count * (m + 1));
  star.centres.resize(count * N);
  star.radii2.resize(count);
  star.max_radius2 = 0;
  const double* pp = nb.centre_point();
  const double* basis = nb.centre_basis();
  const double inv = 1.0 / nb.scale();  // exact: a power of two
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t c = order[k];
    std::copy(rows[c].begin(), rows[c].begin() + m + 1, star.cells.begin() + k * (m + 1));
    const LocalPoint* rp[detail::kMaxM];
    for (int j = 0; j < m; ++j) rp[j] = &nb[local[c][j]];
    double v[detail::kMaxM] = {};
    if (!detail::solve_centre(m, rp, v))
      for (int j = 0; j < m; ++j) v[j] = std::numeric_limits<double>::quiet_NaN();  // cannot happen for a cell
    double r2 = 0;
    for (int j = 0; j < m; ++j) v[j] *= inv, r2 += v[j] * v[j];
    for (int k2 = 0; k2 < N; ++k2) {
      double x = pp[k2];
      for (int j = 0; j < m; ++j) x += basis[j * N + k2] * v[j];
      star.centres[k * N + k2] = x;
    }
    star.radii2[k] = r2;
    star.max_radius2 = std::max(star.max_radius2, r2);
  }
}

// The star of the point `nb` was last reset to: the power-cell clipping, or CGAL's regular
// triangulation where a sign is uncertain (always, under StarPath::regular_triangulation).
template <int M>
void one_star(Neighbourhood& nb, detail::PowerCell<M>& cell, LocalStar& ls, FinishScratch& scratch, StarPath path,
              Star& star) {
  StarMethod method = StarMethod::power_cell;
  if (path != StarPath::automatic || power_cell_star<M>(nb, cell, ls) != Outcome::done) {
    detail::regular_triangulation_star(nb, ls);  // reuses the neighbours fetched so far
    method = StarMethod::regular_triangulation;
  }
  finish_star(nb, ls, method, scratch, star);
}

std::size_t default_initial_neighbours(int m) {
  switch (m) {
    case 2: return 16;   // a star considers ~13 neighbours in a random sample, ~7 in an eps-net
    case 3: return 48;   // ~43 in a random sample
    default: return 128;
  }
}

template <int M>
void run_stars(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
               std::span<const std::size_t> which, std::vector<Star>& stars, const StarOptions& options) {
  const std::size_t k0 = options.initial_neighbours ? options.initial_neighbours : default_initial_neighbours(M);
  std::mutex progress_mutex;
  std::atomic<std::size_t> done{0};
  const std::size_t total = which.size();
  parallel_chunks(total, options.threads, 64, [&](int) {
    struct Worker {
      Neighbourhood nb;
      detail::PowerCell<M> cell;
      LocalStar ls;
      FinishScratch scratch;
    };
    auto w = std::make_shared<Worker>(Worker{Neighbourhood(points, planes, index, k0), {}, {}, {}});
    return [&, w](std::size_t b, std::size_t e) {
      for (std::size_t t = b; t < e; ++t) {
        const std::size_t p = which[t];
        w->nb.reset(p);
        one_star<M>(w->nb, w->cell, w->ls, w->scratch, options.path, stars[p]);
      }
      if (options.progress) {
        std::size_t d = done.fetch_add(e - b) + (e - b);
        std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress(d, total);
      }
    };
  });
}

// `planes_cover`: the planes must cover every point (compute_stars); tentative_star reads only m
// from them (the refiner looks ahead in the middle of a round, before that round's points get
// their planes).
void check_inputs(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                  bool planes_cover = true) {
  const int m = planes.intrinsic_dimension();
  if (m < 2 || m > 4)
    throw std::invalid_argument("the tangential complex is implemented for intrinsic dimension m = 2, 3, 4 (got " +
                                std::to_string(m) + ")");
  if (planes.ambient_dimension() != points.dimension)
    throw std::invalid_argument("tangent planes live in R^" + std::to_string(planes.ambient_dimension()) +
                                " but the points in R^" + std::to_string(points.dimension));
  if (points.dimension > io::kMaxAmbientDimension)
    throw std::invalid_argument("ambient dimension above " + std::to_string(io::kMaxAmbientDimension) + " is not supported");
  if (planes_cover && planes.size() < points.size())
    throw std::invalid_argument("tangent planes cover " + std::to_string(planes.size()) + " of " +
                                std::to_string(points.size()) + " points");
  if (index.size() != points.size() || (index.size() && index.dimension() != points.dimension))
    throw std::invalid_argument("the neighbour index holds " + std::to_string(index.size()) + " points, the point set " +
                                std::to_string(points.size()) + "; extend the index after inserting points");
}

}  // namespace

StarStats compute_stars(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                        std::span<const std::size_t> which, std::vector<Star>& stars, const StarOptions& options) {
  check_inputs(points, planes, index);
  for (std::size_t p : which)
    if (p >= points.size())
      throw std::invalid_argument("star " + std::to_string(p) + " requested but there are only " +
                                  std::to_string(points.size()) + " points");
  if (stars.size() < points.size()) stars.resize(points.size());
  // Each star is written by one worker only: drop repeated indices.
  std::vector<std::size_t> unique_which;
  if (!std::is_sorted(which.begin(), which.end()) || std::adjacent_find(which.begin(), which.end()) != which.end()) {
    unique_which.assign(which.begin(), which.end());
    std::sort(unique_which.begin(), unique_which.end());
    unique_which.erase(std::unique(unique_which.begin(), unique_which.end()), unique_which.end());
    which = unique_which;
  }
  // Spatially coherent processing order: neighbouring stars touch the same tree nodes and points.
  const std::vector<std::size_t> order = index.spatial_order(which);
  switch (planes.intrinsic_dimension()) {
    case 2: run_stars<2>(points, planes, index, order, stars, options); break;
    case 3: run_stars<3>(points, planes, index, order, stars, options); break;
    default: run_stars<4>(points, planes, index, order, stars, options); break;
  }
  StarStats stats;
  for (std::size_t p : which) {
    const Star& star = stars[p];
    ++stats.stars;
    stats.cells += star.size();
    stats.fallbacks += options.path == StarPath::automatic && star.method == StarMethod::regular_triangulation;
    stats.open += !star.closed;
    stats.neighbours_total += star.neighbours;
    stats.neighbours_max = std::max<std::size_t>(stats.neighbours_max, star.neighbours);
    stats.max_radius2 = std::max(stats.max_radius2, star.max_radius2);
  }
  return stats;
}

namespace {

template <int M>
void external_star(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                   std::span<const double> x, std::span<const double> basis, Star& star) {
  Neighbourhood nb(points, planes, index, default_initial_neighbours(M));
  detail::PowerCell<M> cell;
  LocalStar ls;
  FinishScratch scratch;
  nb.reset_external(x, basis);
  one_star<M>(nb, cell, ls, scratch, StarPath::automatic, star);
}

}  // namespace

Star tentative_star(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                    std::span<const double> x, std::span<const double> basis) {
  check_inputs(points, planes, index, false);
  const int m = planes.intrinsic_dimension();
  if (static_cast<int>(x.size()) != points.dimension || basis.size() != static_cast<std::size_t>(points.dimension * m))
    throw std::invalid_argument("tentative_star: x needs N coordinates and its basis N*m entries");
  Star star;
  switch (m) {
    case 2: external_star<2>(points, planes, index, x, basis, star); break;
    case 3: external_star<3>(points, planes, index, x, basis, star); break;
    default: external_star<4>(points, planes, index, x, basis, star); break;
  }
  return star;
}

bool power_centre(const io::PointSet& points, const TangentPlanes& planes, std::size_t p, std::span<const int> cell,
                  std::span<double> centre, double* radius2) {
  const int m = planes.intrinsic_dimension(), N = points.dimension;
  if (m < 2 || m > detail::kMaxM || static_cast<int>(cell.size()) != m + 1 || static_cast<int>(centre.size()) != N)
    throw std::invalid_argument("power_centre: a cell has m + 1 vertices and the centre N coordinates");
  const double* pp = points.point(p).data();
  // Same scale rule as the star: any power of two gives the same bits; use the nearest vertex.
  double dmin = std::numeric_limits<double>::infinity();
  for (int g : cell) {
    if (static_cast<std::size_t>(g) == p) continue;
    const double* q = points.point(g).data();
    double d2 = 0;
    for (int k = 0; k < N; ++k) d2 += (q[k] - pp[k]) * (q[k] - pp[k]);
    dmin = std::min(dmin, d2);
  }
  const double scale = detail::scale_for(dmin);
  LocalPoint lp[detail::kMaxM];
  const LocalPoint* rows[detail::kMaxM];
  int r = 0;
  bool has_p = false;
  for (int g : cell) {
    if (static_cast<std::size_t>(g) == p) {
      has_p = true;
      continue;
    }
    if (r == m) break;
    detail::project_neighbour(pp, points.point(g).data(), planes.basis(p).data(), N, m, scale, lp[r]);
    rows[r] = &lp[r];
    ++r;
  }
  if (!has_p || r != m) throw std::invalid_argument("power_centre: the cell must contain p");
  double v[detail::kMaxM] = {};
  if (!detail::solve_centre(m, rows, v)) return false;
  const double inv = 1.0 / scale;
  double r2 = 0;
  for (int j = 0; j < m; ++j) v[j] *= inv, r2 += v[j] * v[j];
  const double* basis = planes.basis(p).data();
  for (int k = 0; k < N; ++k) {
    double x = pp[k];
    for (int j = 0; j < m; ++j) x += basis[j * N + k] * v[j];
    centre[k] = x;
  }
  if (radius2) *radius2 = r2;
  return true;
}

}  // namespace delcert::tangential
