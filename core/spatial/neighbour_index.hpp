// NeighbourIndex: the one nearest-point search of the producer. Exact k-nearest and radius
// queries over a point set (#points by N) that may grow: the sampler indexes its dense sample,
// the tangential complex its points, and the refiner appends each inserted point and queries
// between insertions.
//
// A kd-tree over a copy of the points, stored in tree order so that a leaf is contiguous in
// memory, searched depth-first with incremental cell distances and a bounded heap. Appended
// points go to a small buffer scanned by every query; the tree is rebuilt when the buffer
// exceeds max(64, size / 32) points, so an append costs O(log n) amortised.
//
// Results are exact and deterministic: nearest(q, k) is the k smallest (squared distance, index)
// pairs, sorted, whatever the tree shape or the buffer content; the squared distance is
// sum_j (x_j - q_j)^2 summed in coordinate order, as everywhere in core/tangential.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "io/points.hpp"

namespace delcert::spatial {

class NeighbourIndex {
 public:
  NeighbourIndex() = default;
  explicit NeighbourIndex(const io::PointSet& points);

  std::size_t size() const { return n_; }
  int dimension() const { return d_; }

  // Appends a point; its index is the previous size().
  void push_back(std::span<const double> p);
  // Appends points[size()] .. points[points.size()-1] (after the caller appended to its set).
  void extend(const io::PointSet& points);

  // The min(k, size()) nearest points to q, sorted by (squared distance, index), with their
  // squared distances.
  void nearest(std::span<const double> q, std::size_t k, std::vector<std::pair<double, std::size_t>>& out) const;
  // Every point with squared distance <= r2 to q, in no particular order.
  void ball(std::span<const double> q, double r2, std::vector<std::pair<double, std::size_t>>& out) const;
  // The indices of those points, sorted.
  std::vector<std::size_t> ball(std::span<const double> q, double r2) const;
  // visit(index, squared distance) for each of those points, in no particular order.
  void for_each_in_ball(std::span<const double> q, double r2,
                        const std::function<void(std::size_t, double)>& visit) const;
  // Squared distance from q to the nearest point (+inf when empty) and, if `index` is given, that
  // point's index (among equally near points the lowest).
  double nearest_distance2(std::span<const double> q, std::size_t* index = nullptr) const;

  // `indices` reordered so that nearby points come together (the tree's leaf order; appended
  // points not yet in the tree last). Processing queries in this order keeps the tree hot in
  // the cache; it changes no result.
  std::vector<std::size_t> spatial_order(std::span<const std::size_t> indices) const;

 private:
  struct Node {
    int dim = -1;  // -1: leaf
    double split = 0;
    std::size_t begin = 0, end = 0;  // leaf range in tree order
    int left = -1, right = -1;
  };
  void rebuild();
  int build(std::size_t begin, std::size_t end);
  double distance2(const double* x, const double* q) const {
    double s = 0;
    for (int j = 0; j < d_; ++j) {
      const double e = x[j] - q[j];
      s += e * e;
    }
    return s;
  }

  int d_ = 0;
  std::size_t n_ = 0;
  std::vector<double> coords_;     // tree points in tree order, #tree points by d
  std::vector<std::size_t> ids_;   // their indices
  std::vector<Node> nodes_;
  std::vector<double> buffer_;     // appended points not in the tree yet, #buffer by d
  std::size_t buffer_first_ = 0;   // index of the first buffered point
};

}  // namespace delcert::spatial
