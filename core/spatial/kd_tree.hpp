// A static kd-tree over a fixed set of points in R^d (#points by d, row-major doubles, not
// copied: the caller keeps them alive). Built once in O(n log n); answers radius and
// k-nearest queries. Deterministic: ties are broken by point index.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace delcert {

class KdTree {
 public:
  KdTree() = default;
  KdTree(const double* coordinates, std::size_t num_points, int dimension, int leaf_size = 12);

  std::size_t size() const { return n_; }
  int dimension() const { return d_; }

  // Calls visit(index, squared_distance) for every point with squared distance <= r2 to q,
  // in no particular order.
  void for_each_in_ball(std::span<const double> q, double r2,
                        const std::function<void(std::size_t, double)>& visit) const;

  // Indices of all points with squared distance <= r2 to q, sorted by index.
  std::vector<std::size_t> ball(std::span<const double> q, double r2) const;

  // The k nearest points (fewer if the tree is smaller), sorted by (distance, index).
  std::vector<std::size_t> nearest(std::span<const double> q, std::size_t k) const;

 private:
  struct Node {
    int split_dim = -1;  // -1 for a leaf
    std::size_t begin = 0, end = 0;
    int left = -1, right = -1;
  };
  int build(std::size_t begin, std::size_t end, int leaf_size);
  double box_distance2(int node, std::span<const double> q) const;
  double distance2(std::size_t i, std::span<const double> q) const;

  const double* x_ = nullptr;
  std::size_t n_ = 0;
  int d_ = 0;
  std::vector<std::size_t> index_;
  std::vector<Node> nodes_;
  std::vector<double> boxes_;  // per node: d lower bounds then d upper bounds
};

}  // namespace delcert
