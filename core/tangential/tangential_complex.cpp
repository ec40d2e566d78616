#include "core/tangential/tangential_complex.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/support/parallel.hpp"

namespace delcert::tangential {

using support::parallel_chunks;

namespace {

// Lexicographic order of two rows of w ints.
inline bool row_less(const int* a, const int* b, std::size_t w) {
  for (std::size_t i = 0; i < w; ++i)
    if (a[i] != b[i]) return a[i] < b[i];
  return false;
}

}  // namespace

Assembly assemble(const std::vector<Star>& stars, std::size_t num_points, int threads,
                  std::span<const std::size_t> order) {
  if (stars.size() < num_points) throw std::invalid_argument("assemble: fewer stars than points");
  if (!order.empty() && order.size() != num_points)
    throw std::invalid_argument("assemble: the visiting order must list every point once");
  Assembly out;
  out.complex.num_vertices = num_points;
  int m = -1;
  for (std::size_t p = 0; p < num_points; ++p)
    if (stars[p].size()) {
      if (m >= 0 && stars[p].m != m) throw std::invalid_argument("assemble: stars of different dimensions");
      m = stars[p].m;
    }
  const std::size_t w = m >= 0 ? static_cast<std::size_t>(m + 1) : 1;
  constexpr std::size_t kChunk = 512;
  const std::size_t chunks = (num_points + kChunk - 1) / kChunk;
  struct Part {
    std::vector<int> rows;         // emitted simplices, w ints each
    std::vector<char> consistent;  // per emitted simplex
    std::size_t cells = 0;
  };
  std::vector<Part> parts(chunks);
  parallel_chunks(chunks, threads, 1, [&](int) {
    return [&](std::size_t b, std::size_t e) {
      for (std::size_t ch = b; ch < e; ++ch) {
        Part& part = parts[ch];
        const std::size_t t_end = std::min(num_points, (ch + 1) * kChunk);
        for (std::size_t t = ch * kChunk; t < t_end; ++t) {
          const std::size_t p = order.empty() ? t : order[t];
          const Star& star = stars[p];
          part.cells += star.size();
          for (std::size_t c = 0; c < star.size(); ++c) {
            auto cell = star.cell(c);
            bool owner = true, consistent = true;
            for (int q : cell) {
              if (static_cast<std::size_t>(q) == p) continue;
              const bool in_q = static_cast<std::size_t>(q) < num_points && stars[q].contains(cell);
              if (!in_q) consistent = false;
              else if (static_cast<std::size_t>(q) < p) owner = false;  // the smallest owner emits it
            }
            if (!owner) continue;
            part.rows.insert(part.rows.end(), cell.begin(), cell.end());
            part.consistent.push_back(consistent);
          }
        }
      }
    };
  });
  std::vector<int> rows;
  std::vector<char> consistent;
  std::vector<char> used(num_points, 0);
  for (Part& part : parts) {
    out.star_cells += part.cells;
    rows.insert(rows.end(), part.rows.begin(), part.rows.end());
    consistent.insert(consistent.end(), part.consistent.begin(), part.consistent.end());
    std::vector<int>().swap(part.rows);
  }
  for (int v : rows) used[v] = 1;
  const std::size_t count = consistent.size();
  std::vector<std::size_t> sorted(count);
  std::iota(sorted.begin(), sorted.end(), std::size_t{0});
  std::sort(sorted.begin(), sorted.end(),
            [&](std::size_t a, std::size_t b) { return row_less(&rows[a * w], &rows[b * w], w); });
  // 0-simplices (isolated points) sort before every cell that starts with a larger vertex:
  // merge them in while emitting, so the list is sorted lexicographically as a whole.
  std::vector<int> isolated;
  for (std::size_t p = 0; p < num_points; ++p)
    if (!used[p]) isolated.push_back(static_cast<int>(p));
  out.isolated_vertices = isolated.size();
  out.complex.simplices.reserve(count + isolated.size());
  std::size_t next_isolated = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const int* r = &rows[sorted[k] * w];
    while (next_isolated < isolated.size() && isolated[next_isolated] <= r[0])
      out.complex.simplices.push_back({isolated[next_isolated++]});
    out.complex.simplices.emplace_back(r, r + w);
    if (!consistent[sorted[k]]) out.inconsistent.emplace_back(r, r + w);
  }
  while (next_isolated < isolated.size()) out.complex.simplices.push_back({isolated[next_isolated++]});
  return out;
}

Assembly TangentialComplex::assemble(int threads) const {
  if (index_.size() != stars_.size()) return tangential::assemble(stars_, stars_.size(), threads);
  std::vector<std::size_t> all(stars_.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  return tangential::assemble(stars_, stars_.size(), threads, index_.spatial_order(all));
}

TangentialComplex::TangentialComplex(const io::PointSet& points, const TangentPlanes& planes,
                                     const StarOptions& options, StarStats* stats)
    : m_(planes.intrinsic_dimension()), N_(points.dimension), index_(points) {
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  StarStats s = compute_stars(points, planes, index_, all, stars_, options);
  if (stats) *stats = s;
}

void TangentialComplex::sync_index(const io::PointSet& points) {
  if (index_.size() == 0 && index_.dimension() != points.dimension) index_ = spatial::NeighbourIndex(io::PointSet{points.dimension, {}});
  if (points.size() < index_.size() || points.dimension != index_.dimension())
    throw std::invalid_argument("the point set shrank or changed dimension; a TangentialComplex only supports appending");
  index_.extend(points);
}

StarStats TangentialComplex::recompute(const io::PointSet& points, const TangentPlanes& planes,
                                       std::span<const std::size_t> which, const StarOptions& options) {
  if (m_ == 0) m_ = planes.intrinsic_dimension(), N_ = points.dimension;
  if (planes.intrinsic_dimension() != m_ || points.dimension != N_)
    throw std::invalid_argument("recompute: the dimensions differ from the complex's");
  sync_index(points);
  return compute_stars(points, planes, index_, which, stars_, options);
}

std::vector<std::size_t> TangentialComplex::insert(const io::PointSet& points, const TangentPlanes& planes,
                                                   const StarOptions& options, StarStats* stats) {
  const std::size_t first = index_.size();
  if (m_ == 0) m_ = planes.intrinsic_dimension(), N_ = points.dimension;
  sync_index(points);
  std::vector<std::size_t> inserted(points.size() - first);
  std::iota(inserted.begin(), inserted.end(), first);
  std::vector<std::size_t> todo = stars_to_update(points, inserted);
  StarStats s = recompute(points, planes, todo, options);
  if (stats) *stats = s;
  return todo;
}

std::vector<std::size_t> TangentialComplex::stars_to_update(const io::PointSet& points,
                                                            std::span<const std::size_t> inserted) const {
  if (index_.size() != points.size())
    throw std::invalid_argument("stars_to_update: the neighbour index does not hold the current points yet");
  std::vector<char> mark(points.size(), 0);
  for (std::size_t x : inserted) {
    if (x >= points.size()) throw std::invalid_argument("stars_to_update: inserted index out of range");
    mark[x] = 1;
  }
  // A star of another point with every cell ball far from the new points keeps its cells.
  double reach2 = 0;  // (2 max R)^2 over the other closed stars
  for (std::size_t p = 0; p < stars_.size() && p < points.size(); ++p) {
    if (mark[p]) continue;
    if (!stars_[p].closed) mark[p] = 1;
    else reach2 = std::max(reach2, 4 * stars_[p].max_radius2);
  }
  for (std::size_t p = stars_.size(); p < points.size(); ++p) mark[p] = 1;  // never computed
  reach2 *= 1 + 1e-6;
  std::vector<std::pair<double, std::size_t>> near;
  for (std::size_t x : inserted) {
    auto px = points.point(x);
    index_.ball(px, reach2, near);
    for (const auto& [d2, p] : near) {
      if (mark[p]) continue;
      const Star& star = stars_[p];
      if (d2 > 4 * star.max_radius2 * (1 + 1e-6)) continue;
      for (std::size_t c = 0; c < star.size(); ++c) {
        auto centre = star.centre(c);
        double e2 = 0;
        for (int k = 0; k < points.dimension; ++k) e2 += (px[k] - centre[k]) * (px[k] - centre[k]);
        if (e2 <= star.radii2[c] * (1 + 1e-6)) {
          mark[p] = 1;
          break;
        }
      }
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < points.size(); ++p)
    if (mark[p]) out.push_back(p);
  return out;
}

}  // namespace delcert::tangential
