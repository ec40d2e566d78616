// Tangential stars (docs/design.md §3.2, paper §3.1.2).
//
// For p in P, every other point q is projected onto T_p, q' = p + T T^T (q - p), with weight
// w(q) = -||q - q'||^2, so that the power of x in T_p to q' is ||x - q||^2. star(p) is the set of
// m-cells incident to p of the regular triangulation of these weighted points in T_p ~ R^m.
// In local coordinates u_q = T^T (q - p) (p at the origin), x is in p's power cell iff
// 2 u_q . x <= ||u_q||^2 - w(q) =: a_q for every q: the power cell of p is a convex polytope, its
// vertices are the power centres c_p(s) of the star cells s and its facets are the neighbours
// of p in the star.
//
// How it is computed: the power cell is clipped by the neighbours' halfspaces in increasing
// distance order until the next neighbour is farther than 2 max_s R_p(s) (then it cannot enter
// any Delaunay ball). Every sign that decides the combinatorics is a determinant of the rounded
// local input (u_q, w_q as doubles) evaluated with a certified error bound, so the star is the
// exact regular-triangulation star of that input. When a sign cannot be certified (a point on or
// within rounding of a Delaunay sphere, a nearly degenerate cell), that star is recomputed
// with CGAL's dD regular triangulation and exact predicates, which also resolves exact
// degeneracies (cospherical points) by CGAL's symbolic perturbation.
//
// "Exact" means exact for the rounded local input. The certifier's T_p is ker J_F(p) in
// rationals, which differs from the double basis by rounding, so a configuration within ~1e-15
// (relative) of a tie may be decided differently there; such a simplex is not protected anyway
// and the certifier reports it (docs/design.md §2).
//
// Every star depends only on (points, planes, p): the output is the same for every thread
// count, batch size and processing order, bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/points.hpp"

namespace delcert::tangential {

enum class StarMethod : std::uint8_t {
  power_cell,            // the certified power-cell clipping (fast path)
  regular_triangulation  // CGAL's dD regular triangulation (fallback or forced)
};

struct Star {
  int m = 0;                    // intrinsic dimension; a cell has m + 1 vertices
  int N = 0;                    // ambient dimension
  std::vector<int> cells;       // #cells by (m+1): global vertex indices, each row sorted, rows sorted
  std::vector<double> centres;  // #cells by N: the power centre c_p(s) in T_p, ambient coordinates
  std::vector<double> radii2;   // #cells: R_p(s)^2 = ||c_p(s) - p||^2
  double max_radius2 = 0;       // max over cells of radii2 (0 when there are no cells)
  bool closed = true;           // false: p's power cell is unbounded even with all points (too few points)
  StarMethod method = StarMethod::power_cell;
  std::uint32_t neighbours = 0;  // how many nearest neighbours were considered

  std::size_t size() const { return radii2.size(); }
  std::span<const int> cell(std::size_t c) const { return {cells.data() + c * (m + 1), static_cast<std::size_t>(m + 1)}; }
  std::span<const double> centre(std::size_t c) const { return {centres.data() + c * N, static_cast<std::size_t>(N)}; }
  // Index of the cell with these sorted vertices, or -1 (binary search).
  long find(std::span<const int> sorted_vertices) const;
  bool contains(std::span<const int> sorted_vertices) const { return find(sorted_vertices) >= 0; }
};

enum class StarPath : std::uint8_t {
  automatic,             // power-cell clipping, CGAL regular triangulation where a sign is uncertain
  regular_triangulation  // CGAL for every star (the reference; several times slower)
};

struct StarOptions {
  int threads = 1;  // <= 0: one per hardware thread; the output is the same for every value
  StarPath path = StarPath::automatic;
  std::size_t initial_neighbours = 0;  // first k-nearest query size (0: chosen from m); doubled as needed
  // Called with (stars done, stars to do) from the worker threads, one call at a time.
  std::function<void(std::size_t, std::size_t)> progress;
};

struct StarStats {
  std::size_t stars = 0;              // stars computed
  std::size_t cells = 0;              // sum of their sizes
  std::size_t fallbacks = 0;          // stars that needed the regular triangulation under StarPath::automatic
  std::size_t open = 0;               // stars whose power cell stayed unbounded (not closed)
  std::size_t neighbours_total = 0;   // sum over stars of the neighbours considered
  std::size_t neighbours_max = 0;
  double max_radius2 = 0;             // max over computed cells of R_p(s)^2
};

// Computes star(p) for every p in `which` from all of `points` and stores it in stars[p];
// `stars` is first resized to points.size() (stars not listed keep their value). `index` must
// hold exactly `points` (spatial::NeighbourIndex(points), or kept in step with spatial::NeighbourIndex::extend);
// `planes` must cover every point. m = planes.intrinsic_dimension() must be 2, 3 or 4.
// Throws std::invalid_argument on mismatched sizes, an unsupported m, or two identical points.
StarStats compute_stars(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                        std::span<const std::size_t> which, std::vector<Star>& stars, const StarOptions& options = {});

// The star a point x would have if it were appended to `points` (index points.size()), computed
// as compute_stars computes every star (same certified signs, same fallback, same bits as
// compute_stars after the append); nothing is inserted. The refiner's look-ahead. `basis` is x's
// tangent basis (N*m doubles, column-major, orthonormal, as TangentPlanes::basis); `planes` gives
// m only and need not cover the points. Throws std::invalid_argument on mismatched sizes, an
// unsupported m, or when x is one of the points.
Star tentative_star(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                    std::span<const double> x, std::span<const double> basis);

// The power centre of the simplex `cell` (sorted global indices, containing p) in T_p, in
// ambient coordinates, as computed for star(p) (bit-identical; docs/design.md §3.2). Returns false when
// the projected simplex is degenerate (no unique centre).
bool power_centre(const io::PointSet& points, const TangentPlanes& planes, std::size_t p, std::span<const int> cell,
                  std::span<double> centre, double* radius2);

}  // namespace delcert::tangential
