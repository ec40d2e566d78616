#include "core/spatial/neighbour_index.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace delcert::spatial {

namespace {

constexpr std::size_t kLeafSize = 8;
constexpr int kMaxDimension = io::kMaxAmbientDimension;
// A cell is skipped only when its lower bound exceeds the current threshold by more than the
// rounding of either side (incremental bounds and point distances agree to a few ulps).
constexpr double kPruneSlack = 1 + 1e-12;

}  // namespace

NeighbourIndex::NeighbourIndex(const io::PointSet& points) : d_(points.dimension), n_(points.size()) {
  if (d_ > kMaxDimension) throw std::invalid_argument("NeighbourIndex: dimension above " + std::to_string(kMaxDimension) + " is not supported");
  coords_ = points.coordinates;
  ids_.resize(n_);
  std::iota(ids_.begin(), ids_.end(), std::size_t{0});
  rebuild();
}

void NeighbourIndex::push_back(std::span<const double> p) {
  if (static_cast<int>(p.size()) != d_) throw std::invalid_argument("NeighbourIndex::push_back: wrong dimension");
  if (buffer_.empty()) buffer_first_ = n_;
  buffer_.insert(buffer_.end(), p.begin(), p.end());
  ++n_;
  if (buffer_.size() / d_ > std::max<std::size_t>(64, n_ / 32)) rebuild();
}

void NeighbourIndex::extend(const io::PointSet& points) {
  if (points.dimension != d_ && n_ == 0) d_ = points.dimension;
  if (points.dimension != d_) throw std::invalid_argument("NeighbourIndex::extend: wrong dimension");
  for (std::size_t i = n_; i < points.size(); ++i) push_back(points.point(i));
}

void NeighbourIndex::rebuild() {
  // Gather every point in index order, then lay them out in tree order.
  std::vector<double> src(n_ * d_);
  for (std::size_t t = 0; t < ids_.size(); ++t)
    std::copy(coords_.begin() + t * d_, coords_.begin() + (t + 1) * d_, src.begin() + ids_[t] * d_);
  std::copy(buffer_.begin(), buffer_.end(), src.begin() + buffer_first_ * d_);
  buffer_.clear();
  ids_.resize(n_);
  std::iota(ids_.begin(), ids_.end(), std::size_t{0});
  coords_.swap(src);  // coords_ in index order while building
  nodes_.clear();
  if (n_) build(0, n_);
  std::vector<double> ordered(n_ * d_);
  for (std::size_t t = 0; t < n_; ++t)
    std::copy(coords_.begin() + ids_[t] * d_, coords_.begin() + (ids_[t] + 1) * d_, ordered.begin() + t * d_);
  coords_.swap(ordered);
}

int NeighbourIndex::build(std::size_t begin, std::size_t end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{-1, 0, begin, end, -1, -1});
  if (end - begin <= kLeafSize) return id;
  int dim = 0;
  double spread = -1;
  for (int j = 0; j < d_; ++j) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t t = begin; t < end; ++t) {
      const double v = coords_[ids_[t] * d_ + j];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (hi - lo > spread) spread = hi - lo, dim = j;
  }
  if (!(spread > 0)) return id;  // identical points: one leaf
  const std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(ids_.begin() + begin, ids_.begin() + mid, ids_.begin() + end, [&](std::size_t a, std::size_t b) {
    const double va = coords_[a * d_ + dim], vb = coords_[b * d_ + dim];
    return va < vb || (va == vb && a < b);
  });
  // Left holds values <= split, right values >= split.
  const double split = coords_[ids_[mid] * d_ + dim];
  const int left = build(begin, mid);
  const int right = build(mid, end);
  nodes_[id].dim = dim;
  nodes_[id].split = split;
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

namespace {

using Item = std::pair<double, std::size_t>;  // (squared distance, index), compared lexicographically

struct KnnSearch {
  const double* q;
  std::size_t k;
  std::vector<Item>& heap;  // max-heap of the best k so far
  double off[kMaxDimension];

  double threshold() const { return heap.size() < k ? std::numeric_limits<double>::infinity() : heap.front().first; }
  void consider(double d2, std::size_t id) {
    if (heap.size() < k) {
      heap.emplace_back(d2, id);
      std::push_heap(heap.begin(), heap.end());
    } else if (Item(d2, id) < heap.front()) {
      std::pop_heap(heap.begin(), heap.end());
      heap.back() = Item(d2, id);
      std::push_heap(heap.begin(), heap.end());
    }
  }
};

}  // namespace

void NeighbourIndex::nearest(std::span<const double> q, std::size_t k, std::vector<Item>& out) const {
  out.clear();
  k = std::min(k, n_);
  if (!k) return;
  out.reserve(k);
  KnnSearch s{q.data(), k, out, {}};
  // Depth-first, nearer child first, with the incremental lower bound of Arya and Mount.
  auto visit = [&](auto&& self, int node, double rd) -> void {
    const Node& nd = nodes_[node];
    if (nd.dim < 0) {
      for (std::size_t t = nd.begin; t < nd.end; ++t) {
        const double d2 = distance2(&coords_[t * d_], s.q);
        if (d2 <= s.threshold()) s.consider(d2, ids_[t]);
      }
      return;
    }
    const double diff = s.q[nd.dim] - nd.split;
    const int near = diff < 0 ? nd.left : nd.right, far = diff < 0 ? nd.right : nd.left;
    self(self, near, rd);
    const double old = s.off[nd.dim];
    const double nrd = rd - old * old + diff * diff;
    // Written as !(a > b): near 1e308 the incremental bound can be inf - inf = NaN, and a NaN must
    // visit the far side rather than silently prune it.
    if (!(nrd > s.threshold() * kPruneSlack)) {
      s.off[nd.dim] = diff;
      self(self, far, nrd);
      s.off[nd.dim] = old;
    }
  };
  if (!nodes_.empty()) visit(visit, 0, 0.0);
  for (std::size_t b = 0; b * d_ < buffer_.size(); ++b) s.consider(distance2(&buffer_[b * d_], s.q), buffer_first_ + b);
  std::sort_heap(out.begin(), out.end());
}

std::vector<std::size_t> NeighbourIndex::spatial_order(std::span<const std::size_t> indices) const {
  std::vector<std::size_t> rank(n_, n_);
  for (std::size_t t = 0; t < ids_.size(); ++t) rank[ids_[t]] = t;
  for (std::size_t b = 0; b * d_ < buffer_.size(); ++b) rank[buffer_first_ + b] = ids_.size() + b;
  std::vector<std::size_t> out(indices.begin(), indices.end());
  std::sort(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
    const std::size_t ra = a < n_ ? rank[a] : n_, rb = b < n_ ? rank[b] : n_;
    return ra < rb || (ra == rb && a < b);
  });
  return out;
}

void NeighbourIndex::ball(std::span<const double> q, double r2, std::vector<Item>& out) const {
  out.clear();
  double off[kMaxDimension] = {};
  auto visit = [&](auto&& self, int node, double rd) -> void {
    const Node& nd = nodes_[node];
    if (nd.dim < 0) {
      for (std::size_t t = nd.begin; t < nd.end; ++t) {
        const double d2 = distance2(&coords_[t * d_], q.data());
        if (d2 <= r2) out.emplace_back(d2, ids_[t]);
      }
      return;
    }
    const double diff = q[nd.dim] - nd.split;
    const int near = diff < 0 ? nd.left : nd.right, far = diff < 0 ? nd.right : nd.left;
    self(self, near, rd);
    const double old = off[nd.dim];
    const double nrd = rd - old * old + diff * diff;
    if (!(nrd > r2 * kPruneSlack)) {  // NaN visits (see nearest())
      off[nd.dim] = diff;
      self(self, far, nrd);
      off[nd.dim] = old;
    }
  };
  if (!nodes_.empty()) visit(visit, 0, 0.0);
  for (std::size_t b = 0; b * d_ < buffer_.size(); ++b) {
    const double d2 = distance2(&buffer_[b * d_], q.data());
    if (d2 <= r2) out.emplace_back(d2, buffer_first_ + b);
  }
}

std::vector<std::size_t> NeighbourIndex::ball(std::span<const double> q, double r2) const {
  std::vector<Item> found;
  ball(q, r2, found);
  std::vector<std::size_t> out(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) out[i] = found[i].second;
  std::sort(out.begin(), out.end());
  return out;
}

void NeighbourIndex::for_each_in_ball(std::span<const double> q, double r2,
                                      const std::function<void(std::size_t, double)>& visit) const {
  std::vector<Item> found;
  ball(q, r2, found);
  for (const auto& [d2, i] : found) visit(i, d2);
}

double NeighbourIndex::nearest_distance2(std::span<const double> q, std::size_t* index) const {
  std::vector<Item> nn;
  nearest(q, 1, nn);
  if (nn.empty()) return std::numeric_limits<double>::infinity();
  if (index) *index = nn[0].second;
  return nn[0].first;
}

}  // namespace delcert::spatial
