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
#include "certify/detail/intrinsic_engines.hpp"
#include "certify/detail/parallel.hpp"
#include "exact/enclosure.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {

namespace {

using exact::IntervalNumber;
using nlohmann::json;

// det of the k x k matrix rows[0..k) (each a pointer to k entries), by Laplace expansion along
// the first column (k <= 6 here: at most 720 products). Division-free, so the same code is exact
// for mpq_class and an enclosure for IntervalNumber.
template <class T>
T laplace(std::vector<const T*>& rows, int col, int k) {
  if (k == 1) return rows[0][col];
  T sum(0);
  for (int j = 0; j < k; ++j) {
    std::vector<const T*> minor;
    for (int i = 0; i < k; ++i)
      if (i != j) minor.push_back(rows[i]);
    T d = rows[j][col] * laplace(minor, col + 1, k - 1);
    if (j % 2) sum -= d;
    else sum += d;
  }
  return sum;
}

enum class Side { positive, negative, zero, unknown };

int sign_of(const IntervalNumber& x) { return x.inf() > 0 ? 1 : x.sup() < 0 ? -1 : 0; }

struct Sphere {
  int N = 0;
  mpq_class r;
  std::vector<std::vector<mpq_class>> u;        // exact p - c, per point
  std::vector<mpq_class> s;                     // |u|^2 exact
  std::vector<std::vector<IntervalNumber>> ui;  // enclosures of u
  std::vector<IntervalNumber> ni;               // enclosures of |u|

  // orient(rows[0..N), q) as explained above; rows[N] is the tested point.
  Side orient(const std::vector<int>& idx) const {
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
        if (sg) return sg > 0 ? Side::positive : Side::negative;
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
    if (live.empty()) return Side::zero;
    if (live.size() == 1) return sgn(live[0].second) > 0 ? Side::positive : Side::negative;
    for (int precision : {256, 2048, 16384}) {
      exact::Enclosure sum(0L, precision);
      for (const auto& [rad, coef] : live) sum = sum + exact::Enclosure(coef, precision) * sqrt(exact::Enclosure(rad, precision));
      if (sum.is_positive()) return Side::positive;
      if (sum.is_negative()) return Side::negative;
    }
    return Side::unknown;
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
    const int k = N - 1;  // m: the simplex's dimension
    const exact::Interval re = exact::enclose(r);
    const IntervalNumber R(re.lo, re.hi);
    std::vector<std::vector<IntervalNumber>> a(N, std::vector<IntervalNumber>(N));
    for (int j = 0; j < N; ++j)
      for (int v = 0; v < N; ++v) a[j][v] = R * ui[simplex[j]][v] / ni[simplex[j]];
    std::vector<std::vector<IntervalNumber>> e(k, std::vector<IntervalNumber>(N));
    for (int j = 0; j < k; ++j)
      for (int v = 0; v < N; ++v) e[j][v] = a[j + 1][v] - a[0][v];
    std::vector<std::vector<IntervalNumber>> G(k, std::vector<IntervalNumber>(k));
    std::vector<IntervalNumber> b(k);
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        IntervalNumber d(0);
        for (int v = 0; v < N; ++v) d += e[i][v] * e[j][v];
        G[i][j] = d;
      }
      b[i] = G[i][i] / 2;
    }
    std::vector<const IntervalNumber*> rows;
    for (auto& g : G) rows.push_back(g.data());
    const IntervalNumber D = laplace(rows, 0, k);
    if (!(D.inf() > 0)) return INFINITY;  // a Gram determinant is >= 0; not bounded away from 0
    std::vector<IntervalNumber> o(N, IntervalNumber(0));
    for (int j = 0; j < k; ++j) {  // Cramer: lambda_j = det(G with column j replaced by b) / D
      std::vector<std::vector<IntervalNumber>> Gj = G;
      for (int i = 0; i < k; ++i) Gj[i][j] = b[i];
      std::vector<const IntervalNumber*> rj;
      for (auto& g : Gj) rj.push_back(g.data());
      const IntervalNumber lambda = laplace(rj, 0, k) / D;
      for (int v = 0; v < N; ++v) o[v] += lambda * e[j][v];
    }
    IntervalNumber r2(0);
    for (int v = 0; v < N; ++v) r2 += exact::square(o[v]);
    const double bound = exact::sqrt(r2).sup();
    return std::isfinite(bound) ? bound : INFINITY;
  }
};

struct Decision {
  enum class Kind { certified, rejected, undecided } kind = Kind::undecided;
  json witness;
  std::string reason;
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
  std::vector<std::vector<int>> unique(candidates);
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());

  auto decide = [&](const std::vector<int>& simplex) {
    Decision d;
    const int cside = S.centre_side(simplex);
    double rho = INFINITY;
    if (cside != 0) {
      const double R = S.circumradius_upper(simplex);
      exact::UpwardRounding up;
      rho = 2 * R + delta[simplex[0]] + delta_max;  // each operation rounded upward
    }
    std::vector<int> tested;
    if (std::isfinite(rho)) tested = grid.ball(points.point(simplex[0]), rho);
    else
      for (std::size_t q = 0; q < n; ++q) tested.push_back(static_cast<int>(q));
    const std::set<int> in_simplex(simplex.begin(), simplex.end());
    int first[2] = {-1, -1};  // a point strictly on the positive / negative side
    int tie = -1, unknown = -1;
    long count = 0;
    std::vector<int> idx(simplex);
    idx.push_back(-1);
    for (int q : tested) {
      if (in_simplex.count(q)) continue;
      ++count;
      idx[N] = q;
      const Side side = S.orient(idx);
      if (side == Side::positive && first[0] < 0) first[0] = q;
      if (side == Side::negative && first[1] < 0) first[1] = q;
      if (side == Side::zero && tie < 0) tie = q;
      if (side == Side::unknown && unknown < 0) unknown = q;
    }
    int outside = -1;  // a point not tested: strictly on the centre's side (proof above)
    if (std::isfinite(rho) && tested.size() < n) {
      std::size_t t = 0;
      for (int q = 0; q < static_cast<int>(n); ++q) {
        while (t < tested.size() && tested[t] < q) ++t;
        if ((t < tested.size() && tested[t] == q) || in_simplex.count(q)) continue;
        outside = q;
        break;
      }
      if (outside >= 0 && first[cside > 0 ? 0 : 1] < 0) first[cside > 0 ? 0 : 1] = outside;
    }
    if (first[0] >= 0 && first[1] >= 0) {
      d.kind = Decision::Kind::rejected;
      d.witness = {{"kind", "not_intrinsic"},
                   {"simplex", simplex},
                   {"points_on_both_sides", {first[0], first[1]}},
                   {"detail", "the two points' projections lie strictly on opposite sides of the hyperplane through the "
                              "simplex's projected points, so each cap bounded by it (each geodesic ball through the "
                              "simplex) holds one of them"}};
      if (first[0] == outside || first[1] == outside) d.witness["untested_point"] = outside;
    } else if (tie >= 0 || unknown >= 0) {
      d.reason = tie >= 0 ? "point " + std::to_string(tie) +
                                " is exactly on the boundary of the simplex's geodesic ball (a tie: not protected)"
                          : "the side of point " + std::to_string(unknown) +
                                " was not decided (at 16384 bits): a possible tie, not protected";
    } else if (count + (outside >= 0 ? 1 : 0) == 0) {
      d.reason = "no other point to decide the side of the empty cap";
    } else {
      const bool empty_small = cside != 0 && ((cside > 0) == (first[0] >= 0));
      d.kind = Decision::Kind::certified;
      d.witness = {{"kind", "intrinsic_voronoi_vertex"},
                   {"simplex", simplex},
                   {"empty_cap", cside == 0 ? "a hemisphere" : empty_small ? "the one not holding the centre"
                                                                          : "the one holding the centre"},
                   {"points_tested", count},
                   {"test_radius", std::isfinite(rho) ? json(num(rho)) : json("all points")},
                   {"detail", "every other projected point lies strictly on one side of the hyperplane through the "
                              "simplex's projected points: the cap on the other side is an empty geodesic ball, its "
                              "pole the intrinsic Voronoi vertex"}};
    }
    return d;
  };
  std::map<std::vector<int>, Decision> decided;
  auto decide_all = [&](const std::vector<std::vector<int>>& batch) {
    std::vector<Decision> out(batch.size());
    parallel_for(batch.size(), threads, [&](std::size_t k, int) { out[k] = decide(batch[k]); });
    for (std::size_t k = 0; k < batch.size(); ++k) decided.emplace(batch[k], std::move(out[k]));
  };
  decide_all(unique);

  // GIFT WRAPPING. The candidates may miss facets (their sources are other complexes). Across a
  // ridge that lies in one certified facet f = ridge + {a} only, the hull's other facet is
  // ridge + {q} for the q whose hyperplane leaves every point on a's side: found in floating point
  // (Jarvis's rule on the normalised points near the ridge), then DECIDED like any candidate. The
  // floating-point search only proposes; nothing it computes is trusted. Rounds until no new
  // candidate appears (each round decides at most one new candidate per open ridge).
  std::vector<std::vector<double>> x(n, std::vector<double>(N));  // normalised projections, approximate
  for (std::size_t q = 0; q < n; ++q) {
    double nn = 0;
    for (int v = 0; v < N; ++v) nn += std::pow(points.point(q)[v] - metric.center[v].get_d(), 2);
    nn = std::sqrt(nn);
    for (int v = 0; v < N; ++v) x[q][v] = (points.point(q)[v] - metric.center[v].get_d()) / nn;
  }
  auto orient_f = [&](const std::vector<int>& rows) {  // sign of det [[1, x_j]] in doubles
    std::vector<std::vector<double>> a(N + 1, std::vector<double>(N + 1, 1.0));
    for (int j = 0; j <= N; ++j)
      for (int v = 0; v < N; ++v) a[j][v + 1] = x[rows[j]][v];
    std::vector<const double*> r;
    for (auto& row : a) r.push_back(row.data());
    const double det = laplace(r, 0, N + 1);
    return det > 0 ? 1 : det < 0 ? -1 : 0;
  };
  for (int round = 0; round < 64; ++round) {
    std::map<std::vector<int>, std::vector<int>> count;  // ridge -> opposite vertices in certified facets
    for (const auto& [simplex, d] : decided) {
      if (d.kind != Decision::Kind::certified) continue;
      for (std::size_t drop = 0; drop < simplex.size(); ++drop) {
        std::vector<int> r;
        for (std::size_t i = 0; i < simplex.size(); ++i)
          if (i != drop) r.push_back(simplex[i]);
        count[r].push_back(simplex[drop]);
      }
    }
    std::set<std::vector<int>> fresh;
    for (const auto& [ridge, opposite] : count) {
      if (opposite.size() != 1) continue;
      const int a = opposite[0];
      double reach = 0;  // the facet's diameter on the unit sphere (approximate: it only sizes the search)
      std::vector<int> facet(ridge);
      facet.push_back(a);
      for (int i : facet)
        for (int j : facet) {
          double d2 = 0;
          for (int v = 0; v < N; ++v) d2 += (x[i][v] - x[j][v]) * (x[i][v] - x[j][v]);
          reach = std::max(reach, std::sqrt(d2));
        }
      int q = -1;
      for (double radius = 2 * reach * metric.radius.get_d(); q < 0 && radius < 8 * metric.radius.get_d(); radius *= 2) {
        std::vector<int> near = grid.ball(points.point(ridge[0]), radius + 2 * delta_max);
        std::vector<int> rows(ridge);
        rows.push_back(-1), rows.push_back(-1);
        for (int r : near) {
          if (r == a || std::count(ridge.begin(), ridge.end(), r)) continue;
          if (q < 0) {
            q = r;
            continue;
          }
          rows[N - 1] = q, rows[N] = a;
          const int sa = orient_f(rows);
          rows[N] = r;
          if (sa != 0 && orient_f(rows) == -sa) q = r;  // r beyond the plane through ridge + q: turn to it
        }
        if (q >= 0) {
          std::vector<int> rows2(ridge);
          rows2.push_back(q), rows2.push_back(a);
          if (orient_f(rows2) == 0) q = -1;
        }
      }
      if (q < 0) continue;
      std::vector<int> candidate(ridge);
      candidate.push_back(q);
      std::sort(candidate.begin(), candidate.end());
      if (!decided.count(candidate)) fresh.insert(candidate);
    }
    if (fresh.empty()) break;
    decide_all(std::vector<std::vector<int>>(fresh.begin(), fresh.end()));
  }

  std::map<std::vector<int>, int> ridges;
  for (const auto& [simplex, d] : decided) {
    if (d.kind == Decision::Kind::certified) {
      D.simplices.push_back({simplex, d.witness});
      for (std::size_t drop = 0; drop < simplex.size(); ++drop) {
        std::vector<int> r;
        for (std::size_t i = 0; i < simplex.size(); ++i)
          if (i != drop) r.push_back(simplex[i]);
        ++ridges[r];
      }
    } else if (d.kind == Decision::Kind::rejected) {
      D.rejected.push_back({simplex, d.witness});
    } else {
      D.undecided.push_back({simplex, d.reason});
    }
  }
  const auto open = std::find_if(ridges.begin(), ridges.end(), [](const auto& r) { return r.second != 2; });
  if (n < static_cast<std::size_t>(N) + 1) D.reason = "fewer than N + 1 points";
  else if (D.simplices.empty()) D.reason = "no simplex of Del_M certified";
  else if (open != ridges.end()) {
    std::string face;
    for (int v : open->first) face += (face.empty() ? "" : ",") + std::to_string(v);
    D.reason = "the certified simplices do not close up: the face {" + face + "} lies in " +
               std::to_string(open->second) + " of them (" + std::to_string(D.undecided.size()) +
               " candidate(s) undecided)";
  }
  D.complete = D.reason.empty();
  return D;
}

}  // namespace delcert::certify::detail
