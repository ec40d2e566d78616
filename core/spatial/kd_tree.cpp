#include "core/spatial/kd_tree.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>

namespace delcert {

KdTree::KdTree(const double* coordinates, std::size_t num_points, int dimension, int leaf_size)
    : x_(coordinates), n_(num_points), d_(dimension), index_(num_points) {
  std::iota(index_.begin(), index_.end(), std::size_t{0});
  if (n_) build(0, n_, std::max(1, leaf_size));
}

int KdTree::build(std::size_t begin, std::size_t end, int leaf_size) {
  int id = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{-1, begin, end, -1, -1});
  boxes_.resize(boxes_.size() + 2 * d_);
  double* lo = &boxes_[2 * d_ * id];
  double* hi = lo + d_;
  std::fill(lo, lo + d_, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + d_, -std::numeric_limits<double>::infinity());
  for (std::size_t k = begin; k < end; ++k)
    for (int j = 0; j < d_; ++j) {
      double v = x_[index_[k] * d_ + j];
      lo[j] = std::min(lo[j], v);
      hi[j] = std::max(hi[j], v);
    }
  if (end - begin <= static_cast<std::size_t>(leaf_size)) return id;
  int dim = 0;
  double spread = -1;
  for (int j = 0; j < d_; ++j)
    if (hi[j] - lo[j] > spread) spread = hi[j] - lo[j], dim = j;
  if (spread <= 0) return id;  // all points equal: keep as a leaf
  std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(index_.begin() + begin, index_.begin() + mid, index_.begin() + end, [&](std::size_t a, std::size_t b) {
    double va = x_[a * d_ + dim], vb = x_[b * d_ + dim];
    return va < vb || (va == vb && a < b);
  });
  nodes_[id].split_dim = dim;
  int l = build(begin, mid, leaf_size);
  int r = build(mid, end, leaf_size);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

double KdTree::box_distance2(int node, std::span<const double> q) const {
  const double* lo = &boxes_[2 * d_ * node];
  const double* hi = lo + d_;
  double s = 0;
  for (int j = 0; j < d_; ++j) {
    double e = q[j] < lo[j] ? lo[j] - q[j] : (q[j] > hi[j] ? q[j] - hi[j] : 0.0);
    s += e * e;
  }
  return s;
}

double KdTree::distance2(std::size_t i, std::span<const double> q) const {
  double s = 0;
  const double* p = x_ + i * d_;
  for (int j = 0; j < d_; ++j) {
    double e = p[j] - q[j];
    s += e * e;
  }
  return s;
}

void KdTree::for_each_in_ball(std::span<const double> q, double r2,
                              const std::function<void(std::size_t, double)>& visit) const {
  if (!n_) return;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    int id = stack.back();
    stack.pop_back();
    if (box_distance2(id, q) > r2) continue;
    const Node& nd = nodes_[id];
    if (nd.split_dim < 0) {
      for (std::size_t k = nd.begin; k < nd.end; ++k) {
        double d2 = distance2(index_[k], q);
        if (d2 <= r2) visit(index_[k], d2);
      }
    } else {
      stack.push_back(nd.right);
      stack.push_back(nd.left);
    }
  }
}

std::vector<std::size_t> KdTree::ball(std::span<const double> q, double r2) const {
  std::vector<std::size_t> out;
  for_each_in_ball(q, r2, [&](std::size_t i, double) { out.push_back(i); });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::size_t> KdTree::nearest(std::span<const double> q, std::size_t k) const {
  using Item = std::pair<double, std::size_t>;  // max-heap of the best k so far
  std::priority_queue<Item> best;
  if (!n_ || !k) return {};
  using Pending = std::pair<double, int>;  // min-heap of nodes by box distance
  std::priority_queue<Pending, std::vector<Pending>, std::greater<>> todo;
  todo.emplace(box_distance2(0, q), 0);
  while (!todo.empty()) {
    auto [bd, id] = todo.top();
    todo.pop();
    if (best.size() == k && bd > best.top().first) break;
    const Node& nd = nodes_[id];
    if (nd.split_dim < 0) {
      for (std::size_t t = nd.begin; t < nd.end; ++t) {
        Item it{distance2(index_[t], q), index_[t]};
        if (best.size() < k) best.push(it);
        else if (it < best.top()) best.pop(), best.push(it);
      }
    } else {
      todo.emplace(box_distance2(nd.left, q), nd.left);
      todo.emplace(box_distance2(nd.right, q), nd.right);
    }
  }
  std::vector<std::size_t> out(best.size());
  for (std::size_t i = out.size(); i-- > 0;) out[i] = best.top().second, best.pop();
  return out;
}

}  // namespace delcert
