#include "certify/detail/grid.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

// Why the grid returns a SUPERSET of every queried box, at any scale and in any rounding mode.
//
// Assumptions: IEEE-754 binary64 with gradual underflow (no flush-to-zero / denormals-are-zero:
// the project never enables them, no -ffast-math); every basic operation is correctly rounded in
// the CURRENT rounding mode, which may be to-nearest (the constructor, called from certify.cpp)
// or upward (ball() is called from certify/star.cpp inside exact::UpwardRounding), or any other.
// Input coordinates are finite (the points reader refuses anything else).
//
// 1. Cell edge h = 2^e, e an integer in [-1074, 1023]. The scaled value s(x) = x * f1 * f2 with
//    f1 * f2 = 2^-e (f1 = 2^-e when e >= -1022, else f1 = 2^1022 and f2 = 2^(-e-1022) <= 2^52;
//    every factor is an exact double). Multiplying by a power of two is EXACT in every rounding
//    mode unless the result overflows or is subnormal with lost bits:
//      - f > 1 only grows |x|: exact unless it overflows (then s is +-inf or +-DBL_MAX with the
//        sign of x, depending on the mode: in every case |s| >= 2^1023);
//      - f1 < 1 (e > 0) may underflow: then |true s| < 2^-1022 and, rounding being monotone and
//        2^-1022 a double, |computed s| <= 2^-1022 (possibly 0 or -0); x itself is exact, and its
//        sign decides floor(true s), which is 0 or -1.
//    scaled_floor(x) := (x < 0 && s > -1) ? -1 : floor(s). Claim: it equals floor(x / 2^e)
//    exactly whenever |x / 2^e| <= 2^1001. Proof: if |true s| >= 1 it is normal and (no
//    overflow) s is exact, floor(s) is exact; if 0 <= true s < 1 then s is exact or underflowed
//    to |s| <= 2^-1022, either way in [0, 1) and floor gives 0 (floor(-0) = -0 == 0); if
//    -1 < true s < 0 the first branch gives -1 (x < 0, and s > -1 because s is exact or
//    |s| <= 2^-1022). When |x / 2^e| > 2^1001 the result has the right sign and magnitude
//    > 2^1001 (exact, or overflowed to |s| >= 2^1023), which is all the clamp in 3. needs.
// 2. For each axis, k0 = scaled_floor(lo), k1 = scaled_floor(hi) are exact: e is chosen with
//    |x| / 2^e <= 2^1001 for every point (e >= ilogb(max |coordinate|) - 1000). The number of cells
//    k1 - k0 + 1 is accepted only if the computed k1 - k0 is below 2^31: the true difference is
//    an integer, so if it is below 2^31 it is representable and computed exactly; if it is not,
//    monotone rounding (2^31 being a double) makes the computed value >= 2^31 and e is increased.
//    The product of the cells per axis is kept <= 2^62 with exact int64 arithmetic (fits()).
// 3. index(t, x) = clamp(scaled_floor(x), k0, k1) - k0. The clamp is exact (comparisons), and the
//    subtraction of two integers whose difference lies in [0, 2^31) is exact. So index is the
//    MATHEMATICAL function clamp(floor(x / h), k0, k1) - k0 of the real x: monotone in x and
//    independent of the rounding mode (values beyond 2^1001 clamp to the right end by 1.).
// 4. A query (c, r) (r may differ per axis: the same argument axis by axis): every q with
//    |q_k - c_k| <= r satisfies L <= c_k - r <= q_k <= c_k + r <= U
//    with L = nextafter(fl(c_k - r), -inf), U = nextafter(fl(c_k + r), +inf): in every rounding mode
//    fl(v) is one of the two doubles bracketing v (or v itself), so its predecessor is <= v and its
//    successor >= v, also when fl overflows (+-inf, or +-DBL_MAX under a directed mode whose
//    neighbour is +-inf). By 3., index(L) <= index(q_k) <= index(U): the query scans every cell
//    index between them, hence every such q. NaN centres or radii return every point.
// 5. Keys are the mixed-radix numbers of the index tuples, below the product of dims <= 2^62, so
//    they are distinct and decode exactly (the "scan every occupied cell" path).
//
// Cost: an index is two multiplications, a floor and a clamp (the old code: a subtraction, a
// division and a floor); a query adds two nextafter per axis. The cell edge is the power of two
// nearest (in ratio) to the old choice of three spacings, so cells are within a factor sqrt(2) of
// the old ones per axis. The cells of a query box are read from one of three tables: a dense
// table over every cell (up to 2^24 cells: 1M points on S^2), else a dense table over the lines
// of cells along the last axis with a binary search in each line (10M points on S^2: 1024^2 lines
// instead of a hash lookup per cell), else a hash map of the occupied cells.

namespace delcert::certify::detail {

namespace {

// The power of two nearest to h > 0 (finite) in ratio: exponent e with 2^e in [h/sqrt2, h sqrt2].
int nearest_exponent(double h) {
  int x = 0;
  double f = std::frexp(h, &x);  // h = f 2^x, f in [0.5, 1)
  return f < std::numbers::sqrt2 / 2 ? x - 1 : x;
}

}  // namespace

double PointGrid::scaled_floor(double x) const {
  const double s = (x * f1_) * f2_;
  return (x < 0 && s > -1) ? -1.0 : std::floor(s);
}

std::int64_t PointGrid::index(int t, double x) const {
  return static_cast<std::int64_t>(std::clamp(scaled_floor(x), k0_[t], k1_[t]) - k0_[t]);
}

PointGrid::PointGrid(const io::PointSet& points, int m, double cell_hint) : points_(points) {
  const int N = points.dimension;
  const std::size_t n = points.size();
  std::vector<double> lo(N, 0), hi(N, 0), ext(N, 0);
  for (int k = 0; k < N; ++k) {
    lo[k] = hi[k] = n ? points.point(0)[k] : 0;
    for (std::size_t i = 1; i < n; ++i) {
      lo[k] = std::min(lo[k], points.point(i)[k]);
      hi[k] = std::max(hi[k], points.point(i)[k]);
    }
    // An upper bound of hi - lo in any rounding mode (+inf when it overflows).
    ext[k] = std::nextafter(hi[k] - lo[k], INFINITY);
  }
  std::vector<int> by_extent(N);
  std::iota(by_extent.begin(), by_extent.end(), 0);
  std::stable_sort(by_extent.begin(), by_extent.end(), [&](int a, int b) { return ext[a] > ext[b]; });
  double extent = 0, magnitude = 0;
  for (int k = 0; k < N; ++k) {
    extent = std::max(extent, ext[k]);
    magnitude = std::max({magnitude, std::abs(lo[k]), std::abs(hi[k])});
  }
  // Every distance is at most sqrt(N) * extent; c >= sqrt(N) (the 2^-30 margin exceeds the
  // rounding of sqrt and of the product) and the final nextafter covers the product's rounding,
  // including in the subnormal range. Capped at DBL_MAX (finite: callers double radii up to it).
  const double c = std::sqrt(double(std::max(N, 1))) * (1 + 0x1p-30);
  diameter_ = std::min(std::nextafter(extent * c, INFINITY), DBL_MAX);
  if (!(extent > 0)) extent = 1;  // one point (duplicates are refused by the reader)
  extent = std::min(extent, DBL_MAX);
  const double dim = std::max(1, std::min(m, 3));
  // About three sample spacings per cell: a query visits few cells, most of them occupied.
  spacing_ = std::clamp(extent * std::pow(1.0 / std::max<double>(1, double(n)), 1.0 / dim), DBL_TRUE_MIN, DBL_MAX);
  const double want = cell_hint > 0 && cell_hint <= DBL_MAX ? cell_hint : 3 * std::min(spacing_, DBL_MAX / 4);
  // e >= -1074 (2^e a double), e <= 1023, and |x| / 2^e <= 2^1001 for every coordinate x.
  const int e_min = std::max(-1074, magnitude > 0 ? std::ilogb(magnitude) + 1 - 1001 : -1074);
  const int e_start = std::clamp(nearest_exponent(want), e_min, 1023);

  auto set_exponent = [&](int e) {
    e_ = e;
    if (e >= -1022) {
      f1_ = std::ldexp(1.0, -e), f2_ = 1;
    } else {
      f1_ = 0x1p1022, f2_ = std::ldexp(1.0, -e - 1022);
    }
  };
  // Sets k0_, k1_, dims_ for the current axes and exponent; false when a limit is exceeded.
  auto fits = [&]() {
    k0_.clear(), k1_.clear(), dims_.clear();
    std::int64_t total = 1;
    for (int a : axes_) {
      k0_.push_back(scaled_floor(lo[a]));
      k1_.push_back(scaled_floor(hi[a]));
      const double d = k1_.back() - k0_.back();
      if (!(d < kMaxCellsPerAxis)) return false;  // the true count is >= 2^31 (see 2.)
      dims_.push_back(static_cast<std::int64_t>(d) + 1);
      // total <= 2^62 and dims <= 2^31: the product below is < 2^93 -- test before multiplying.
      if (dims_.back() > static_cast<std::int64_t>(kMaxCells) / total) return false;
      total *= dims_.back();
    }
    return true;
  };
  auto total_cells = [&]() {
    double total = 1;
    for (auto d : dims_) total *= double(d);
    return total;
  };
  // Up to kMaxAxes axes (a fourth axis cuts the candidates of a 3-manifold in R^4 several fold),
  // but only three when four would not fit a dense table.
  auto dense_ok = [&](double total) { return total <= std::max(64.0 * double(n), double(1 << 20)) && total <= double(1 << 24); };
  for (int A = std::min(N, kMaxAxes); A >= 1; --A) {
    axes_.assign(by_extent.begin(), by_extent.begin() + A);
    int e = e_start;
    set_exponent(e);
    // Terminates: at e = 1023 every coordinate scales into [-2, 2), so each axis has <= 4 cells.
    while (!fits()) set_exponent(++e);
    if (A <= 3 || dense_ok(total_cells())) break;
  }
  if (axes_.empty()) set_exponent(e_start);

  std::vector<std::int64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t idx[kMaxAxes] = {0, 0, 0, 0};
    for (std::size_t t = 0; t < axes_.size(); ++t) idx[t] = index(static_cast<int>(t), points.point(i)[axes_[t]]);
    keys[i] = key(idx);
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return keys[a] < keys[b]; });
  ordered_.resize(n * N);
  for (std::size_t k = 0; k < n; ++k) std::copy_n(points.point(order_[k]).data(), N, ordered_.begin() + k * N);
  const double total = total_cells();
  const std::int64_t last_dim = axes_.empty() ? 1 : dims_.back();
  const double lines = total / double(last_dim);  // exact: a product of integers below 2^62 over a factor
  if (dense_ok(total)) {
    dense_.assign(static_cast<std::size_t>(total) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++dense_[keys[i] + 1];
    for (std::size_t c = 1; c < dense_.size(); ++c) dense_[c] += dense_[c - 1];
  } else if (axes_.size() >= 2 && dense_ok(lines)) {
    // key = line * last_dim + last-axis index (key()), so order_, sorted by key, is sorted by line
    // and within a line by the last-axis index.
    lines_.assign(static_cast<std::size_t>(lines) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++lines_[keys[i] / last_dim + 1];
    for (std::size_t l = 1; l < lines_.size(); ++l) lines_[l] += lines_[l - 1];
    last_.resize(n);
    for (std::size_t k = 0; k < n; ++k) last_[k] = static_cast<std::int32_t>(keys[order_[k]] % last_dim);  // < 2^31
  } else {
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i;
      while (j < n && keys[order_[j]] == keys[order_[i]]) ++j;
      cells_[keys[order_[i]]] = {static_cast<int>(i), static_cast<int>(j)};
      i = j;
    }
  }
  slab_lo_ = 0, slab_hi_ = axes_.empty() ? 0 : dims_[0] - 1;
}

// The slab's points are one run of order_: keys are mixed-radix with the first axis most
// significant (key()), so the cells with first-axis index in [first, last] are the keys in
// [first * stride, (last + 1) * stride), stride = the product of the other axes' cell counts,
// and order_ is sorted by key. The tables are the full grid's, cut to that range and shifted.
PointGrid::PointGrid(const PointGrid& full, std::int64_t first, std::int64_t last)
    : points_(full.points_), axes_(full.axes_), k0_(full.k0_), k1_(full.k1_), dims_(full.dims_), e_(full.e_),
      f1_(full.f1_), f2_(full.f2_), diameter_(full.diameter_), spacing_(full.spacing_) {
  const int N = points_.dimension;
  if (full.key_base_ != 0 || full.slab_lo_ != 0 || (!full.axes_.empty() && full.slab_hi_ != full.dims_[0] - 1))
    throw std::logic_error("PointGrid: a slab is cut from a grid over every point");
  if (axes_.empty() || full.order_.empty()) {  // nothing to cut: every point
    order_ = full.order_, ordered_ = full.ordered_, dense_ = full.dense_, lines_ = full.lines_, last_ = full.last_;
    cells_ = full.cells_, slab_lo_ = full.slab_lo_, slab_hi_ = full.slab_hi_;
    return;
  }
  slab_lo_ = std::clamp<std::int64_t>(first, 0, dims_[0] - 1), slab_hi_ = std::clamp<std::int64_t>(last, 0, dims_[0] - 1);
  if (slab_hi_ < slab_lo_) slab_hi_ = slab_lo_;  // (an empty request keeps one slice: covers() stays exact)
  std::int64_t stride = 1;
  for (std::size_t t = 1; t < dims_.size(); ++t) stride *= dims_[t];
  const std::int64_t last_dim = dims_.back();
  key_base_ = slab_lo_ * stride;
  const std::int64_t key_end = (slab_hi_ + 1) * stride;  // <= the product of dims_ <= 2^62
  std::int64_t b = 0, e = 0;
  if (!full.dense_.empty()) {
    b = full.dense_[key_base_], e = full.dense_[key_end];
    dense_.assign(full.dense_.begin() + key_base_, full.dense_.begin() + key_end + 1);
    for (int& x : dense_) x -= static_cast<int>(b);
  } else if (!full.lines_.empty()) {
    line_base_ = key_base_ / last_dim;  // stride is a multiple of last_dim (at least two axes here)
    const std::int64_t line_end = key_end / last_dim;
    b = full.lines_[line_base_], e = full.lines_[line_end];
    lines_.assign(full.lines_.begin() + line_base_, full.lines_.begin() + line_end + 1);
    for (int& x : lines_) x -= static_cast<int>(b);
    last_.assign(full.last_.begin() + b, full.last_.begin() + e);
  } else {
    b = static_cast<std::int64_t>(full.order_.size()), e = 0;
    for (const auto& [k, range] : full.cells_)
      if (k >= key_base_ && k < key_end) b = std::min<std::int64_t>(b, range.first), e = std::max<std::int64_t>(e, range.second);
    if (e < b) b = e = 0;
    for (const auto& [k, range] : full.cells_)
      if (k >= key_base_ && k < key_end)
        cells_[k] = {range.first - static_cast<int>(b), range.second - static_cast<int>(b)};
  }
  order_.assign(full.order_.begin() + b, full.order_.begin() + e);
  ordered_.assign(full.ordered_.begin() + b * N, full.ordered_.begin() + e * N);
}

bool PointGrid::covers(std::span<const double> c, double r) const {
  if (axes_.empty() || (slab_lo_ == 0 && slab_hi_ == dims_[0] - 1)) return true;  // every point is held
  const double x = c[axes_[0]];
  // The query's first-axis cells, exactly as gather_box computes them (step 4, then the clamp of 3.).
  const double a = scaled_floor(std::nextafter(x - r, -INFINITY)), b = scaled_floor(std::nextafter(x + r, INFINITY));
  if (!(r >= 0) || std::isnan(a) || std::isnan(b)) return false;
  const std::int64_t lo = static_cast<std::int64_t>(std::clamp(a, k0_[0], k1_[0]) - k0_[0]),
                     hi = static_cast<std::int64_t>(std::clamp(b, k0_[0], k1_[0]) - k0_[0]);
  return lo >= slab_lo_ && hi <= slab_hi_;
}

std::pair<std::int64_t, std::int64_t> PointGrid::first_axis_range(std::span<const int> points) const {
  if (points.empty() || axes_.empty()) return {0, -1};
  std::int64_t lo = dims_[0], hi = -1;
  for (int p : points) {
    const std::int64_t i = index(0, points_.point(p)[axes_[0]]);
    lo = std::min(lo, i), hi = std::max(hi, i);
  }
  return {lo, hi};
}

std::int64_t PointGrid::cells_for(double h) const {
  const std::int64_t cap = axes_.empty() ? 1 : dims_[0];
  // A ball of radius h centred at x in cell i (i 2^e <= x < (i + 1) 2^e) has x - h >= (i - t) 2^e,
  // t = h / 2^e, so its lowest cell is >= i - ceil(t); the query's nextafter (step 4) can lower
  // fl(x - h) across one more boundary: >= i - ceil(t) - 1. Likewise above. So k = ceil(t) + 1.
  // t is computed as (h * f1) * f2: multiplying by a power of two is exact unless it overflows
  // (+inf or DBL_MAX: the cap) or lands below 2^-1022 (then 0 < t < 1, computed possibly as 0:
  // ceil(t) = 1 is used for every h > 0).
  const double t = (h * f1_) * f2_;
  const double cells = std::max(std::ceil(t), h > 0 ? 1.0 : 0.0) + 1;
  if (!(cells < double(cap))) return cap;
  return static_cast<std::int64_t>(cells);
}

std::int64_t PointGrid::key(const std::int64_t* idx) const {
  std::int64_t k = 0;  // < product of dims_ <= 2^62: no overflow (see 5.)
  for (std::size_t t = 0; t < axes_.size(); ++t) k = k * dims_[t] + idx[t];
  return k;
}

std::vector<int> PointGrid::candidates(std::span<const double> c, double r) const {
  std::vector<Run> runs;
  gather(c, r, runs);
  std::vector<int> out;
  for (const auto& [b, e] : runs) out.insert(out.end(), order_.begin() + b, order_.begin() + e);
  std::sort(out.begin(), out.end());
  return out;
}

void PointGrid::gather(std::span<const double> c, double r, std::vector<Run>& out) const {
  double half[kMaxAxes];
  for (double& h : half) h = r;
  gather_box(c, half, out);
}

void PointGrid::gather(std::span<const double> c, std::span<const double> half, std::vector<Run>& out) const {
  double h[kMaxAxes] = {0, 0, 0, 0};
  for (std::size_t t = 0; t < axes_.size(); ++t) h[t] = half[axes_[t]];
  gather_box(c, h, out);
}

void PointGrid::gather_box(std::span<const double> c, const double* half, std::vector<Run>& out) const {
  out.clear();
  const int A = static_cast<int>(axes_.size());
  const Run all{0, static_cast<int>(order_.size())};
  if (A == 0 || order_.empty()) {  // no axis (dimension 0): every point
    out.push_back(all);
    return;
  }
  std::int64_t lo[kMaxAxes] = {0, 0, 0, 0}, hi[kMaxAxes] = {0, 0, 0, 0};
  double cells = 1;
  for (int t = 0; t < A; ++t) {
    const double x = c[axes_[t]], r = half[t];
    if (r < 0) return;  // an empty box (NaN goes on: every point)
    // Proof step 4: L <= c - r and U >= c + r in every rounding mode; a, b as in step 1.
    const double a = scaled_floor(std::nextafter(x - r, -INFINITY)), b = scaled_floor(std::nextafter(x + r, INFINITY));
    if (std::isnan(a) || std::isnan(b)) {  // NaN centre or radius: every point
      out.assign(1, all);
      return;
    }
    if (b < k0_[t] || a > k1_[t]) return;  // the box misses every point (exact test)
    lo[t] = static_cast<std::int64_t>(std::max(a, k0_[t]) - k0_[t]);  // = index(t, L), step 3
    hi[t] = static_cast<std::int64_t>(std::min(b, k1_[t]) - k0_[t]);  // = index(t, U)
    if (t == 0) {  // a slab (covers()): only its cells are held
      lo[0] = std::max(lo[0], slab_lo_), hi[0] = std::min(hi[0], slab_hi_);
      if (lo[0] > hi[0]) return;
    }
    cells *= double(hi[t] - lo[t] + 1);
  }
  if (!cells_.empty() && cells >= double(cells_.size())) {  // cheaper to scan every occupied cell
    for (const auto& [k, range] : cells_) {
      std::int64_t rest = k, idx[kMaxAxes] = {0, 0, 0, 0};
      for (int t = A - 1; t >= 0; --t) idx[t] = rest % dims_[t], rest /= dims_[t];
      bool inside = true;
      for (int t = 0; t < A; ++t) inside = inside && idx[t] >= lo[t] && idx[t] <= hi[t];
      if (inside) out.push_back(range);
    }
    return;
  }
  // Every cell of the index box, the last axis innermost (odometer over the other axes).
  std::int64_t idx[kMaxAxes];
  for (int t = 0; t < A; ++t) idx[t] = lo[t];
  for (;;) {
    if (!dense_.empty()) {
      // Keys along the last axis are consecutive: one run of order_ per line of cells.
      std::int64_t a[kMaxAxes], b[kMaxAxes];
      std::copy(idx, idx + A, a);
      std::copy(idx, idx + A, b);
      a[A - 1] = lo[A - 1], b[A - 1] = hi[A - 1];
      const std::int64_t ka = key(a) - key_base_, kb = key(b) + 1 - key_base_;
      if (dense_[ka] < dense_[kb]) out.push_back({dense_[ka], dense_[kb]});
    } else if (!lines_.empty()) {
      // The line's points are sorted by last-axis index: two binary searches cut out [lo, hi].
      std::int64_t line = 0;
      for (int t = 0; t < A - 1; ++t) line = line * dims_[t] + idx[t];
      line -= line_base_;
      const auto b = last_.begin() + lines_[line], e = last_.begin() + lines_[line + 1];
      const auto from = std::lower_bound(b, e, lo[A - 1]), to = std::upper_bound(from, e, hi[A - 1]);
      if (from < to) out.push_back({static_cast<int>(from - last_.begin()), static_cast<int>(to - last_.begin())});
    } else {
      for (idx[A - 1] = lo[A - 1]; idx[A - 1] <= hi[A - 1]; ++idx[A - 1]) {
        auto it = cells_.find(key(idx));
        if (it != cells_.end()) out.push_back(it->second);
      }
    }
    int t = A - 2;
    while (t >= 0 && idx[t] == hi[t]) idx[t] = lo[t], --t;
    if (t < 0) break;
    ++idx[t];
  }
}

// The filter of visit_ball (grid.hpp) keeps every point of B(c, r), in any rounding mode: if
// |x - c| <= r then r is finite or +inf. If r * r * (1 + 2^-40) overflows to +inf (or is NaN-free
// +inf) every candidate is kept.
// Otherwise r < 2^512 and every |x_j - c_j| <= r, so no operation below overflows; each of the N
// differences, squares and sums is correctly rounded, so the computed d2 is at most
// |x - c|^2 (1 + 2^-52)^(N+2) + (2N) 2^-1074 (the absolute term: rounding in the subnormal
// range), and the computed r2 is at least r^2 (1 + 2^-40)(1 - 2^-52)^2. For N <= 64 and
// r2 > 1e-280 the first is below the second. Below 1e-280 every candidate is kept.
std::vector<int> PointGrid::ball(std::span<const double> c, double r) const {
  std::vector<int> out;
  visit_ball(c, r, [&](int i, const double*) { out.push_back(i); });
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace delcert::certify::detail
