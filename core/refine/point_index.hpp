// A growing point set with radius queries, for the refiner: points are appended one at a time
// (a batch of insertions) and queried between appends.
//
// Logarithmic method (Bentley-Saxe): the points live in blocks with a static KdTree each, block
// sizes decreasing powers-of-two-ish; an append goes to a small linear buffer, and a full buffer
// is merged with the trailing blocks of no larger size into one new block. Appends cost amortised
// O(log^2 n), queries visit O(log n) trees. Each block owns a copy of its coordinates, so the
// caller's storage may reallocate freely. Indices are global: the i-th appended point is i.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/spatial/kd_tree.hpp"
#include "io/points.hpp"

namespace delcert::refine {

class PointIndex {
 public:
  explicit PointIndex(int dimension = 0) : d_(dimension) {}
  explicit PointIndex(const io::PointSet& points);

  int dimension() const { return d_; }
  std::size_t size() const { return n_; }

  void push_back(std::span<const double> p);

  // visit(index, squared distance) for every point with squared distance <= r2 to q.
  void for_each_in_ball(std::span<const double> q, double r2, const std::function<void(std::size_t, double)>& visit) const;
  // Indices with squared distance <= r2, sorted.
  std::vector<std::size_t> ball(std::span<const double> q, double r2) const;
  // Squared distance from q to the nearest point (+inf when empty), and its index (ties: lowest).
  double nearest_distance2(std::span<const double> q, std::size_t* index = nullptr) const;

 private:
  struct Block {
    std::size_t first = 0;        // global index of its first point
    std::vector<double> coords;   // #points by d
    KdTree tree;
    std::size_t size() const { return tree.size(); }
  };
  void flush_buffer();

  int d_ = 0;
  std::size_t n_ = 0;
  std::vector<std::unique_ptr<Block>> blocks_;  // in global index order
  std::vector<double> buffer_;                  // points not yet in a block
  std::size_t buffer_first_ = 0;
  static constexpr std::size_t kBuffer = 32;
};

}  // namespace delcert::refine
