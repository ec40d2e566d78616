// A uniform grid over (up to) four coordinate axes of the ambient space: the certifier's own
// spatial search, deliberately simpler than the producer's kd-tree.
//
// Sufficiency (what the certifier relies on): candidates(c, r) returns every point q with
// |q_k - c_k| <= r on the grid's axes, hence every point of the closed ball B(c, r) (projection
// onto coordinate axes does not increase distances); ball(c, r) keeps those whose floating-point
// distance passes a filter that provably keeps every point of B(c, r). Both hold for any input
// magnitude (subnormal to DBL_MAX, mixed), any number of points and under any IEEE rounding mode
// (the grid is built under round-to-nearest and queried from certify/star.cpp under
// exact::UpwardRounding): cell indices are computed EXACTLY, see the proof in grid.cpp.
#pragma once

#include <cfloat>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/points.hpp"

namespace delcert::certify::detail {

class PointGrid {
 public:
  static constexpr int kMaxAxes = 4;
  // Cells per axis are below 2^31 and their product is at most 2^62 (int64 keys never wrap):
  // the cell size grows when a hint or the point count would ask for more.
  static constexpr double kMaxCellsPerAxis = 0x1p31;
  static constexpr double kMaxCells = 0x1p62;

  // `cell_hint`: intended cell size (e.g. a typical spacing); <= 0 picks one from the point count
  // and the intrinsic dimension m. The cell size actually used is a power of two near it.
  PointGrid(const io::PointSet& points, int intrinsic_dimension, double cell_hint = 0);
  // A slab of `full`: the same geometry (cells, spacing(), diameter()), holding only the points whose
  // cell index on the first grid axis lies in [first, last] (clamped to the grid), contiguous in cell
  // order. A query answers exactly as `full` does whenever covers() holds for it (an MPI rank's own
  // part plus its halo: certify/distributed.hpp).
  PointGrid(const PointGrid& full, std::int64_t first, std::int64_t last);

  // True when every point of the box |q_k - c_k| <= r (hence of B(c, r), and of every box query
  // with half-widths <= r) is held: the query's cells on the first grid axis lie in the slab
  // (exact, in any rounding mode: the same cell indices as the query's, grid.cpp step 4). Always
  // true for a grid over every point. A NaN centre or radius is covered only by such a grid.
  bool covers(std::span<const double> c, double r) const;
  // The cell indices on the first grid axis of the given points: [min, max] ({0, -1} for none).
  std::pair<std::int64_t, std::int64_t> first_axis_range(std::span<const int> points) const;
  // The halo of width h >= 0 in cells: every query of radius <= h centred in a cell of [first,
  // last] (first grid axis) lies in [first - k, last + k] (grid.cpp). Capped at the number of
  // cells on the axis (also for h NaN or infinite).
  std::int64_t cells_for(double h) const;

  // Indices of every point q with |q_k - c_k| <= r on the grid axes (a superset of B(c, r)),
  // in increasing index order. A NaN radius or centre returns every point.
  std::vector<int> candidates(std::span<const double> c, double r) const;
  // The candidates within floating-point distance r (1 + 2^-40) of c: still every point of B(c, r).
  std::vector<int> ball(std::span<const double> c, double r) const;
  // Calls f(index, coordinates) for each point of ball(c, r), in no particular order
  // (deterministic: it depends only on the grid and the query). The coordinates are the grid's
  // copy, read in sequence (N doubles, equal to points.point(index)).
  template <class F>
  void visit_ball(std::span<const double> c, double r, F&& f) const;
  // The same for the points of ball(c, r) that are also in the box |q_k - c_k| <= half[k] (half:
  // N non-negative half-widths; a superset: the box is applied on the grid's axes only, by cells).
  template <class F>
  void visit_ball(std::span<const double> c, double r, std::span<const double> half, F&& f) const;

  // The cell edge 2^cell_exponent() (a power of two, possibly subnormal).
  int cell_exponent() const { return e_; }
  // A rough typical distance between neighbouring points (a starting radius for searches):
  // positive and finite.
  double spacing() const { return spacing_; }
  // An upper bound on the distance between any two points, positive and finite (capped at
  // DBL_MAX): any r at least the true diameter covers every point (r = +inf always does).
  double diameter() const { return diameter_; }
  // The point indices in cell order (cells in lexicographic order of their integer coordinates).
  const std::vector<int>& order() const { return order_; }
  // The held slab on the first grid axis (every cell for a grid over every point).
  std::pair<std::int64_t, std::int64_t> slab() const { return {slab_lo_, slab_hi_}; }
  // Which cell table the queries read: "dense", "lines" or "cells" (for the tests).
  const char* table() const { return !dense_.empty() ? "dense" : !lines_.empty() ? "lines" : "cells"; }

 private:
  // floor(x / 2^e_) clamped to [k0, k1] of axis t, minus k0: exact, see grid.cpp.
  std::int64_t index(int t, double x) const;
  double scaled_floor(double x) const;  // floor(x / 2^e_) exactly (when it does not overflow)
  std::int64_t key(const std::int64_t* idx) const;
  static double filter_radius2(double r) { return r * r * (1 + 0x1p-40); }  // see grid.cpp
  using Run = std::pair<int, int>;  // [begin, end) in order_
  void gather(std::span<const double> c, double r, std::vector<Run>& out) const;  // the candidates' runs
  void gather(std::span<const double> c, std::span<const double> half, std::vector<Run>& out) const;
  void gather_box(std::span<const double> c, const double* half, std::vector<Run>& out) const;  // per grid axis
  template <class F>
  void visit_runs(std::span<const double> c, double r, const std::vector<Run>& runs, F&& f) const;
  const io::PointSet& points_;
  std::vector<int> axes_;          // up to kMaxAxes coordinate indices
  std::vector<double> k0_, k1_;    // per axis: floor(lo / 2^e), floor(hi / 2^e) (integers)
  std::vector<std::int64_t> dims_; // cells per axis: k1 - k0 + 1
  int e_ = 0;
  double f1_ = 1, f2_ = 1;         // 2^-e = f1 * f2, each factor a double (f2 != 1 only if e < -1022)
  double diameter_ = 0, spacing_ = 1;
  // The held slab [slab_lo_, slab_hi_] of first-axis indices, and the first key and line it holds:
  // dense_ and lines_ are indexed from key_base_ and line_base_ (0 for a grid over every point).
  std::int64_t slab_lo_ = 0, slab_hi_ = 0, key_base_ = 0, line_base_ = 0;
  std::vector<int> order_;  // point indices sorted by cell key
  std::vector<double> ordered_;  // the points' coordinates in that order (n x N: the filter reads them in sequence)
  // One of three cell tables (grid.cpp, "Cost"): when the grid is small enough, dense_: key -> begin
  // in order_ (CSR, #cells + 1); else, when its lines along the last axis are few enough, lines_:
  // line -> begin in order_ (CSR, #lines + 1) and last_: the last-axis index of each point of
  // order_ (sorted within a line); else cells_: key -> [begin, end) of the occupied cells.
  std::vector<int> dense_, lines_;
  std::vector<std::int32_t> last_;
  std::unordered_map<std::int64_t, std::pair<int, int>> cells_;
};

template <class F>
void PointGrid::visit_ball(std::span<const double> c, double r, F&& f) const {
  thread_local std::vector<Run> runs;  // scratch (its capacity is reused)
  gather(c, r, runs);
  visit_runs(c, r, runs, f);
}

template <class F>
void PointGrid::visit_ball(std::span<const double> c, double r, std::span<const double> half, F&& f) const {
  thread_local std::vector<Run> runs;
  gather(c, half, runs);
  visit_runs(c, r, runs, f);
}

template <class F>
void PointGrid::visit_runs(std::span<const double> c, double r, const std::vector<Run>& runs, F&& f) const {
  const int N = points_.dimension;
  const double r2 = filter_radius2(r);
  const bool all = !(r2 > 1e-280) || !(r2 <= DBL_MAX);  // too small to filter safely, infinite or NaN: keep all
  for (const auto& [b, e] : runs)
    for (int k = b; k < e; ++k) {
      const double* x = ordered_.data() + static_cast<std::size_t>(k) * N;
      double d2 = 0;
      for (int j = 0; !all && j < N; ++j) d2 += (x[j] - c[j]) * (x[j] - c[j]);
      if (all || d2 <= r2) f(order_[k], x);
    }
}

}  // namespace delcert::certify::detail
