// Internal to core/tangential: the local weighted problem of one star, shared by the power-cell
// path (stars.cpp) and the regular-triangulation path (regular_star_cgal.cpp).
//
// Local coordinates. For the star of p with tangent basis T (orthonormal, N by m) a neighbour q
// becomes u = s T^T (q - p) and w = -s^2 ||(q - p) - T T^T (q - p)||^2, both rounded to doubles
// once; s is a power of two (near 1 / the nearest-neighbour distance) so that all later
// quantities are O(1), and because scaling by a power of two is exact, s changes no rounding
// and no decision. These doubles (u, w) *are* the input of the local problem: every predicate
// below is a sign of a polynomial in them, decided exactly (certified filter or CGAL's exact
// predicates), so both paths compute the same star.
#pragma once

#include <cstddef>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/points.hpp"

namespace delcert::tangential::detail {

inline constexpr int kMaxM = 4;

struct LocalPoint {
  double u[kMaxM] = {};  // scaled local coordinates (first m used)
  double w = 0;          // scaled weight, <= 0
  double a = 0;          // fl(||u||^2 - w); the exact value bounds p's power cell: 2 u.x <= ||u||^2 - w
  double d2 = 0;         // scaled squared ambient distance to p (the order of the neighbours)
  int global = -1;       // index in the point set
};

// Computes (u, w, a, d2) of q for the star of p at scale s (see above).
void project_neighbour(const double* p, const double* q, const double* basis, int N, int m, double scale,
                       LocalPoint& out);

// Power of two close to 1 / sqrt(d2), for d2 > 0.
double scale_for(double d2);

// The neighbours of one point p, in increasing (distance, index) order, fetched from the index
// in doubling batches on demand.
class Neighbourhood {
 public:
  Neighbourhood(const io::PointSet& points, const TangentPlanes& planes, const spatial::NeighbourIndex& index,
                std::size_t initial_k);

  // Starts over for point p (fetches the first batch).
  void reset(std::size_t p);
  // Starts over for a point x that is not in the set (a tentative star, tentative_star in
  // star.hpp): its index is points.size(), its tangent basis `basis` (N*m, column-major); both
  // spans must outlive the next reset.
  void reset_external(std::span<const double> x, std::span<const double> basis);
  // Makes at least `count` neighbours available; false when there are fewer other points.
  bool ensure(std::size_t count);
  std::size_t available() const { return local_.size(); }
  const LocalPoint& operator[](std::size_t i) const { return local_[i]; }

  std::size_t centre() const { return p_; }
  const double* centre_point() const { return centre_; }  // p's coordinates (N)
  const double* centre_basis() const { return basis_; }   // its tangent basis (N*m, column-major)
  int m() const { return m_; }
  int N() const { return N_; }
  double scale() const { return scale_; }
  const io::PointSet& points() const { return points_; }
  const TangentPlanes& planes() const { return planes_; }

 private:
  void restart(std::size_t p, bool external, const double* centre, const double* basis);
  void fetch(std::size_t k);

  const io::PointSet& points_;
  const TangentPlanes& planes_;
  const spatial::NeighbourIndex& index_;
  int N_, m_;
  std::size_t initial_k_, p_ = 0, k_ = 0;
  bool exhausted_ = false, external_ = false;
  const double* centre_ = nullptr;
  const double* basis_ = nullptr;
  double scale_ = 1;
  std::vector<LocalPoint> local_;
  std::vector<std::pair<double, std::size_t>> found_;
};

// Solves 2 U v = a for the m rows (u_i, a_i) (the power centre in scaled local coordinates), by
// Gaussian elimination with partial pivoting in long double (exact rationals if that breaks
// down). Rows must be given in a canonical order (increasing global index) so that every caller
// gets the same bits. False only if the system is exactly singular.
bool solve_centre(int m, const LocalPoint* const* rows, double* v);

// A star in local form: for each cell the m local indices of its vertices other than p.
struct LocalStar {
  std::vector<int> cells;  // #cells by m, local neighbour indices
  bool closed = true;
  std::size_t considered = 0;
};

// The regular-triangulation path (CGAL, exact predicates): consumes neighbours in order until
// the star is complete. Defined in regular_star_cgal.cpp, the only translation unit with CGAL.
void regular_triangulation_star(Neighbourhood& neighbourhood, LocalStar& out);

// Relative margin on 4 max R^2 in the completeness test "d(p, q)^2 > 4 max R^2 (1 + margin)".
// Beyond it, a_q = ||u_q||^2 - w_q (the exact value for the rounded input) exceeds 4 R^2, so
// q's halfspace contains the ball ||x|| <= R strictly (2 u.x <= 2 sqrt(a) R < a). a_q differs
// from d(p, q)^2 by the non-orthonormality of T (accepted up to 1e-9 per entry of T^T T - I,
// so at most 4e-9 relative for m <= 4) and by rounding (1e-15).
inline constexpr double kCompletenessMargin = 1e-6;

}  // namespace delcert::tangential::detail
