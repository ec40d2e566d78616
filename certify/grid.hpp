// A uniform grid over (up to) four coordinate axes of the ambient space: the certifier's own
// spatial search, deliberately simpler than the producer's kd-tree.
//
// Sufficiency (what the certifier relies on): candidates(c, r) returns every point q with
// |q_k - c_k| <= r on the grid's axes, hence every point of the closed ball B(c, r) (projection
// onto coordinate axes does not increase distances); ball(c, r) keeps those whose floating-point
// distance is at most r (1 + 2^-40), which still contains every point of B(c, r) because that
// computation's relative error is below (N + 4) 2^-52. Cell indices are computed in floating
// point: cells are never smaller than 2^-30 times max(extent, largest |coordinate|), so an index
// is off by less than 2^-20 of a cell, and the query widens its index range by 2^-10 of a cell
// on each side.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/io/points.hpp"

namespace delcert::certify {

class PointGrid {
 public:
  static constexpr int kMaxAxes = 4;

  // `cell_hint`: intended cell size (e.g. a typical spacing); <= 0 picks one from the point count
  // and the intrinsic dimension m.
  PointGrid(const io::PointSet& points, int intrinsic_dimension, double cell_hint = 0);

  // Indices of every point q with |q_k - c_k| <= r on the grid axes (a superset of B(c, r)),
  // in increasing index order.
  std::vector<int> candidates(std::span<const double> c, double r) const;
  // The candidates within floating-point distance r (1 + 2^-40) of c: still every point of B(c, r).
  std::vector<int> ball(std::span<const double> c, double r) const;

  double cell_size() const { return h_; }
  // A rough typical distance between neighbouring points (a starting radius for searches).
  double spacing() const { return spacing_; }
  // Length of the diagonal of the bounding box: any r at least this covers every point.
  double diameter() const { return diameter_; }

 private:
  std::int64_t key(const std::int64_t* idx) const;
  std::vector<int> gather(std::span<const double> c, double r) const;  // candidates, unsorted
  const io::PointSet& points_;
  std::vector<int> axes_;          // up to kMaxAxes coordinate indices
  std::vector<double> origin_;     // per axis
  std::vector<std::int64_t> dims_; // cells per axis
  double h_ = 1, diameter_ = 0, spacing_ = 1;
  std::vector<int> order_;  // point indices sorted by cell key
  std::unordered_map<std::int64_t, std::pair<int, int>> cells_;  // key -> [begin, end) in order_
  std::vector<int> dense_;  // when the grid is small enough: key -> begin in order_ (CSR, #cells + 1)
};

}  // namespace delcert::certify
