// Del_M on a round sphere M = S(c, r) in R^N (m = N - 1), docs/design.md §3.9.
//
// CHARACTERISATION. On a sphere the geodesic balls of radius < pi r are the open caps
// {x in M : nu . (x - c) > t}, and every cap is one. So an m-simplex s (m + 1 = N points of the
// projected sample pi(P) = {c + r (p - c) / |p - c|}) is in Del_M(pi(P)) iff some open cap
// bounded by the (m - 1)-sphere through pi(s) holds no point of pi(P) and its boundary holds no
// point but those of s: iff every other point of pi(P) lies STRICTLY on one side of the affine
// hyperplane H(s) through pi(s) (the cap on the other side is the empty geodesic ball; its pole
// is the intrinsic Voronoi vertex of s). Such an s is a facet of the polytope K = conv(pi(P)).
//
// THE SIGN. With u = p - c (exact rationals), n = |u| = sqrt(|u|^2) and the last row the tested
// point q, orient(s, q) = sign det [[1, pi(x_j)]] (j over s, then q) equals
//   sign det A,  A = [[n_j, u_j]]  ((N + 1) x (N + 1)),
// because translating by -c keeps the determinant, row j of [[1, r u_j / n_j]] times n_j > 0 and
// the last N columns divided by r > 0 keep its sign. Expanding along the first column,
//   det A = sum_j (-1)^j n_j D_j,  D_j = det(U without row j)  (U: the N + 1 rows u_j, exact),
// a sum of square roots of rationals with rational coefficients. Decided by (1) an interval
// evaluation of det A (CGAL's Interval_nt under upward rounding: outward for every operation,
// overflow gives an infinite bound, i.e. no decision; underflow rounds outward too), then (2)
// exactly: D_j as exact rationals, terms with the same radicand |u_j|^2 merged (exactly); no
// term left: det A = 0 exactly (a proven tie); one term: its coefficient's sign; else MPFI
// enclosures of the sum at 256, 2048 and 16384 bits. A sum that stays undecided is reported
// UNDECIDED (a tie cannot always be proven without factoring the radicands, but it is never
// guessed). The centre c (translated to 0) has row [1, 0, ..., 0]: orient(s, c) = (-1)^N sign
// det(U_s), exactly.
//
// WHICH POINTS ARE TESTED. Let h >= 0 be the distance from c to H(s) over r and C the closed cap
// on the side of H(s) NOT holding c (h > 0, i.e. orient(s, c) != 0). Its boundary circle has
// centre z = c + h r nu and radius R_s (the circumradius of pi(s)), and for x in C:
//   |x - z|^2 = r^2 - 2 h r nu.(x - c) + h^2 r^2 <= r^2 (1 - h^2) = R_s^2,
// so |x - pi(p_0)| <= 2 R_s. Hence a point q with pi(q) in C has
//   |q - p_0| <= |q - pi(q)| + 2 R_s + |pi(p_0) - p_0| <= 2 R_s + delta_q + delta_0 <= rho,
// with delta_q = | |u_q| - r | and rho = 2 R^_s + delta^_0 + delta^_max from certified upper bounds
// (interval arithmetic, upward rounding; R^_s from the Gram system of pi(s) solved by Cramer's
// rule in intervals: +inf when its determinant's enclosure holds 0). Every q outside the grid's
// ball B(p_0, rho) (a superset of the closed ball, certify/detail/grid.hpp) is therefore strictly
// on c's side: only the points of the ball are tested. When orient(s, c) = 0, every point is.
//
// COMPLETENESS. Let C* be the certified simplices (all other points strictly on one side, so
// pi(s) affinely independent and conv(pi(s)) a facet of K). K is full-dimensional as soon as one
// simplex is certified with another point strictly off H(s). In a polytope every ridge lies in
// exactly two facets and the facet-ridge graph is connected. If every (m - 1)-face (ridge) of
// every simplex of C* lies in exactly two simplices of C*, those are the two facets of K through
// it, so C* is closed under adjacency and is every facet of K: all of Del_M(pi(P)), pure (every
// face of the hull boundary is a face of a facet). Requires n >= N + 1 points.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "certify/certificate.hpp"
#include "certify/intrinsic/engines.hpp"
#include "certify/restricted/sphere_hull.hpp"
#include "exact/enclosure.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {

namespace {

using exact::IntervalNumber;
using nlohmann::json;

struct Sphere {
  int N = 0;
  mpq_class r;
  std::vector<std::vector<mpq_class>> u;        // exact p - c, per point
  std::vector<mpq_class> s;                     // |u|^2 exact
  std::vector<std::vector<IntervalNumber>> ui;  // enclosures of u
  std::vector<IntervalNumber> ni;               // enclosures of |u|

  // orient(rows[0..N), q) as explained above; rows[N] is the tested point.
  HullSide orient(const std::vector<int>& idx) const {
    {
      exact::UpwardRounding up;
      IntervalNumber det(0);
      bool finite = true;
      for (int j = 0; j <= N && finite; ++j) {
        std::vector<const IntervalNumber*> rows;
        for (int i = 0; i <= N; ++i)
          if (i != j) rows.push_back(ui[idx[i]].data());
        IntervalNumber t = ni[idx[j]] * laplace(rows, 0, N);
        det = j % 2 ? det - t : det + t;
        finite = std::isfinite(det.inf()) && std::isfinite(det.sup());
      }
      if (finite) {
        const int sg = sign_of(det);
        if (sg) return sg > 0 ? HullSide::positive : HullSide::negative;
      }
    }
    std::map<mpq_class, mpq_class> terms;  // radicand -> merged coefficient
    for (int j = 0; j <= N; ++j) {
      std::vector<const mpq_class*> rows;
      for (int i = 0; i <= N; ++i)
        if (i != j) rows.push_back(u[idx[i]].data());
      mpq_class d = laplace(rows, 0, N);
      if (j % 2) d = -d;
      terms[s[idx[j]]] += d;
    }
    std::vector<std::pair<mpq_class, mpq_class>> live;
    for (auto& [rad, coef] : terms)
      if (sgn(coef) != 0) live.emplace_back(rad, coef);
    if (live.empty()) return HullSide::zero;
    if (live.size() == 1) return sgn(live[0].second) > 0 ? HullSide::positive : HullSide::negative;
    for (int precision : {256, 2048, 16384}) {
      exact::Enclosure sum(0L, precision);
      for (const auto& [rad, coef] : live) sum = sum + exact::Enclosure(coef, precision) * sqrt(exact::Enclosure(rad, precision));
      if (sum.is_positive()) return HullSide::positive;
      if (sum.is_negative()) return HullSide::negative;
    }
    return HullSide::unknown;
  }

  // (-1)^N sign det(U_s): the side of the centre (0 when H(s) passes through c).
  int centre_side(const std::vector<int>& simplex) const {
    std::vector<const mpq_class*> rows;
    for (int i : simplex) rows.push_back(u[i].data());
    const int d = sgn(laplace(rows, 0, N));
    return N % 2 ? -d : d;
  }

  // A certified upper bound of the circumradius of pi(s) (+inf when not bounded).
  double circumradius_upper(const std::vector<int>& simplex) const {
    exact::UpwardRounding up;
    const exact::Interval re = exact::enclose(r);
    const IntervalNumber R(re.lo, re.hi);
    std::vector<std::vector<IntervalNumber>> a(N, std::vector<IntervalNumber>(N));
    for (int j = 0; j < N; ++j)
      for (int v = 0; v < N; ++v) a[j][v] = R * ui[simplex[j]][v] / ni[simplex[j]];
    return detail::circumradius_upper(a);
  }
};

}  // namespace

IntrinsicDelaunay intrinsic_delaunay_sphere(const io::ShapeSpec& metric, const io::PointSet& points,
                                            const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                            int threads) {
  IntrinsicDelaunay D;
  D.metric = "sphere";
  D.convention = "d_M(x, p) := d_M(x, pi(p)) with pi(p) = c + r (p - c) / |p - c| (the radial projection onto M); "
                 "geodesic balls of the sphere are its caps, so an m-simplex is in Del_M iff every other projected "
                 "point lies strictly on one side of the hyperplane through its projected points";
  D.completeness = "the certified simplices are facets of conv(pi(P)); every ridge lies in exactly two of them, so "
                   "they are all its facets (the facet-ridge graph of a polytope is connected): all of Del_M, pure";
  const int N = points.dimension;
  const std::size_t n = points.size();
  Sphere S;
  S.N = N;
  S.r = metric.radius;
  S.u.resize(n), S.s.resize(n), S.ui.resize(n), S.ni.resize(n);
  double delta_max = 0;  // certified upper bound of max_q | |u_q| - r |
  std::vector<double> delta(n);
  {
    exact::UpwardRounding up;
    const exact::Interval ri = exact::enclose(metric.radius);
    for (std::size_t q = 0; q < n; ++q) {
      S.u[q].resize(N), S.ui[q].resize(N);
      for (int v = 0; v < N; ++v) {
        S.u[q][v] = exact::to_rational(points.point(q)[v]) - metric.center[v];
        S.s[q] += S.u[q][v] * S.u[q][v];
        const exact::Interval iv = exact::enclose(S.u[q][v]);
        S.ui[q][v] = IntervalNumber(iv.lo, iv.hi);
      }
      if (sgn(S.s[q]) == 0) {
        D.reason = "point " + std::to_string(q) + " is the sphere's centre: its projection onto M is undefined";
        return D;
      }
      const exact::Interval si = exact::enclose(S.s[q]);
      S.ni[q] = exact::sqrt(IntervalNumber(si.lo, si.hi));
      const IntervalNumber dq = S.ni[q] - IntervalNumber(ri.lo, ri.hi);
      delta[q] = std::max(std::abs(dq.inf()), std::abs(dq.sup()));
      delta_max = std::max(delta_max, delta[q]);
    }
  }
  D.computed = true;

  LiftedSphere L;  // the projected points themselves (certify/detail/sphere_hull.hpp)
  L.D = N;
  L.count = n;
  L.orient = [&S](const std::vector<int>& rows) { return S.orient(rows); };
  L.centre_side = [&S](const std::vector<int>& facet) { return S.centre_side(facet); };
  L.cap = [&](const std::vector<int>& facet) {
    LiftedSphere::Cap cap;
    const double R = S.circumradius_upper(facet);
    if (!std::isfinite(R)) return cap;
    exact::UpwardRounding up;
    cap.radius = 2 * R + delta[facet[0]] + delta_max;  // each operation rounded upward
    if (std::isfinite(cap.radius)) cap.ids = grid.ball(points.point(facet[0]), cap.radius);
    return cap;
  };
  L.near = [&](const std::vector<int>& ridge, double chord) {
    return grid.ball(points.point(ridge[0]), chord * metric.radius.get_d() + 2 * delta_max);
  };
  L.approx.assign(n, std::vector<double>(N));  // normalised projections, approximate
  for (std::size_t q = 0; q < n; ++q) {
    double nn = 0;
    for (int v = 0; v < N; ++v) nn += std::pow(points.point(q)[v] - metric.center[v].get_d(), 2);
    nn = std::sqrt(nn);
    for (int v = 0; v < N; ++v) L.approx[q][v] = (points.point(q)[v] - metric.center[v].get_d()) / nn;
  }
  std::map<std::vector<int>, HullDecision> decided;
  decide_facets(L, candidates, decided, threads);
  const std::optional<OpenRidge> open = wrap_and_count(L, decided, threads);

  for (const auto& [simplex, d] : decided) {
    if (d.kind == HullDecision::Kind::certified) {
      const bool bounded = std::isfinite(d.radius);
      D.simplices.push_back(
          {simplex,
           {{"kind", "intrinsic_voronoi_vertex"},
            {"simplex", simplex},
            {"empty_cap", d.centre_side == 0 ? "a hemisphere"
                          : d.empty_cap_small ? "the one not holding the centre"
                                              : "the one holding the centre"},
            {"points_tested", d.tested},
            {"test_radius", bounded ? json(num(d.radius)) : json("all points")},
            {"detail", "every other projected point lies strictly on one side of the hyperplane through the "
                       "simplex's projected points: the cap on the other side is an empty geodesic ball, its "
                       "pole the intrinsic Voronoi vertex"}}});
    } else if (d.kind == HullDecision::Kind::rejected) {
      json w = {{"kind", "not_intrinsic"},
                {"simplex", simplex},
                {"points_on_both_sides", {d.both_sides[0], d.both_sides[1]}},
                {"detail", "the two points' projections lie strictly on opposite sides of the hyperplane through the "
                           "simplex's projected points, so each cap bounded by it (each geodesic ball through the "
                           "simplex) holds one of them"}};
      if (d.untested >= 0 && (d.both_sides[0] == d.untested || d.both_sides[1] == d.untested))
        w["untested_point"] = d.untested;
      D.rejected.push_back({simplex, std::move(w)});
    } else {
      D.undecided.push_back(
          {simplex, d.tie >= 0 ? "point " + std::to_string(d.tie) +
                                     " is exactly on the boundary of the simplex's geodesic ball (a tie: not protected)"
                    : d.unknown >= 0 ? "the side of point " + std::to_string(d.unknown) +
                                           " was not decided (at 16384 bits): a possible tie, not protected"
                                     : "no other point to decide the side of the empty cap"});
    }
  }
  if (n < static_cast<std::size_t>(N) + 1) D.reason = "fewer than N + 1 points";
  else if (D.simplices.empty()) D.reason = "no simplex of Del_M certified";
  else if (open) {
    std::string face;
    for (int v : open->ridge) face += (face.empty() ? "" : ",") + std::to_string(v);
    D.reason = "the certified simplices do not close up: the face {" + face + "} lies in " +
               std::to_string(open->facets) + " of them (" + std::to_string(D.undecided.size()) +
               " candidate(s) undecided)";
  }
  D.complete = D.reason.empty();
  return D;
}

}  // namespace delcert::certify::detail
