#include "core/refine/point_index.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "core/spatial/distance.hpp"

namespace delcert::refine {

PointIndex::PointIndex(const io::PointSet& points) : d_(points.dimension) {
  if (points.size() == 0) return;
  auto b = std::make_unique<Block>();
  b->first = 0;
  b->coords = points.coordinates;
  b->tree = KdTree(b->coords.data(), points.size(), d_);
  n_ = points.size();
  buffer_first_ = n_;
  blocks_.push_back(std::move(b));
}

void PointIndex::push_back(std::span<const double> p) {
  if (static_cast<int>(p.size()) != d_) throw std::invalid_argument("PointIndex::push_back: wrong dimension");
  buffer_.insert(buffer_.end(), p.begin(), p.end());
  ++n_;
  if (buffer_.size() / d_ >= kBuffer) flush_buffer();
}

void PointIndex::flush_buffer() {
  std::size_t count = buffer_.size() / d_;
  if (!count) return;
  // Merge trailing blocks that are not larger than what is being added (keeps sizes geometric).
  std::vector<double> coords;
  std::size_t first = buffer_first_;
  std::size_t total = count;
  std::size_t merge_from = blocks_.size();
  while (merge_from > 0 && blocks_[merge_from - 1]->size() <= total) {
    --merge_from;
    total += blocks_[merge_from]->size();
  }
  coords.reserve(total * d_);
  for (std::size_t b = merge_from; b < blocks_.size(); ++b) {
    coords.insert(coords.end(), blocks_[b]->coords.begin(), blocks_[b]->coords.end());
    first = std::min(first, blocks_[b]->first);
  }
  coords.insert(coords.end(), buffer_.begin(), buffer_.end());
  blocks_.resize(merge_from);
  auto blk = std::make_unique<Block>();
  blk->first = first;
  blk->coords = std::move(coords);
  blk->tree = KdTree(blk->coords.data(), total, d_);
  blocks_.push_back(std::move(blk));
  buffer_.clear();
  buffer_first_ = n_;
}

void PointIndex::for_each_in_ball(std::span<const double> q, double r2,
                                  const std::function<void(std::size_t, double)>& visit) const {
  for (const auto& b : blocks_) {
    const std::size_t first = b->first;
    b->tree.for_each_in_ball(q, r2, [&](std::size_t i, double d2) { visit(first + i, d2); });
  }
  const std::size_t count = buffer_.size() / std::max(1, d_);
  for (std::size_t i = 0; i < count; ++i) {
    const double s = squared_distance({buffer_.data() + i * d_, static_cast<std::size_t>(d_)}, q);
    if (s <= r2) visit(buffer_first_ + i, s);
  }
}

std::vector<std::size_t> PointIndex::ball(std::span<const double> q, double r2) const {
  std::vector<std::size_t> out;
  for_each_in_ball(q, r2, [&](std::size_t i, double) { out.push_back(i); });
  std::sort(out.begin(), out.end());
  return out;
}

double PointIndex::nearest_distance2(std::span<const double> q, std::size_t* index) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_i = 0;
  auto consider = [&](std::size_t i, double d2) {
    if (d2 < best || (d2 == best && i < best_i)) best = d2, best_i = i;
  };
  for (const auto& b : blocks_) {
    auto nn = b->tree.nearest(q, 1);
    if (nn.empty()) continue;
    consider(b->first + nn[0], squared_distance({b->coords.data() + nn[0] * d_, static_cast<std::size_t>(d_)}, q));
  }
  const std::size_t count = buffer_.size() / std::max(1, d_);
  for (std::size_t i = 0; i < count; ++i) {
    const double s = squared_distance({buffer_.data() + i * d_, static_cast<std::size_t>(d_)}, q);
    consider(buffer_first_ + i, s);
  }
  if (index) *index = best_i;
  return best;
}

}  // namespace delcert::refine
