#include "certify/grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace delcert::certify {

PointGrid::PointGrid(const io::PointSet& points, int m, double cell_hint) : points_(points) {
  const int N = points.dimension;
  const std::size_t n = points.size();
  std::vector<double> lo(N, 0), hi(N, 0);
  for (int k = 0; k < N; ++k) {
    lo[k] = hi[k] = n ? points.point(0)[k] : 0;
    for (std::size_t i = 1; i < n; ++i) {
      lo[k] = std::min(lo[k], points.point(i)[k]);
      hi[k] = std::max(hi[k], points.point(i)[k]);
    }
  }
  std::vector<int> by_extent(N);
  std::iota(by_extent.begin(), by_extent.end(), 0);
  std::stable_sort(by_extent.begin(), by_extent.end(), [&](int a, int b) { return hi[a] - lo[a] > hi[b] - lo[b]; });
  double extent = 0, diag2 = 0, magnitude = 0;
  for (int k = 0; k < N; ++k) {
    extent = std::max(extent, hi[k] - lo[k]);
    diag2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    magnitude = std::max({magnitude, std::abs(lo[k]), std::abs(hi[k])});
  }
  diameter_ = std::sqrt(diag2) * (1 + 1e-12) + 1e-300;
  if (extent <= 0) extent = 1;
  double dim = std::max(1, std::min(m, 3));
  // About three sample spacings per cell: a query visits few cells, most of them occupied.
  spacing_ = extent * std::pow(1.0 / std::max<double>(1, double(n)), 1.0 / dim);
  h_ = cell_hint > 0 ? cell_hint : 3 * spacing_;
  h_ = std::max(h_, std::ldexp(std::max(extent, magnitude), -30));
  // Up to kMaxAxes axes (a fourth axis cuts the candidates of a 3-manifold in R^4 several fold),
  // but only three when four would not fit a dense table.
  auto dense_ok = [&](double total) { return total <= std::max(64.0 * double(n), double(1 << 20)) && total <= double(1 << 24); };
  for (int A = std::min(N, kMaxAxes); A >= 1; --A) {
    axes_.assign(by_extent.begin(), by_extent.begin() + A);
    origin_.clear();
    dims_.clear();
    double total = 1;
    for (int a : axes_) {
      origin_.push_back(lo[a]);
      dims_.push_back(static_cast<std::int64_t>(std::floor((hi[a] - lo[a]) / h_)) + 1);
      total *= double(dims_.back());
    }
    if (A <= 3 || dense_ok(total)) break;
  }
  std::vector<std::int64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t idx[kMaxAxes] = {0, 0, 0, 0};
    for (std::size_t t = 0; t < axes_.size(); ++t)
      idx[t] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((points.point(i)[axes_[t]] - origin_[t]) / h_)), 0,
                                        dims_[t] - 1);
    keys[i] = key(idx);
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return keys[a] < keys[b]; });
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && keys[order_[j]] == keys[order_[i]]) ++j;
    cells_[keys[order_[i]]] = {static_cast<int>(i), static_cast<int>(j)};
    i = j;
  }
  double total = 1;
  for (auto d : dims_) total *= double(d);
  if (dense_ok(total)) {
    dense_.assign(static_cast<std::size_t>(total) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++dense_[keys[i] + 1];
    for (std::size_t c = 1; c < dense_.size(); ++c) dense_[c] += dense_[c - 1];
  }
}

std::int64_t PointGrid::key(const std::int64_t* idx) const {
  std::int64_t k = 0;
  for (std::size_t t = 0; t < axes_.size(); ++t) k = k * dims_[t] + idx[t];
  return k;
}

std::vector<int> PointGrid::candidates(std::span<const double> c, double r) const {
  std::vector<int> out = gather(c, r);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int> PointGrid::gather(std::span<const double> c, double r) const {
  std::vector<int> out;
  out.reserve(64);
  const int A = static_cast<int>(axes_.size());
  std::int64_t lo[kMaxAxes] = {0, 0, 0, 0}, hi[kMaxAxes] = {0, 0, 0, 0};
  double cells = 1;
  for (int t = 0; t < A; ++t) {
    // The 2^-10 cell widening absorbs the rounding of the index computation (see header).
    double a = std::floor((c[axes_[t]] - r - origin_[t]) / h_ - 0x1p-10),
           b = std::floor((c[axes_[t]] + r - origin_[t]) / h_ + 0x1p-10);
    lo[t] = static_cast<std::int64_t>(std::clamp<double>(a, 0, double(dims_[t] - 1)));
    hi[t] = static_cast<std::int64_t>(std::clamp<double>(b, 0, double(dims_[t] - 1)));
    if (b < 0 || a > double(dims_[t] - 1)) return out;  // the box misses the grid
    cells *= double(hi[t] - lo[t] + 1);
  }
  if (A == 0) return order_;  // no axis (dimension 0): every point
  if (cells >= double(cells_.size()) && dense_.empty()) {  // cheaper to scan every occupied cell
    for (const auto& [k, range] : cells_) {
      std::int64_t rest = k, idx[kMaxAxes] = {0, 0, 0, 0};
      for (int t = A - 1; t >= 0; --t) idx[t] = rest % dims_[t], rest /= dims_[t];
      bool inside = true;
      for (int t = 0; t < A; ++t) inside = inside && idx[t] >= lo[t] && idx[t] <= hi[t];
      if (inside) out.insert(out.end(), order_.begin() + range.first, order_.begin() + range.second);
    }
    return out;
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
      out.insert(out.end(), order_.begin() + dense_[key(a)], order_.begin() + dense_[key(b) + 1]);
    } else {
      for (idx[A - 1] = lo[A - 1]; idx[A - 1] <= hi[A - 1]; ++idx[A - 1]) {
        auto it = cells_.find(key(idx));
        if (it != cells_.end()) out.insert(out.end(), order_.begin() + it->second.first, order_.begin() + it->second.second);
      }
    }
    int t = A - 2;
    while (t >= 0 && idx[t] == hi[t]) idx[t] = lo[t], --t;
    if (t < 0) break;
    ++idx[t];
  }
  return out;
}

std::vector<int> PointGrid::ball(std::span<const double> c, double r) const {
  std::vector<int> out = gather(c, r);
  const int N = points_.dimension;
  const double r2 = r * r * (1 + 0x1p-40);
  if (!(r2 > 1e-280)) {  // too small to filter safely (underflow): keep every candidate
    std::sort(out.begin(), out.end());
    return out;
  }
  std::size_t k = 0;
  for (int i : out) {
    auto x = points_.point(i);
    double d2 = 0;
    for (int j = 0; j < N; ++j) d2 += (x[j] - c[j]) * (x[j] - c[j]);
    if (d2 <= r2) out[k++] = i;
  }
  out.resize(k);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace delcert::certify
