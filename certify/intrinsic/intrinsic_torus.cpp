// Del_M on a flat torus: M the product of circles of radii r_1..r_m (rational, > 0) in the
// coordinate planes (x1, x2), (x3, x4), ..., N = 2m (certify/intrinsic.hpp; docs/design.md §3.9).
//
// NOTATION. A point p (near M, see the convention in intrinsic.hpp) has the angles
// phi_i(p) = atan2(x_{2i}(p), x_{2i-1}(p)), undefined when (x_{2i-1}, x_{2i}) = (0, 0): such a point
// leaves Del_M not computed. pi(p) is the point of M with these angles; a(p) = (r_i phi_i(p))_i is
// its position in the flat torus T = R^m / L, L = 2 pi r_1 Z x ... x 2 pi r_m Z, and the geodesic
// distance of M is the flat metric of T: d_M(x, y) = d_T(a(x), a(y)) = min over l in L of
// |a(x) - a(y) + l|, i.e. d^2 = sum_i r_i^2 dtheta_i^2 with dtheta_i the angle difference taken in
// [-pi, pi] (the lattice is rectangular, so the minimum is taken coordinate by coordinate). Let
// rho = pi min_i r_i: every nonzero l in L has |l| >= 2 rho. P~ = a(P) + L is the periodic lift.
//
// LEMMA 1 (embedded balls). If c in R^m and R < rho then for every y with |y - c| <= R,
// d_T(y, c) = |y - c| (mod L), and y -> y mod L is injective on the closed ball B(c, R).
//   Proof: for l != 0, |y - c + l| >= |l| - |y - c| >= 2 rho - R > R >= |y - c|; two points y, y'
//   of the ball with y - y' = l in L have |l| <= 2R < 2 rho, so l = 0.
//
// A CANDIDATE {p_0..p_m} is decided as follows (decide() below). Lifts: u_0 = 0 and, for j >= 1,
// u_j = (r_i delta_ji)_i with delta_ji = phi_i(p_j) - phi_i(p_0) reduced into (-pi, pi) (an
// enclosure that cannot be reduced strictly inside: UNDECIDED, the lifts are ambiguous). c solves
// 2 u_j . c = |u_j|^2 (j = 1..m) by interval Gaussian elimination with pivots certified nonzero
// (otherwise UNDECIDED: the lifted simplex is not certified non-degenerate), R^2 = |c|^2: c is
// the circumcentre of the lifts, relative to a(p_0). We require R < rho / 2, certified.
//
// LEMMA 2 (the lifts are the only ones). If R < rho / 2 then the vertices' lifts are pairwise
// at distance <= 2R < rho <= pi r_i, so every coordinate difference u_j - u_k is the shortest
// representative of a(p_j) - a(p_k): any set of lifts of the vertices with diameter < rho is a
// translate of {u_j} by L. In particular a vertex set has at most one circumscribed lifted ball
// of radius < rho / 2.
//
// CERTIFIED (in Del_M): R < rho / 2 and every other point q of P has d_T(x, a(q)) > R, certified,
// where x = a(p_0) + c mod L. By Lemma 1 the vertices are at geodesic distance exactly R from x
// (|u_j - c| = R), so x is a point of M equidistant from the simplex's vertices and strictly
// closer to them than to any other point: the simplex is in the nerve of the geodesic Voronoi
// diagram, i.e. in Del_M. The witness: the angles of x, R and the margin (a certified lower bound
// of min_q d_T(x, a(q))^2 - R^2). Equivalently, the lifted simplex is a cell of the Delaunay
// tessellation DT(P~) with no other point of P~ on its circumsphere (a protected simplex).
//
// WHICH q ARE TESTED (the ambient prefilter). Let X = (r_i e(angle_i(x)))_i in R^N be the point x
// of M, e(t) the unit vector of angle t, and E(p) = |p - pi(p)| = sqrt(sum_i (rho_i(p) - r_i)^2)
// with rho_i(p) = |(x_{2i-1}, x_{2i})(p)| (pi(p) = (r_i e(phi_i(p)))_i, so p - pi(p) has the
// components (rho_i - r_i) e(phi_i)). Per circle the chord is at most the arc:
// |r_i e(s) - r_i e(t)| = 2 r_i sin(|s - t| / 2) <= r_i |s - t| for the shortest |s - t| <= pi, so
// |pi(q) - X| <= d_T(x, a(q)). For every q with d_T(x, a(q)) <= 2R the triangle inequality gives
// |q - X| <= E(q) + |pi(q) - X| <= E_max + 2R, and for the double centre X~ (midpoints of the
// enclosures of X) |q - X~| <= 2R + E_max + |X - X~|, each term bounded above from enclosures.
// So grid.ball(X~, that bound) returns every q with d_T(x, a(q)) <= 2R (grid.hpp: every point of
// the closed ball); any other q has d_T(x, a(q))^2 - R^2 > 3R^2, which enters the margin as such.
// The test of one q: delta_i = phi_i(q) - angle_i(x),
// reduced by a multiple of 2 pi near [-pi, pi]; the shortest angle is |delta_i| if certainly
// <= pi, 2 pi - |delta_i| if certainly >= pi, and otherwise lies in the hull of both (their
// minimum lies between the minima of the endpoints). All in MPFI enclosures (exact/enclosure.hpp).
//
// REJECTED (not in Del_M): some q has d_T(x, a(q)) < R, certified. This refutes every empty
// geodesic ball of the vertices of radius < rho / 2: by Lemma 2 its lifts are a translate of
// {u_j}, its centre is the circumcentre c, which has q inside. An empty ball of radius >= rho / 2
// is excluded only when the covering radius of P in M is below rho / 2; that is proven by
// completeness (below), so a rejection is reported only when Del_M is complete, and otherwise
// the candidate is UNDECIDED with the witness in the reason. Conversely, when Del_M is complete,
// every candidate left UNDECIDED is REJECTED "by completeness" (it is not one of the certified
// vertex sets, which are all of Del_M).
//
// COMPLETENESS. Claim: if the certified simplices are nonempty, have pairwise distinct vertex sets,
// every (m-1)-subset of a certified simplex lies in exactly two certified simplices, and every
// point of P is a vertex of one, then the certified simplices are all the m-simplices of Del_M,
// Del_M is pure, and the covering radius of P in M is max R < rho / 2.
//   Proof. P~ is periodic, so DT(P~) (cells: hulls of the points of P~ on an empty sphere) is a
//   face-to-face tiling of R^m by convex polytopes. Each certified simplex lifts (all translates
//   by L) to cells of DT(P~) that are simplices (no other point on the sphere, vertices affinely
//   independent); its vertices are m + 1 distinct points of P (two lifts of one point are >= 2 rho
//   apart, the lifted simplex has diameter < rho), and no other point of P lies at the same place
//   of T as a vertex (it would be on the sphere). Let s be a certified lifted cell and t a facet of
//   it: the facet t is a face of the tiling, so exactly two cells contain it, s and the cell s'
//   across. The bookkeeping gives a second certified simplex s2 containing the vertex set of t;
//   by Lemma 2 (t has diameter < rho) the lift of s2 can be translated so that its copy of t is
//   the copy in s; it is then a cell of DT(P~) containing the facet t and different from s (a
//   different vertex set of P, and no two points of P share a place of T), hence s2 = s'. So the
//   set of certified lifted cells is nonempty and closed under adjacency across facets; since
//   R^m minus the (m-2)-skeleton of the tiling is connected and a path in it meets cells only
//   through facets, it is every cell of DT(P~). Every Voronoi vertex of P~ is then the circumcentre
//   of a certified cell, and every Voronoi cell (bounded: P~ is relatively dense) is the hull of
//   its vertices, so the covering radius is max R < rho / 2. A vertex set in Del_M (a point x of
//   M with the vertices nearest, at distance R' <= covering radius < rho / 2) lifts to points of
//   P~ on an empty sphere, i.e. vertices of the one cell of DT(P~) dual to the Voronoi face of x:
//   a certified simplex, whose m + 1 vertices they are. Pure: every face of a cell is a face of an
//   m-simplex. The last two conditions (distinct vertex sets; every point used) are consequences
//   of the argument; they are checked anyway and their failure refuses completeness.
//
// ROUNDING: all arithmetic is MPFI (outward rounding whatever the FPU mode); doubles appear only
// as exact inputs (the coordinates), as endpoints of enclosures (lower()/upper(), outward), as the
// grid's search radius (an upper bound: upper() of an enclosure), and to choose the multiple k of
// 2 pi to subtract (any k is correct, it only affects how tight the reduction is).
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "certify/intrinsic/engines.hpp"
#include "certify/detail/parallel.hpp"
#include "exact/enclosure.hpp"

namespace delcert::certify::detail {

namespace {

using exact::Enclosure;
using nlohmann::json;

json enclosure_json(const Enclosure& e) { return json::array({e.lower_string(), e.upper_string()}); }

struct Torus {
  int m = 0;
  std::vector<Enclosure> r, r2;      // radii and their squares
  Enclosure pi{0L}, two_pi{0L};
  Enclosure half_rho_sq{0L};          // (pi min r_i / 2)^2
  Enclosure e_max{0L};                // an upper bound of max_p |p - pi(p)|
  std::vector<std::vector<Enclosure>> phi;  // phi[p][i]
};

// d + 2 pi k with k chosen so that the result is near [-pi, pi] (any k is correct).
Enclosure reduce(const Torus& T, const Enclosure& d) {
  const double mid = 0.5 * d.lower() + 0.5 * d.upper();
  const double k = std::nearbyint(mid / (2 * M_PI));
  if (k == 0 || !std::isfinite(k)) return d;
  return d - Enclosure(static_cast<long>(k)) * T.two_pi;
}

// Certainly strictly inside (-pi, pi).
bool strictly_inside(const Torus& T, const Enclosure& d) { return (T.pi - d).is_positive() && (T.pi + d).is_positive(); }

// An enclosure of min_k (d + 2 pi k)^2 for d reduced near [-pi, pi]: with a = |d|, it is a^2 for
// a <= pi and (2 pi - a)^2 for pi <= a <= 3 pi (a straddling pi: the hull of both); always in [0, pi^2].
Enclosure shortest_square(const Torus& T, const Enclosure& d) {
  if (strictly_inside(T, d)) return square(d);
  if (d.contains_zero() || !(Enclosure(3L) * T.pi - (d.is_negative() ? -d : d)).is_positive())
    return hull(Enclosure(0L), square(T.pi));  // not expected (enclosures are tight): the trivial bound
  const Enclosure a = d.is_negative() ? -d : d;  // |d|, certainly in (0, 3 pi)
  Enclosure other = square(T.two_pi - a);
  if ((a - T.pi).is_positive()) return other;
  return hull(square(d), other);
}

struct Outcome {
  enum class Kind { certified, rejected, undecided } kind = Kind::undecided;
  json witness;
  std::string reason;
};

Outcome decide(const Torus& T, const PointGrid& grid, const std::vector<int>& s) {
  const int m = T.m;
  Outcome out;
  const int p0 = s[0];
  // Lifts relative to a(p_0).
  std::vector<std::vector<Enclosure>> u(m + 1, std::vector<Enclosure>(m, Enclosure(0L)));
  for (int j = 1; j <= m; ++j)
    for (int i = 0; i < m; ++i) {
      Enclosure d = reduce(T, T.phi[s[j]][i] - T.phi[p0][i]);
      if (!strictly_inside(T, d)) {
        out.reason = "simplex too large for its lifts: an angle difference between its vertices is not certified "
                     "below pi";
        return out;
      }
      u[j][i] = T.r[i] * d;
    }
  // 2 u_j . c = |u_j|^2, j = 1..m: interval Gaussian elimination, pivots certified nonzero.
  std::vector<std::vector<Enclosure>> A(m, std::vector<Enclosure>(m + 1, Enclosure(0L)));
  for (int j = 0; j < m; ++j) {
    Enclosure n2(0L);
    for (int i = 0; i < m; ++i) {
      A[j][i] = Enclosure(2L) * u[j + 1][i];
      n2 = n2 + square(u[j + 1][i]);
    }
    A[j][m] = n2;
  }
  for (int col = 0; col < m; ++col) {
    int best = -1;
    double best_mag = -1;
    for (int row = col; row < m; ++row) {
      const Enclosure& a = A[row][col];
      if (a.contains_zero()) continue;
      const double mag = std::min(std::fabs(a.lower()), std::fabs(a.upper()));
      if (mag > best_mag) best = row, best_mag = mag;
    }
    if (best < 0) {
      out.reason = "degenerate simplex: its lifted vertices are not certified affinely independent";
      return out;
    }
    std::swap(A[col], A[best]);
    for (int row = col + 1; row < m; ++row) {
      Enclosure f = A[row][col] / A[col][col];
      for (int k = col; k <= m; ++k) A[row][k] = A[row][k] - f * A[col][k];
    }
  }
  std::vector<Enclosure> c(m, Enclosure(0L));
  for (int i = m - 1; i >= 0; --i) {
    Enclosure v = A[i][m];
    for (int k = i + 1; k < m; ++k) v = v - A[i][k] * c[k];
    c[i] = v / A[i][i];
  }
  Enclosure R2(0L);
  for (int i = 0; i < m; ++i) R2 = R2 + square(c[i]);
  if (!(T.half_rho_sq - R2).is_positive()) {
    out.reason = "simplex too large for its lifts: circumradius not certified below pi min r_i / 2";
    return out;
  }
  const Enclosure R = sqrt(R2);
  std::vector<Enclosure> centre(m, Enclosure(0L));  // angles of x
  json centre_json = json::array();
  for (int i = 0; i < m; ++i) {
    centre[i] = T.phi[p0][i] + c[i] / T.r[i];
    centre_json.push_back(enclosure_json(centre[i]));
  }
  // Every q with d_T(x, a(q)) <= 2R is within ambient distance 2R + E_max + |X - X~| of X~ (proof above).
  std::vector<double> X;
  Enclosure deviation2(0L);
  for (int i = 0; i < m; ++i)
    for (const Enclosure& e : {T.r[i] * cos(centre[i]), T.r[i] * sin(centre[i])}) {
      const double mid = 0.5 * e.lower() + 0.5 * e.upper();
      const Enclosure off = e - Enclosure(mid);
      deviation2 = deviation2 + square(Enclosure(std::max(-off.lower(), off.upper())));
      X.push_back(mid);
    }
  const double search = (Enclosure(2L) * R + T.e_max + sqrt(deviation2)).upper();
  Enclosure margin = Enclosure(3L) * R2;  // lower bound for the points outside the search ball
  bool tie = false;
  int tie_point = -1;
  for (int q : grid.ball(X, search)) {
    if (std::binary_search(s.begin(), s.end(), q)) continue;
    Enclosure d2(0L);
    for (int i = 0; i < m; ++i) d2 = d2 + T.r2[i] * shortest_square(T, reduce(T, T.phi[q][i] - centre[i]));
    Enclosure diff = d2 - R2;
    if (diff.is_negative()) {
      out.kind = Outcome::Kind::rejected;
      out.witness = {{"kind", "not_intrinsic"},
                     {"simplex", s},
                     {"point", q},
                     {"centre_angles", centre_json},
                     {"radius", enclosure_json(R)},
                     {"distance_squared_minus_radius_squared", enclosure_json(diff)}};
      out.reason = "point " + std::to_string(q) + " is strictly inside the geodesic circumball of the shortest lifts (d^2 - R^2 <= " +
                   diff.upper_string() + ")";
      return out;
    }
    if (!diff.is_positive()) {
      if (!tie) tie_point = q;
      tie = true;
      continue;
    }
    if (diff.lower() < margin.lower()) margin = diff;
  }
  if (tie) {
    out.reason = "not protected: point " + std::to_string(tie_point) +
                 " cannot be separated from the boundary of the empty geodesic ball (a possible tie)";
    return out;
  }
  out.kind = Outcome::Kind::certified;
  out.witness = {{"kind", "intrinsic_voronoi_vertex"},
                 {"simplex", s},
                 {"centre_angles", centre_json},
                 {"radius", enclosure_json(R)},
                 {"margin", margin.lower_string()}};
  return out;
}

const char* kConvention =
    "d_M(x, p) := d_M(x, pi(p)), pi(p) the radial projection of p within each coordinate plane (x_{2i-1}, x_{2i}) "
    "onto the circle of radius r_i, i.e. the point of M with the angles phi_i(p) = atan2(x_{2i}, x_{2i-1}); "
    "d_M^2 = sum_i r_i^2 dtheta_i^2 with dtheta_i the angle difference in [-pi, pi] (the flat torus metric)";

const char* kCompleteness =
    "closed pseudomanifold: every certified simplex has an empty protected geodesic circumball of radius "
    "< pi min r_i / 2 (embedded, its lifts unique), so it lifts to a cell of the periodic Delaunay tessellation "
    "of the angle coordinates; every (m-1)-face lies in exactly two certified simplices, so the certified cells "
    "are closed under facet adjacency in that face-to-face tiling of connected R^m, hence all of its cells; the "
    "covering radius is then max R < pi min r_i / 2, every m-simplex of Del_M is certified and Del_M is pure "
    "(proof in certify/intrinsic_torus.cpp)";

}  // namespace

IntrinsicDelaunay intrinsic_delaunay_flat_torus(const io::ShapeSpec& metric, const io::PointSet& points,
                                                const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                                int threads) {
  IntrinsicDelaunay D;
  D.metric = "product_of_circles";
  D.convention = kConvention;
  D.completeness = kCompleteness;
  Torus T;
  T.m = static_cast<int>(metric.radii.size());
  const int m = T.m;
  if (m < 1 || points.dimension != 2 * m) {
    D.reason = "the product of circles needs N = 2m (m = " + std::to_string(m) + ", N = " +
               std::to_string(points.dimension) + ")";
    return D;
  }
  for (const mpq_class& r : metric.radii)
    if (sgn(r) <= 0) {
      D.reason = "a radius of the product of circles is not positive";
      return D;
    }
  const std::size_t n = points.size();
  for (std::size_t p = 0; p < n; ++p) {
    auto x = points.point(p);
    for (int i = 0; i < m; ++i)
      if (x[2 * i] == 0 && x[2 * i + 1] == 0) {
        D.reason = "point " + std::to_string(p) + " has (x" + std::to_string(2 * i + 1) + ", x" + std::to_string(2 * i + 2) +
                   ") = (0, 0): its angle, hence its projection onto M, is undefined";
        return D;
      }
  }
  T.pi = Enclosure::pi();
  T.two_pi = Enclosure(2L) * T.pi;
  mpq_class rmin = metric.radii[0];
  for (const mpq_class& r : metric.radii) {
    T.r.emplace_back(r);
    T.r2.push_back(square(Enclosure(r)));
    rmin = std::min(rmin, r);
  }
  T.half_rho_sq = square(T.pi * Enclosure(rmin) / Enclosure(2L));
  T.phi.resize(n);
  double e_max = 0;
  for (std::size_t p = 0; p < n; ++p) {
    auto x = points.point(p);
    Enclosure e2(0L);
    for (int i = 0; i < m; ++i) {
      const Enclosure a(x[2 * i]), b(x[2 * i + 1]);
      // atan2(+-0, x < 0) = pi exactly: MPFI would return the whole branch cut [-pi, pi] there.
      T.phi[p].push_back(x[2 * i + 1] == 0 && x[2 * i] < 0 ? T.pi : atan2(b, a));
      e2 = e2 + square(sqrt(square(a) + square(b)) - T.r[i]);
    }
    e_max = std::max(e_max, sqrt(e2).upper());
  }
  T.e_max = Enclosure(e_max);

  // Unique candidates in sorted order (compute_intrinsic_delaunay validated them).
  std::map<std::vector<int>, Outcome> decided;
  auto decide_all = [&](const std::vector<std::vector<int>>& batch) {
    std::vector<Outcome> outs(batch.size());
    parallel_for(batch.size(), threads, [&](std::size_t k, int) { outs[k] = decide(T, grid, batch[k]); });
    for (std::size_t k = 0; k < batch.size(); ++k) decided.emplace(batch[k], std::move(outs[k]));
  };
  {
    std::vector<std::vector<int>> unique = candidates;
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    decide_all(unique);
  }

  // GIFT WRAPPING. The candidates may miss cells (their sources are other complexes). Across a
  // ridge in one certified simplex ridge + {a} only, the cell on the other side is ridge + {q} for
  // the q beyond the ridge's hyperplane whose circumcentre lies farthest back toward a along the
  // ridge's normal (the empty-ball pivot): found in floating point on the shortest lifts relative
  // to the ridge's first vertex, then DECIDED like any candidate (nothing the search computes is
  // trusted; decide() and completeness ignore where a candidate came from). Rounds until no new
  // candidate appears (at most 64). Deterministic: ties go to the smaller index.
  std::vector<std::vector<double>> ang(n, std::vector<double>(m));  // approximate angles
  for (std::size_t p = 0; p < n; ++p)
    for (int i = 0; i < m; ++i) ang[p][i] = std::atan2(points.point(p)[2 * i + 1], points.point(p)[2 * i]);
  auto lift = [&](int base, int q) {  // shortest lift of a(q) - a(base), approximate
    std::vector<double> w(m);
    for (int i = 0; i < m; ++i) w[i] = metric.radii[i].get_d() * std::remainder(ang[q][i] - ang[base][i], 2 * M_PI);
    return w;
  };
  auto dot = [&](const std::vector<double>& x, const std::vector<double>& y) {
    return std::inner_product(x.begin(), x.end(), y.begin(), 0.0);
  };
  auto propose = [&](const std::vector<int>& ridge, int a) -> int {
    const int b = ridge[0];
    std::vector<std::vector<double>> u;  // u_1..u_{m-1}
    for (int j = 1; j < m; ++j) u.push_back(lift(b, ridge[j]));
    // Circumcentre c0 of the ridge's lifts in their affine hull: c0 = sum beta_k u_k with
    // sum_k 2 (u_j . u_k) beta_k = |u_j|^2 (Gaussian elimination with partial pivoting).
    const int k = m - 1;
    std::vector<std::vector<double>> G(k, std::vector<double>(k + 1));
    for (int j = 0; j < k; ++j) {
      for (int l = 0; l < k; ++l) G[j][l] = 2 * dot(u[j], u[l]);
      G[j][k] = dot(u[j], u[j]);
    }
    for (int col = 0; col < k; ++col) {
      int best = col;
      for (int row = col + 1; row < k; ++row)
        if (std::fabs(G[row][col]) > std::fabs(G[best][col])) best = row;
      std::swap(G[col], G[best]);
      if (G[col][col] == 0) return -1;
      for (int row = col + 1; row < k; ++row) {
        const double f = G[row][col] / G[col][col];
        for (int l = col; l <= k; ++l) G[row][l] -= f * G[col][l];
      }
    }
    std::vector<double> beta(k);
    for (int j = k - 1; j >= 0; --j) {
      double v = G[j][k];
      for (int l = j + 1; l < k; ++l) v -= G[j][l] * beta[l];
      beta[j] = v / G[j][j];
    }
    std::vector<double> c0(m, 0.0);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < m; ++i) c0[i] += beta[j] * u[j][i];
    const double R0sq = dot(c0, c0);
    // Unit normal pointing away from a: Gram-Schmidt of a's lift against the ridge's directions.
    std::vector<std::vector<double>> e;
    auto orth = [&](std::vector<double> w) {
      for (const auto& f : e) {
        const double t = dot(w, f);
        for (int i = 0; i < m; ++i) w[i] -= t * f[i];
      }
      return w;
    };
    for (const auto& v : u) {
      std::vector<double> w = orth(v);
      const double nw = std::sqrt(dot(w, w));
      if (!(nw > 0)) return -1;
      for (double& x : w) x /= nw;
      e.push_back(w);
    }
    std::vector<double> nrm = orth(lift(b, a));
    const double nn = std::sqrt(dot(nrm, nrm));
    if (!(nn > 0)) return -1;
    for (double& x : nrm) x /= -nn;
    double reach = nn;  // sizes the first search
    for (int j = 0; j < k; ++j) reach = std::max(reach, std::sqrt(dot(u[j], u[j])));
    const double rho = M_PI * rmin.get_d();
    for (double radius = 2 * reach; radius > 0; radius *= 2) {
      const double geo = std::min(radius, rho);
      // Ambient chord <= geodesic distance, each point within e_max of M: every q at geodesic
      // distance <= geo from b is in this ambient ball (used only to size the proposal search).
      int best = -1;
      double best_t = 0;
      for (int q : grid.ball(points.point(b), geo + 2 * T.e_max.upper() + 1e-9 * geo)) {
        if (q == a || std::count(ridge.begin(), ridge.end(), q)) continue;
        std::vector<double> w = lift(b, q);
        for (int i = 0; i < m; ++i) w[i] -= c0[i];
        const double h = dot(w, nrm);
        if (!(h > 0)) continue;
        const double t = (dot(w, w) - R0sq) / (2 * h);
        if (best < 0 || t < best_t || (t == best_t && q < best)) best = q, best_t = t;
      }
      if (best >= 0) {
        // The circumball of ridge + {best}: centre c0 + t nrm; it lies in the searched ball?
        std::vector<double> cc(c0);
        for (int i = 0; i < m; ++i) cc[i] += best_t * nrm[i];
        if (std::sqrt(dot(cc, cc)) + std::sqrt(R0sq + best_t * best_t) <= geo || geo >= rho) return best;
      }
      if (geo >= rho) return -1;
    }
    return -1;
  };
  for (int round = 0; round < 64; ++round) {
    std::map<std::vector<int>, std::vector<int>> count;  // ridge -> opposite vertices in certified simplices
    for (const auto& [simplex, o] : decided) {
      if (o.kind != Outcome::Kind::certified) continue;
      for (int drop = 0; drop <= m; ++drop) {
        std::vector<int> r;
        for (int j = 0; j <= m; ++j)
          if (j != drop) r.push_back(simplex[j]);
        count[r].push_back(simplex[drop]);
      }
    }
    std::vector<std::pair<std::vector<int>, int>> open;
    for (const auto& [ridge, opposite] : count)
      if (opposite.size() == 1) open.emplace_back(ridge, opposite[0]);
    std::vector<int> proposal(open.size(), -1);
    parallel_for(open.size(), threads, [&](std::size_t k, int) { proposal[k] = propose(open[k].first, open[k].second); });
    std::set<std::vector<int>> fresh;
    for (std::size_t k = 0; k < open.size(); ++k) {
      if (proposal[k] < 0) continue;
      std::vector<int> candidate(open[k].first);
      candidate.push_back(proposal[k]);
      std::sort(candidate.begin(), candidate.end());
      if (!decided.count(candidate)) fresh.insert(candidate);
    }
    if (fresh.empty()) break;
    decide_all(std::vector<std::vector<int>>(fresh.begin(), fresh.end()));
  }

  std::vector<Outcome*> rejected;
  std::vector<IntrinsicRejection> rejected_by_completeness;
  std::vector<const std::vector<int>*> rejected_simplex;
  for (auto& [simplex, o] : decided) {
    if (o.kind == Outcome::Kind::certified)
      D.simplices.push_back({simplex, std::move(o.witness)});
    else if (o.kind == Outcome::Kind::undecided)
      D.undecided.push_back({simplex, o.reason});
    else
      rejected.push_back(&o), rejected_simplex.push_back(&simplex);
  }

  // Completeness (the proof at the top): nonempty, distinct vertex sets (unique above), every
  // (m-1)-face in exactly two certified simplices, every point a vertex.
  std::string why;
  if (D.simplices.empty()) {
    why = "no candidate is certified";
  } else {
    std::map<std::vector<int>, int> faces;
    std::vector<char> used(n, 0);
    for (const auto& S : D.simplices)
      for (int drop = 0; drop <= m; ++drop) {
        std::vector<int> f;
        for (int j = 0; j <= m; ++j)
          if (j != drop) f.push_back(S.simplex[j]);
        ++faces[f];
        used[S.simplex[drop]] = 1;
      }
    for (const auto& [f, count] : faces)
      if (count != 2) {
        std::string fs;
        for (int v : f) fs += (fs.empty() ? "" : ", ") + std::to_string(v);
        why = "the certified simplices are not a closed pseudomanifold: the face {" + fs + "} lies in " +
              std::to_string(count) + " of them, not 2";
        break;
      }
    if (why.empty())
      for (std::size_t p = 0; p < n; ++p)
        if (!used[p]) {
          why = "point " + std::to_string(p) + " is a vertex of no certified simplex";
          break;
        }
  }
  D.complete = why.empty();
  D.reason = D.complete ? "" : "not complete: " + why;

  // A rejection refutes only empty balls of radius < pi min r_i / 2; completeness bounds every one.
  // Completeness also decides every undecided candidate: Del_M is exactly the certified simplices,
  // the vertex sets are unique, so a candidate not certified is not in Del_M.
  if (D.complete) {
    for (auto& u : D.undecided)
      rejected_by_completeness.push_back({u.simplex, {{"kind", "not_intrinsic"},
                                                      {"simplex", u.simplex},
                                                      {"by", "completeness"},
                                                      {"undecided_because", u.reason}}});
    D.undecided.clear();
  }
  for (std::size_t k = 0; k < rejected.size(); ++k) {
    if (D.complete) {
      D.rejected.push_back({*rejected_simplex[k], std::move(rejected[k]->witness)});
    } else {
      D.undecided.push_back({*rejected_simplex[k], rejected[k]->reason +
                                                         "; that refutes it only if every empty geodesic ball of P "
                                                         "has radius < pi min r_i / 2, which is proven only when Del_M "
                                                         "is complete"});
    }
  }
  D.rejected.insert(D.rejected.end(), rejected_by_completeness.begin(), rejected_by_completeness.end());
  std::sort(D.rejected.begin(), D.rejected.end(),
            [](const IntrinsicRejection& a, const IntrinsicRejection& b) { return a.simplex < b.simplex; });
  std::sort(D.undecided.begin(), D.undecided.end(),
            [](const IntrinsicUndecided& a, const IntrinsicUndecided& b) { return a.simplex < b.simplex; });
  D.computed = true;
  return D;
}

}  // namespace delcert::certify::detail
