// The tangential Delaunay complex Del_TM(P): one star per point, their union, and consistency
// (docs/design.md §3.2, §6.4, paper §3.1.2). Built once, then updated star by star as the refiner inserts points.
//
//   TangentialComplex tc(points, planes, options);          // every star (options.threads workers)
//   points.push_back(x); extend_tangent_planes(manifold, points, planes);
//   auto changed = tc.insert(points, planes);               // recomputes exactly the stars that can change
//   const Star& s = tc.star(p);                             // cells, c_p(s), R_p(s)^2
//   Assembly a = tc.assemble();                             // union, inconsistent simplices
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "core/tangential/star.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"

namespace delcert::tangential {

struct Assembly {
  io::Complex complex;                         // the union of the stars: maximal simplices, each sorted, list sorted
  std::vector<std::vector<int>> inconsistent;  // simplices missing from the star of one of their vertices, sorted
  std::size_t star_cells = 0;                  // cells over all stars, counted with repetition
  std::size_t isolated_vertices = 0;           // points in no cell (listed as 0-simplices in `complex`)
};

// The union of `stars` over points 0 .. num_points-1 (stars.size() >= num_points). A simplex s
// is consistent when s is in star(q) for every vertex q of s. Parallel; the result does not
// depend on `threads`. `order`, if given, is a permutation of 0 .. num_points-1 in which to visit
// the stars (a spatial order is faster: spatial::NeighbourIndex::spatial_order); it changes no result.
Assembly assemble(const std::vector<Star>& stars, std::size_t num_points, int threads = 1,
                  std::span<const std::size_t> order = {});

class TangentialComplex {
 public:
  TangentialComplex() = default;
  // Computes every star. `points` is append-only from now on: the complex keeps a copy of it in
  // its neighbour index, and later calls must pass the same set, possibly grown.
  TangentialComplex(const io::PointSet& points, const TangentPlanes& planes, const StarOptions& options = {},
                    StarStats* stats = nullptr);

  int intrinsic_dimension() const { return m_; }
  int ambient_dimension() const { return N_; }
  std::size_t size() const { return stars_.size(); }
  const Star& star(std::size_t p) const { return stars_[p]; }
  const std::vector<Star>& stars() const { return stars_; }
  const spatial::NeighbourIndex& index() const { return index_; }

  // The incremental update of the refiner: after the caller appended points (and their planes,
  // see extend_tangent_planes) to the set, recomputes exactly the stars that can change
  // (stars_to_update for the appended points) and returns their indices, sorted.
  std::vector<std::size_t> insert(const io::PointSet& points, const TangentPlanes& planes,
                                  const StarOptions& options = {}, StarStats* stats = nullptr);

  // Recomputes star(p) for p in `which` from the current `points` (first adding any appended
  // points to the index). New points' stars must be among `which`.
  StarStats recompute(const io::PointSet& points, const TangentPlanes& planes, std::span<const std::size_t> which,
                      const StarOptions& options = {});

  // The stars that can change when `inserted` (indices into `points`, which holds old and new
  // points; the index must already hold them, e.g. after recompute or insert) joined the set,
  // sorted: the inserted points, every other point with a cell whose Delaunay ball
  // B(c_p(s), R_p(s)) contains or touches an inserted point (with a relative margin of 1e-6 on
  // R^2 for the rounding of the centres), every star that is not closed, and every point
  // without a star yet. A star not listed keeps all its cells: their balls stay empty, so they
  // still form the complete fan around p.
  std::vector<std::size_t> stars_to_update(const io::PointSet& points, std::span<const std::size_t> inserted) const;

  Assembly assemble(int threads = 1) const;

 private:
  void sync_index(const io::PointSet& points);

  int m_ = 0, N_ = 0;
  spatial::NeighbourIndex index_;
  std::vector<Star> stars_;
};

}  // namespace delcert::tangential
