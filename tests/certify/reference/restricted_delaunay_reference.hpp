// An independent reference for the restricted Delaunay complex Del_RM(P) of a surface in R^3
// (codimension 1), used only by the tests (outside the trust boundary: it uses CGAL's 3D Delaunay
// triangulation, which certify/ never may). It shares no code with certify/: only exact/ (the
// Polynomial type) and io/ (points, specs), CGAL and GMP.
//
// Definition. M = {F = 0} for one polynomial F in x1, x2, x3 with rational coefficients. The
// restricted Delaunay complex Del_RM(P) is the set of simplices of the Delaunay complex of P whose
// dual Voronoi face meets M. For triangles: a triangle abc is in Del_RM iff its dual Voronoi edge
// V(abc) = {x : |x-a| = |x-b| = |x-c| <= |x-q| for all q in P} meets M. P is any finite point set:
// it need not lie on M.
//
// Computation. CGAL::Delaunay_triangulation_3 with exact predicates gives the Delaunay
// triangulation (P must be in general position in R^3, dimension 3; the points are the doubles of
// P read as exact rationals). Every construction is done here in exact rationals (mpq_class), never
// in a floating-point kernel:
//   * a finite facet abc between two finite tetrahedra: V(abc) is the segment from the
//     circumcentre A of one tetrahedron to the circumcentre B of the other (exact Cramer solve),
//     parametrised as A + t (B - A), t in [0, 1];
//   * a convex hull facet abc (one adjacent cell infinite, the finite one being abce): V(abc) is the
//     ray from the circumcentre A of abce in the direction n = (b - a) x (c - a) oriented away from
//     e (outward), A + t n, t in [0, inf). Along it |x-e|^2 - |x-a|^2 increases from 0, and the open
//     half-space beyond abc holds no point of P, so every point of the ray is closer to a, b, c.
// f(t) = F(A + t D) is then a univariate polynomial with rational coefficients (exact substitution),
// and V(abc) meets M iff f has a real root in [0, 1] (resp. [0, inf)). The distinct real roots are
// counted exactly with a Sturm sequence of the square-free part of f over Q (roots at the endpoints
// are tested by exact evaluation and divided out first; at infinity the sign of a polynomial is the
// sign of its leading coefficient). Counting roots of any multiplicity is exactly "the edge meets
// M", for any M = {F = 0}, closed or not.
//
// Before the exact path, an interval filter may prove that F has no zero on a finite Voronoi edge
// (interval circumcentres, F enclosed on the box hull of the segment): that conclusion is exact too;
// every other edge is decided exactly.
//
// Degenerate cases are reported in a separate list, never decided (each with its reason):
//   * edge_in_manifold: f is identically zero: the whole Voronoi edge lies in M (this includes a
//     zero-length edge, two cospherical tetrahedra with a common circumcentre, at a point of M);
//   * voronoi_vertex_on_manifold: f(0) = 0, or f(1) = 0 on a segment: a Voronoi vertex (a point
//     equidistant from 4 or more points of P, and closer to no other) lies on M: m + 2 = 4 points
//     are equidistant from a point of M, and every triangle of that tetrahedron touches M there;
//   * tangency: f has a root of multiplicity >= 2 in the closed interval (a repeated root of f is a
//     root of gcd(f, f'), counted by its own Sturm sequence): the line of the Voronoi edge is tangent
//     to M there (or meets a singular point of M), a contact that a perturbation can remove;
//   * cocircular: the Voronoi edge meets M, and a fourth point d of P lies on the circumcircle of abc
//     (exact orientation and coplanar in-circle predicates). Then every sphere through a, b, c
//     passes through d, the Delaunay complex has a polygon face (abcd...) there, its triangulation by
//     CGAL is one arbitrary choice among several (the Delaunay triangulation is not unique), and the
//     same Voronoi edge is dual to abc, to the other triangles of the polygon and to the polygon
//     itself: "the" restricted Delaunay triangulation is not defined. Such a d is always a vertex of
//     a cell around one of abc's edges (the polygon's triangles adjacent to abc are facets of the
//     triangulation), so only those vertices are tested. Example: the 8 vertices of a cube on the
//     sphere of radius sqrt(3): every square face is cocircular and its dual ray meets the sphere.
// Cospherical groups of 5 or more points whose common circumcentre is not on M change only
// triangles whose Voronoi edge has zero length (and does not meet M): they are counted
// (cospherical_facets) but need no flag.
//
// Witnesses: each triangle comes with its Voronoi edge (start, direction, segment or ray), the
// restricted polynomial f, the number of distinct real roots in the parameter interval and an
// isolating interval [t0, t1] of one root (exactly one distinct root of f in it; t0 == t1 when the
// root is rational and was hit exactly), so a later test can locate the point of V(abc) on M.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "exact/polynomial.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::reference {

// A univariate polynomial with rational coefficients: c[0] + c[1] t + ... + c[d] t^d, no trailing
// zeros (the zero polynomial has no coefficient).
class UPoly {
 public:
  UPoly() = default;
  UPoly(int c);  // NOLINT: a constant (exact::Polynomial::evaluate_with needs T(0))
  explicit UPoly(mpq_class c);
  explicit UPoly(std::vector<mpq_class> coefficients);
  static UPoly linear(const mpq_class& c0, const mpq_class& c1);  // c0 + c1 t
  // The product of (t - r) over the given roots (repeated as listed).
  static UPoly from_roots(const std::vector<mpq_class>& roots);

  const std::vector<mpq_class>& coefficients() const { return c_; }
  int degree() const { return static_cast<int>(c_.size()) - 1; }  // -1 for zero
  bool is_zero() const { return c_.empty(); }
  const mpq_class& leading() const { return c_.back(); }

  mpq_class operator()(const mpq_class& t) const;  // Horner, exact
  int sign_at(const mpq_class& t) const;
  int sign_at_infinity() const;  // sign of the leading coefficient (0 for zero)
  UPoly derivative() const;
  UPoly monic() const;  // divided by its leading coefficient (zero stays zero)
  // A positive rational multiple with coprime integer coefficients (same roots, same signs).
  UPoly primitive() const;

  friend UPoly operator+(const UPoly& a, const UPoly& b);
  friend UPoly operator-(const UPoly& a, const UPoly& b);
  friend UPoly operator*(const UPoly& a, const UPoly& b);
  friend bool operator==(const UPoly& a, const UPoly& b) { return a.c_ == b.c_; }
  // a = q b + r with deg r < deg b; b non-zero.
  friend std::pair<UPoly, UPoly> divmod(const UPoly& a, const UPoly& b);
  friend UPoly gcd(UPoly a, UPoly b);  // monic (zero when both are zero)

  std::string to_string() const;

 private:
  void trim();
  std::vector<mpq_class> c_;
};

// Roots of a non-zero f on the closed interval [lo, hi], or [lo, +inf) when hi is empty.
struct RootAnalysis {
  bool identically_zero = false;  // f == 0: every point is a root; nothing else is set
  int distinct_roots = 0;         // distinct real roots in the closed interval
  bool root_at_lo = false, root_at_hi = false;
  bool repeated_root = false;  // some root in the closed interval has multiplicity >= 2
  // When distinct_roots > 0: an interval [t0, t1] inside the closed interval holding exactly one
  // distinct root of f (t0 == t1: that root exactly).
  std::optional<std::pair<mpq_class, mpq_class>> isolating;
};
RootAnalysis analyse_roots(const UPoly& f, const mpq_class& lo, const std::optional<mpq_class>& hi);
// Distinct real roots of f != 0 in [lo, hi] (hi empty: [lo, inf)), by Sturm sequences.
int count_distinct_roots(const UPoly& f, const mpq_class& lo, const std::optional<mpq_class>& hi);

// F(start + t * direction) exactly.
UPoly restrict_to_line(const exact::Polynomial& F, const std::array<mpq_class, 3>& start,
                       const std::array<mpq_class, 3>& direction);

using Triangle = std::array<std::size_t, 3>;  // indices into P, increasing

enum class Degeneracy { none, edge_in_manifold, voronoi_vertex_on_manifold, tangency, cocircular };
const char* to_string(Degeneracy d);

struct VoronoiEdge {
  std::array<mpq_class, 3> start;      // a circumcentre
  std::array<mpq_class, 3> direction;  // to the other circumcentre (segment), or outward (ray)
  bool ray = false;                    // t in [0, inf) rather than [0, 1]
  UPoly restricted;                    // f(t) = F(start + t * direction)
  RootAnalysis roots;                  // of f on the edge's parameter interval
  std::array<mpq_class, 3> point(const mpq_class& t) const;
};

struct ReferenceTriangle {
  Triangle vertices;
  VoronoiEdge edge;
  Degeneracy degeneracy = Degeneracy::none;
};

struct RestrictedDelaunayReference {
  std::vector<ReferenceTriangle> restricted;  // decided members of Del_RM, sorted by vertices
  std::vector<ReferenceTriangle> degenerate;  // undecided (see the header comment), sorted
  std::size_t delaunay_triangles = 0;         // finite facets of the 3D Delaunay triangulation
  std::size_t hull_triangles = 0;             // of which convex hull facets
  std::size_t finite_cells = 0;
  std::size_t cospherical_facets = 0;  // facets whose two cells are cospherical (or cocircular on the hull)
  std::size_t exact_segments = 0;      // finite Voronoi edges the interval filter left to the exact path

  bool decided() const { return degenerate.empty(); }
  std::vector<Triangle> triangles() const;             // of `restricted`
  std::vector<Triangle> degenerate_triangles() const;  // of `degenerate`
};

// P must have dimension 3, distinct points, not all coplanar; F must have 3 variables. Throws
// std::invalid_argument otherwise.
RestrictedDelaunayReference restricted_delaunay_reference(const io::PointSet& P, const exact::Polynomial& F);

// The single equation of a spec of a surface in R^3 (m = 2, N = 3); throws std::invalid_argument
// for any other spec.
const exact::Polynomial& surface_equation(const io::ManifoldSpec& spec);

}  // namespace delcert::reference
