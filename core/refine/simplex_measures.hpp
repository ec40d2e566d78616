// Simplex measures in double precision (docs/design.md §3.1, paper §2.2).
//
// For a j-simplex s = [v0..vj]: Δ(s) longest edge, L(s) shortest edge, the altitude D(vi, s)
// (distance from vi to the affine hull of the opposite face), thickness
// Υ(s) = min_i D(vi, s) / (j Δ(s)) for j >= 1 and Υ = 1 for a vertex.
// A simplex is Γ0-good when every j-face t of it has Υ(t) >= Γ0^j, Γ0-bad otherwise; a Γ0-flake
// is a Γ0-bad simplex (dimension >= 2) whose proper faces are all Γ0-good.
//
// Everything is computed from one Gram matrix H (#vertices by #vertices) of the edge vectors
// v_u - v0, so every face's Gram determinant, edge length and altitude costs no further access
// to the coordinates. Altitudes use the Gram-determinant identity
//   D(vi, t)^2 = det G(t) / det G(t \ vi)
// (volume of t = volume of the facet times altitude / j); thickness() evaluates all of them at
// once from one LDL^T factorisation of G(t), as det G(t \ vi) / det G(t) = (G(t)^-1)_ii
// (Cramer). Degenerate (affinely dependent) simplices are fine: a Gram matrix that is not
// positive definite to working precision (a pivot below 1e-15 Δ^2, i.e. Υ below about 1e-7)
// gives thickness 0, never a division by zero.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>

#include "io/points.hpp"

namespace delcert::refine {

// At most 6 vertices: an (m+1)-simplex for m <= 4 (the tangential complex supports m = 2, 3, 4).
inline constexpr int kMaxSimplexVertices = 6;

// A face of a simplex given by the bit mask of its vertices (bit u = vertex u).
using FaceMask = std::uint32_t;

enum class SimplexQuality : std::uint8_t {
  good,   // every face t (including the simplex) has Υ(t) >= Γ0^dim(t)
  flake,  // bad, but every proper face is good (then the dimension is >= 2)
  bad     // bad, and some proper face is bad too
};

const char* to_string(SimplexQuality q);

class SimplexGeometry {
 public:
  using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSimplexVertices, kMaxSimplexVertices>;

  SimplexGeometry() = default;
  // `vertices`: #vertices (1..6) spans of the same length N. Throws std::invalid_argument otherwise.
  explicit SimplexGeometry(std::span<const std::span<const double>> vertices);
  // From the Gram matrix H (#vertices by #vertices, H(u, v) = (v_u - v_0).(v_v - v_0); row and
  // column 0 are zero), e.g. gathered from a precomputed Gram matrix of many points.
  static SimplexGeometry from_gram(const SmallMatrix& H);

  int num_vertices() const { return k_; }
  int dimension() const { return k_ - 1; }
  FaceMask all() const { return (FaceMask{1} << k_) - 1; }

  double squared_distance(int u, int v) const;
  // Gram determinant of the face's edge vectors from its lowest vertex: (j! vol_j)^2 for a
  // j-face; 1 for a vertex; may be slightly negative from rounding for degenerate faces.
  double gram_determinant(FaceMask face) const;
  double longest_edge(FaceMask face) const;   // Δ; 0 for a vertex
  double shortest_edge(FaceMask face) const;  // L; 0 for a vertex
  double longest_edge() const { return longest_edge(all()); }
  double shortest_edge() const { return shortest_edge(all()); }
  // Distance from vertex u (which must be in `face`) to the affine hull of face \ u. Uses the
  // Gram-determinant identity when face \ u is non-degenerate, and a least-squares projection
  // otherwise (the hull of a degenerate face is a lower-dimensional flat).
  double altitude(int u, FaceMask face) const;
  double altitude(int u) const { return altitude(u, all()); }
  // Υ(face); 1 for a vertex, 0 for a degenerate face.
  double thickness(FaceMask face) const;
  double thickness() const { return thickness(all()); }

  // Υ(face) >= gamma0^dim(face) for this face alone (not its sub-faces).
  bool face_thick(FaceMask face, double gamma0) const;
  // Every face of `face` (itself included) thick: the face is Γ0-good.
  bool is_good(double gamma0, FaceMask face) const;
  bool is_good(double gamma0) const { return is_good(gamma0, all()); }
  SimplexQuality quality(double gamma0) const;
  // Smallest ratio Υ(t) / Γ0^dim(t) over the faces t of dimension >= 2 (>= 1 iff Γ0-good for
  // Γ0 <= 1, where edges are always good); +inf when there is no such face.
  double goodness_ratio(double gamma0) const;

  // The vertex u's difference vector Gram matrix (#vertices by #vertices, row/col 0 unused = 0):
  // H(u, v) = (v_u - v_0) . (v_v - v_0).
  const SmallMatrix& gram() const { return H_; }
  // Face Gram matrix relative to the face's lowest vertex a: G(s, t) = (v_s - v_a).(v_t - v_a)
  // for the other vertices s, t of the face, in increasing order.
  SmallMatrix face_gram(FaceMask face, int* origin = nullptr) const;

 private:
  int k_ = 0;
  SmallMatrix H_;
};

// Convenience: the simplex on points.point(i) for i in `indices` (at most 6).
SimplexGeometry make_simplex(const io::PointSet& points, std::span<const int> indices);
// Same, with an extra vertex `extra` first (vertex 0), then the indexed points.
SimplexGeometry make_simplex(std::span<const double> extra, const io::PointSet& points, std::span<const int> indices);

// Population count of a face mask (number of vertices).
inline int face_size(FaceMask f) { return __builtin_popcount(f); }

}  // namespace delcert::refine
