// Del_M on a product of round spheres S^k1(r_1) x ... x S^kF(r_F), m = sum k_f <= 3, each factor
// on its own block of coordinates, centred at 0 (S^2 x S^1, circles in any coordinate order, ...;
// certify/intrinsic.hpp; docs/design.md §3.9). No hull or lattice argument applies (a product's
// geodesic balls are neither caps nor Euclidean balls of a cover), so Del_M is computed as Del_RM
// is: every point's GEODESIC Voronoi cell by box subdivision in one stereographic chart per factor
// (certify/detail/param_cell.cpp, GEODESIC: s_q = d_M^2(x, q) - d_M^2(x, p) with the squared
// angles enclosed by exact/angle_series.hpp), assembled by certify/restricted.cpp. Every statement
// of restricted.hpp holds with d_M in place of the ambient distance:
//   * a VERTEX (Krawczyk's unique root of the m equidistance equations s_q = 0 in a box where every
//     g is C^1, i.e. away from each point's cut locus, with every other point proven strictly
//     farther) is a point of M whose nearest points are exactly the simplex's: the simplex is in
//     Del_M, with no assumption. The witness gives the vertex's enclosure, its geodesic radius R
//     and the margin, recomputed here in MPFI (below).
//   * THE COVERING ARGUMENT (restricted.hpp) uses only that f(x) = d_M(x, pi(P)) is continuous on
//     M, that every cell's kept boxes cover M ∩ Vor_M(p) ∩ B_M(pi(p), r_p) (the chart covers the
//     geodesic ball, the candidates hold every point that can be nearer there: param_cell.cpp), and
//     that M is connected (a product of spheres of dimension >= 1 is). So when it holds, the
//     vertices found are ALL the geodesic Voronoi vertices and every m-simplex of Del_M is found.
//   * A candidate not found is then not in Del_M ("by completeness"); without the covering
//     argument it is UNDECIDED with the reason.
// POINTS NEAR M: d_M(x, q) := d_M(x, pi(q)), pi(q)_f = r_f q_f / |q_f| (intrinsic.hpp); a point
// with a zero block has no projection and leaves Del_M not computed. E >= max_q |q - pi(q)| (the
// projection slack) is computed here under upward rounding: |q - pi(q)|^2 = sum_f (|q_f| - r_f)^2.
// THE WITNESS (MPFI, 128 bits, outward): the vertex x from its enclosure X (N intervals), per
// factor cos theta_f(q) = X_f . q_f / (r_f |q_f|) (acos uses the part in [-1, 1]: x_f is on the
// sphere, its enclosure only pokes out by rounding; only the SIGN of the dot product for the
// width of X is not needed), d_M^2 = sum_f r_f^2 theta_f^2, R^2 from the point the cell was found
// at. The margin is min over q of d_M^2(x, q) - R^2, over the points of grid.ball(X~, 2R + E + dev)
// (dev = |X - X~|); any other q has |q - x| > 2R + E, so d_M(x, pi(q)) >= |x - pi(q)| > 2R and
// d_M^2 - R^2 > 3 R^2, which starts the minimum. The cell proved every such difference positive
// in double intervals, and the simplex's own points equidistant (Krawczyk's root); a margin not
// certainly positive here, or a vertex of the simplex certainly not at distance R, would
// contradict it: the simplex is then left UNDECIDED with that reason (the program caught itself),
// never certified.
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "certify/intrinsic/engines.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/enclosure.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::certify::detail {

namespace {

using exact::Enclosure;
using nlohmann::json;

json enclosure_json(const Enclosure& e) { return json::array({e.lower_string(), e.upper_string()}); }

const char* kConvention =
    "d_M(x, p) := d_M(x, pi(p)), pi(p) the radial projection of each factor's block of p onto that factor's "
    "sphere (centre 0, radius r_f); d_M^2 = sum_f r_f^2 theta_f^2 with theta_f the angle within factor f "
    "(the product metric)";

const char* kCompleteness =
    "geodesic Voronoi cells by box subdivision (one stereographic chart per factor): every cell complete and the "
    "covering bound below every analysed geodesic radius, so the geodesic Voronoi vertices found are all of them "
    "(the covering argument of certify/restricted.hpp with d_M; proof in certify/intrinsic_product.cpp)";

// d_M^2(x, pi(q)) for the vertex enclosure X.
Enclosure distance2(const io::ShapeSpec& g, const exact::Box& X, std::span<const double> q) {
  Enclosure d2(0L);
  for (const auto& f : g.factors) {
    Enclosure dot(0L), len2(0L);
    for (int c : f.coordinates) {
      const Enclosure x = Enclosure::between(mpq_class(X[c].lo), mpq_class(X[c].hi));
      dot = dot + x * Enclosure(q[c]);
      len2 = len2 + square(Enclosure(q[c]));
    }
    const Enclosure r(f.radius);
    const Enclosure theta = acos(dot / (r * sqrt(len2)));
    d2 = d2 + square(r) * square(theta);
  }
  return d2;
}

}  // namespace

IntrinsicDelaunay intrinsic_delaunay_product(const io::ManifoldSpec& spec, const io::ShapeSpec& g,
                                             const io::PointSet& points, const PointGrid& grid,
                                             const std::vector<std::vector<int>>& candidates, int threads) {
  IntrinsicDelaunay D;
  D.metric = "product";
  D.convention = kConvention;
  D.completeness = kCompleteness;
  const std::size_t n = points.size();
  double slack = 0;
  {
    exact::UpwardRounding up;
    using IA = exact::IntervalNumber;
    for (std::size_t q = 0; q < n; ++q) {
      IA e2(0);
      for (std::size_t fi = 0; fi < g.factors.size(); ++fi) {
        const auto& f = g.factors[fi];
        IA len2(0);
        bool zero = true;
        for (int c : f.coordinates) len2 += exact::square(IA(points.point(q)[c])), zero = zero && points.point(q)[c] == 0;
        if (zero) {
          D.reason = "point " + std::to_string(q) + " is 0 in the block of factor " + std::to_string(fi + 1) +
                     ": its projection onto M is undefined";
          return D;
        }
        e2 += exact::square(exact::sqrt(len2) - exact::to_interval_number(exact::enclose(f.radius)));
      }
      slack = std::max(slack, exact::sqrt(e2).sup());
    }
  }
  RestrictedDelaunayOptions o;
  o.threads = threads;
  o.expected = &candidates;
  o.cell.shape = &g;
  o.cell.geodesic = true;
  o.cell.projection_slack = slack;
  const exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);  // (unused by geodesic cells)
  const RestrictedDelaunay R = compute_restricted_delaunay(system, points, grid, o);

  std::set<std::vector<int>> found;
  for (const RestrictedSimplex& s : R.simplices) {
    const exact::Box& X = s.vertex.x;
    const Enclosure R2 = distance2(g, X, points.point(s.found_at));
    const Enclosure Rad = sqrt(R2);
    std::vector<double> c;
    Enclosure dev2(0L);
    json vertex = json::array();
    for (const auto& x : X) {
      c.push_back(x.midpoint());
      const Enclosure off = Enclosure::between(mpq_class(x.lo), mpq_class(x.hi)) - Enclosure(x.midpoint());
      dev2 = dev2 + square(Enclosure(std::max(-off.lower(), off.upper())));
      vertex.push_back({x.lo, x.hi});
    }
    const double search = (Enclosure(2L) * Rad + Enclosure(slack) + sqrt(dev2)).upper();
    Enclosure margin = Enclosure(3L) * R2;
    int bad = -1;
    for (int q : grid.ball(c, search)) {
      if (std::binary_search(s.simplex.begin(), s.simplex.end(), q)) continue;
      const Enclosure diff = distance2(g, X, points.point(q)) - R2;
      if (!diff.is_positive()) bad = q;
      if (diff.lower() < margin.lower()) margin = diff;
    }
    for (int v : s.simplex)  // equidistant (Krawczyk's root): a difference certainly nonzero contradicts it
      if (!(distance2(g, X, points.point(v)) - R2).contains_zero()) bad = v;
    if (bad >= 0) {
      const Enclosure d = distance2(g, X, points.point(bad)) - R2;
      D.undecided.push_back({s.simplex, "the vertex re-checked in MPFI contradicts its cell at point " + std::to_string(bad) +
                                            " (d_M^2 - R^2 in " + d.to_string(6) +
                                            "; the cell proved it farther, or equidistant for a vertex of the simplex)"});
      continue;
    }
    found.insert(s.simplex);
    D.simplices.push_back({s.simplex, {{"kind", "intrinsic_voronoi_vertex"},
                                       {"simplex", s.simplex},
                                       {"vertex", vertex},
                                       {"found_at", s.found_at},
                                       {"radius", enclosure_json(Rad)},
                                       {"margin", margin.lower_string()}}});
  }
  long unresolved = 0;
  for (const auto& cell : R.cells) unresolved += static_cast<long>(cell.unresolved_faces.size());
  const bool all_found = R.covering_certified && D.undecided.empty();
  std::string why = !R.covering_certified ? R.reason
                    : !D.undecided.empty() ? "a vertex did not re-check in MPFI"
                    : unresolved || !R.lower_faces.empty() ? "Del_M may not be pure (a geodesic Voronoi face may hold no vertex)"
                                                           : "";
  D.complete = why.empty();
  D.reason = D.complete ? "" : "not complete: " + why;
  std::set<std::vector<int>> seen;
  for (const auto& s : candidates) {
    if (found.count(s) || !seen.insert(s).second) continue;
    if (all_found)
      D.rejected.push_back({s, {{"kind", "not_intrinsic"}, {"simplex", s}, {"by", "completeness"}}});
    else if (std::none_of(D.undecided.begin(), D.undecided.end(), [&](const IntrinsicUndecided& u) { return u.simplex == s; }))
      D.undecided.push_back({s, "no certified geodesic Voronoi vertex, and Del_M is not known completely: " + why});
  }
  std::sort(D.undecided.begin(), D.undecided.end(),
            [](const IntrinsicUndecided& a, const IntrinsicUndecided& b) { return a.simplex < b.simplex; });
  D.computed = true;
  return D;
}

}  // namespace delcert::certify::detail
