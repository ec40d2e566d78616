// Del_M on SO(3) ⊂ R^9 (metric {"type": "so3"}: x1..x9 a rotation matrix, row-major; the
// Frobenius metric, whose geodesic distance is sqrt(2) times the rotation angle), docs/design.md
// §3.9. Lifted to the double cover S^3, where geodesic balls are pairs of caps and Del_M is the
// convex hull of the lifted points modulo the antipodal map (certify/detail/sphere_hull.hpp).
//
// THE DOUBLE COVER. For a quaternion x = (w, a, b, c) in R^4 let
//   R(x) = [[w²+a²-b²-c², 2(ab-wc), 2(ac+wb)], [2(ab+wc), w²-a²+b²-c², 2(bc-wa)],
//           [2(ac-wb), 2(bc+wa), w²-a²-b²+c²]],
// quadratic in x: on S^3 it is onto SO(3), R(-x) = R(x), and for unit x, y with θ the angle of
// the rotation R(x)^T R(y): <R(x), R(y)> = tr R(x)^T R(y) = 1 + 2 cos θ = 4 (x.y)² - 1, i.e.
// cos(θ/2) = |x.y|, and
//   |R(x) - R(y)|² = 8 (1 - (x.y)²) <= 16 (1 - x.y) = 8 |x - y|²            (1 + x.y <= 2).   (1)
// For a 3 x 3 matrix p, <R(x), p> = x^T B(p) x with B(p) the symmetric 4 x 4 matrix below (linear
// in p; matching the coefficients of R's entries).
//
// THE PROJECTION. pi(p) := the nearest point of SO(3) to p. |R(x) - p|² = 3 + |p|² - 2 x^T B x for
// unit x, so pi(p) = R(q) with q a unit eigenvector of the largest eigenvalue λ1 of B = B(p),
// unique when λ1 is simple. Certified per point, all in exact rationals but one square root:
//   * h: a UNIT rational vector near q: h = -H e_0 with H = I - 2 w w^T / w^T w, w = e_0 + s v
//     (v a floating-point eigenvector, s = ±1 the sign of v_0: w_0 >= 1, no cancellation; h = s v
//     up to rounding, so q is taken with its w coordinate >= 0 unless w is about 0). H is exactly
//     orthogonal and symmetric, so C = H B H is similar to B and h (a column of H) is exactly unit.
//   * ρ = C_00 = h^T B h and |r|² = sum_{i>0} C_i0² = |B h - ρ h|² (H orthogonal).
//   * λ2(B) <= λ1(C') <= U2, C' = C without row and column 0 (Cauchy interlacing: C' is a
//     principal submatrix of C), U2 = min(Gershgorin's bound max_i C'_ii + sum_{j != i} |C'_ij|,
//     μ + sqrt(2 |C' - μ I|_F² / 3) with μ = tr C' / 3: the largest of three numbers with mean μ
//     and squared deviations summing to F is at most μ + sqrt(2F/3)).
//   * Davis-Kahan for one vector: with h = sum c_i q_i in B's eigenvectors, |r|² = sum c_i² (λ_i
//     - ρ)² >= δ² sum_{i>1} c_i² = δ² sin² ∠(h, q_1) when δ = ρ - U2 > 0 (then λ1 >= ρ > U2 >=
//     λ2: λ1 is simple). So sin ∠(h, q) <= S = |r| / δ for the eigenvector q with q.h >= 0, and
//     |q - h| = 2 sin(∠/2) <= sqrt(2) sin ∠ <= sqrt(2) S (∠ <= π/2): q_j in [h_j ± sqrt(2) S].
//   * The distance to M: |p - pi(p)|² = 3 + |p|² - 2 λ1 <= 3 + |p|² - 2 ρ (λ1 >= ρ), exactly.
// All bounds are computed in intervals under upward rounding (outward for every operation;
// overflow gives an infinite bound and no certification). A point whose λ1 is not certified
// simple, or whose enclosure is wider than 1/4, stops the engine (the reason names it).
//
// GEODESIC BALLS ARE PAIRS OF CAPS. d_M(R(z), R(y)) = sqrt(2) θ = 2 sqrt(2) min(∠(z, y), ∠(z, -y)),
// so the open geodesic ball of radius sqrt(2) α about R(z), α < π (below the injectivity radius
// sqrt(2) π), lifts to the open caps of angular radius α/2 < π/2 about z and -z. Let Q = {±q_i}
// (ids 2i and 2i + 1). An m-simplex s of P is in Del_M(pi(P)) iff for some signs the lifted
// simplex ŝ bounds such an empty cap holding no point of Q with ŝ alone on its boundary, iff ŝ is
// a facet of K = conv(Q) certified as in sphere_hull.hpp: when every other point of Q is strictly
// on one side of H(ŝ), so is -ŝ, so H(ŝ) misses the origin and the origin is on Q's side: the
// empty cap is the one not holding it, of angular radius < π/2. (H(ŝ) through the origin puts
// -ŝ on it: a tie, never certified.) A facet's antipode is a facet: Del_M(pi(P)) is the facets of
// K modulo the antipodal map, proven complete by the ridge count (sphere_hull.hpp). A candidate is
// proven NOT in Del_M only when all eight sign patterns of its lift are rejected.
//
// WHICH POINTS ARE TESTED. A point y of Q in the closed cap beyond H(ŝ) is within 2 R_ŝ of y_0
// (the circumradius R_ŝ of ŝ, as for the sphere), so by (1) |pi(p_k) - pi(p_0)| <= 4 sqrt(2) R_ŝ
// and |p_k - p_0| <= 4 sqrt(2) R_ŝ + delta_k + delta_0: only the grid's ball of that radius.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "certify/certificate.hpp"
#include "certify/intrinsic/engines.hpp"
#include "certify/detail/parallel.hpp"
#include "certify/restricted/sphere_hull.hpp"
#include "exact/interval.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {

// B(p) with <R(x), p> = x^T B x (p row-major).
Mat4 davenport(const std::array<mpq_class, 9>& p) {
  const mpq_class &p11 = p[0], &p12 = p[1], &p13 = p[2], &p21 = p[3], &p22 = p[4], &p23 = p[5], &p31 = p[6],
                  &p32 = p[7], &p33 = p[8];
  Mat4 B;
  B[0][0] = p11 + p22 + p33, B[1][1] = p11 - p22 - p33, B[2][2] = p22 - p11 - p33, B[3][3] = p33 - p11 - p22;
  B[0][1] = B[1][0] = p32 - p23, B[0][2] = B[2][0] = p13 - p31, B[0][3] = B[3][0] = p21 - p12;
  B[1][2] = B[2][1] = p12 + p21, B[1][3] = B[3][1] = p13 + p31, B[2][3] = B[3][2] = p23 + p32;
  return B;
}

// A floating-point unit eigenvector of B's largest eigenvalue: columns of (B + c I)^(2^10), c a
// Gershgorin shift making it positive semidefinite (a guess only; the bounds above certify it).
std::array<double, 4> top_eigenvector(const Mat4& B) {
  double A[4][4], c = 0;
  for (int i = 0; i < 4; ++i) {
    double row = 0;
    for (int j = 0; j < 4; ++j) row += std::abs(A[i][j] = B[i][j].get_d());
    c = std::max(c, row);
  }
  for (int i = 0; i < 4; ++i) A[i][i] += c;
  for (int k = 0; k < 10; ++k) {
    double S[4][4], mx = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        S[i][j] = 0;
        for (int l = 0; l < 4; ++l) S[i][j] += A[i][l] * A[l][j];
        mx = std::max(mx, std::abs(S[i][j]));
      }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) A[i][j] = mx > 0 ? S[i][j] / mx : 0;
  }
  int best = 0;
  double best_n = -1;
  for (int j = 0; j < 4; ++j) {
    const double n = A[0][j] * A[0][j] + A[1][j] * A[1][j] + A[2][j] * A[2][j] + A[3][j] * A[3][j];
    if (n > best_n) best_n = n, best = j;
  }
  std::array<double, 4> v{};
  const double n = std::sqrt(best_n);
  for (int i = 0; i < 4; ++i) v[i] = n > 0 ? A[i][best] / n : (i == 0);
  return v;
}

namespace {

using exact::IntervalNumber;
using nlohmann::json;


struct Lift {
  std::array<IntervalNumber, 4> q;  // encloses the unit eigenvector q (q.h >= 0)
  std::array<double, 4> approx{};   // h in doubles
  double delta = INFINITY;          // certified upper bound of |p - pi(p)|
  std::string failure;              // why not certified ("" when certified)
};

Lift lift(std::span<const double> point) {
  Lift L;
  std::array<mpq_class, 9> p;
  mpq_class norm2 = 0;
  for (int i = 0; i < 9; ++i) p[i] = exact::to_rational(point[i]), norm2 += p[i] * p[i];
  // B scaled by a power of two bringing its largest entry into [1/2, 4): exact, and it moves
  // no eigenvector and scales rho, U2 and |r| alike (S is invariant), so no magnitude of p
  // (10^-308 .. 10^308) underflows or overflows the enclosures below; rho is scaled back exactly.
  Mat4 B = davenport(p);
  mpq_class largest = 0;
  for (const auto& row : B)
    for (const auto& x : row) largest = std::max(largest, mpq_class(abs(x)));
  if (sgn(largest) == 0) {
    L.failure = "the largest eigenvalue of B(p) is not certified simple (p = 0: every rotation is nearest)";
    return L;
  }
  int exponent = 0;  // largest.get_d() is nonzero and finite or +inf (below 2^1026: |p_ij| <= DBL_MAX)
  std::frexp(std::min(largest.get_d(), 0x1p1023), &exponent);
  mpq_class scale = 1;
  if (exponent > 0) mpz_mul_2exp(scale.get_den_mpz_t(), scale.get_den_mpz_t(), exponent);
  else mpz_mul_2exp(scale.get_num_mpz_t(), scale.get_num_mpz_t(), -exponent);
  for (auto& row : B)
    for (auto& x : row) x *= scale;
  const std::array<double, 4> v = top_eigenvector(B);
  std::array<mpq_class, 4> w;
  for (int i = 0; i < 4; ++i) w[i] = exact::to_rational(v[0] < 0 ? -v[i] : v[i]);
  w[0] += 1;
  mpq_class ww = 0;
  for (const auto& x : w) ww += x * x;
  Mat4 H;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) H[i][j] = mpq_class(i == j) - 2 * w[i] * w[j] / ww;
  Mat4 HB, C;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      HB[i][j] = 0;
      for (int l = 0; l < 4; ++l) HB[i][j] += H[i][l] * B[l][j];
    }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      C[i][j] = 0;
      for (int l = 0; l < 4; ++l) C[i][j] += HB[i][l] * H[l][j];
    }
  const mpq_class& rho = C[0][0];
  const mpq_class r2 = C[1][0] * C[1][0] + C[2][0] * C[2][0] + C[3][0] * C[3][0];
  mpq_class gershgorin, mu = (C[1][1] + C[2][2] + C[3][3]) / 3, F = 0;
  for (int i = 1; i < 4; ++i) {
    mpq_class row = C[i][i];
    for (int j = 1; j < 4; ++j) {
      if (j != i) row += abs(C[i][j]);
      const mpq_class dev = C[i][j] - (i == j ? mu : mpq_class(0));
      F += dev * dev;
    }
    if (i == 1 || row > gershgorin) gershgorin = row;
  }
  exact::UpwardRounding up;
  const auto iv = [](const mpq_class& x) { return exact::to_interval_number(exact::enclose(x)); };
  const IntervalNumber samuelson = iv(mu) + exact::sqrt(iv(2 * F / 3));
  const double U2 = std::min(iv(gershgorin).sup(), samuelson.sup());
  const double delta_gap = (iv(rho) - IntervalNumber(U2)).inf();
  if (!(delta_gap > 0)) {
    L.failure = "the largest eigenvalue of B(p) is not certified simple (its nearest rotation may not be unique)";
    return L;
  }
  const double S = (exact::sqrt(iv(r2)) / IntervalNumber(delta_gap)).sup();
  const double e = (exact::sqrt(IntervalNumber(2)) * IntervalNumber(S)).sup();
  if (!(e < 0.25)) {
    L.failure = "its nearest rotation is not enclosed tightly enough (width " + std::to_string(e) + ")";
    return L;
  }
  for (int j = 0; j < 4; ++j) {
    const mpq_class hj = -H[j][0];  // -H e_0 = s v up to rounding: the quaternion with w >= 0
    L.q[j] = iv(hj) + IntervalNumber(-e, e);
    L.approx[j] = hj.get_d();
  }
  L.delta = exact::sqrt(iv(3 + norm2 - 2 * rho / scale)).sup();  // >= |p - pi(p)|^2 >= 0 (unscaled)
  if (!std::isfinite(L.delta)) L.failure = "its distance to SO(3) overflows";
  return L;
}

// det of the 4 x 4 matrix with rows y[0..4) by 2 x 2 minors (division-free: an enclosure).
IntervalNumber det4(const std::array<const IntervalNumber*, 4>& y) {
  auto m = [&](int r, int s, int a, int b) { return y[r][a] * y[s][b] - y[r][b] * y[s][a]; };
  return m(0, 1, 0, 1) * m(2, 3, 2, 3) - m(0, 1, 0, 2) * m(2, 3, 1, 3) + m(0, 1, 0, 3) * m(2, 3, 1, 2) +
         m(0, 1, 1, 2) * m(2, 3, 0, 3) - m(0, 1, 1, 3) * m(2, 3, 0, 2) + m(0, 1, 2, 3) * m(2, 3, 0, 1);
}

}  // namespace

IntrinsicDelaunay intrinsic_delaunay_so3(const io::PointSet& points, const PointGrid& grid,
                                         const std::vector<std::vector<int>>& candidates, int threads) {
  IntrinsicDelaunay D;
  D.metric = "so3";
  D.convention = "d_M(x, p) := d_M(x, pi(p)) with pi(p) the nearest rotation to p (a certified enclosure of its unit "
                 "quaternion, the top eigenvector of p's 4x4 Davenport matrix); d_M = sqrt(2) x rotation angle, so "
                 "geodesic balls lift to pairs of antipodal caps of S^3";
  D.completeness = "the certified simplices lift to facets of the convex hull of the points' quaternions +-q in R^4; "
                   "every ridge lies in exactly two of them modulo the antipodal map, so they are all its facets: all of "
                   "Del_M, pure";
  const std::size_t n = points.size();
  std::vector<Lift> lifts(n);
  parallel_for(n, threads, [&](std::size_t k, int) { lifts[k] = lift(points.point(k)); });
  double delta_max = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!lifts[k].failure.empty()) {
      D.reason = "point " + std::to_string(k) + ": " + lifts[k].failure;
      return D;
    }
    delta_max = std::max(delta_max, lifts[k].delta);
  }
  D.computed = true;
  // ids: 2k is q_k, 2k + 1 is -q_k
  std::vector<std::array<IntervalNumber, 4>> y(2 * n);
  LiftedSphere L;
  L.D = 4;
  L.count = 2 * n;
  L.approx.assign(2 * n, std::vector<double>(4));
  for (std::size_t k = 0; k < n; ++k)
    for (int j = 0; j < 4; ++j) {
      y[2 * k][j] = lifts[k].q[j], y[2 * k + 1][j] = -lifts[k].q[j];
      L.approx[2 * k][j] = lifts[k].approx[j], L.approx[2 * k + 1][j] = -lifts[k].approx[j];
    }
  L.antipode = [](int id) { return id ^ 1; };
  L.orient = [&y](const std::vector<int>& rows) {  // det [[1, y_j]] = sum_j (-1)^j det(Y without row j)
    exact::UpwardRounding up;
    IntervalNumber det(0);
    for (int j = 0; j < 5; ++j) {
      std::array<const IntervalNumber*, 4> Y;
      for (int i = 0, r = 0; i < 5; ++i)
        if (i != j) Y[r++] = y[rows[i]].data();
      det = j % 2 ? det - det4(Y) : det + det4(Y);
    }
    if (!std::isfinite(det.inf()) || !std::isfinite(det.sup())) return HullSide::unknown;
    const int s = sign_of(det);
    return s > 0 ? HullSide::positive : s < 0 ? HullSide::negative : HullSide::unknown;
  };
  L.centre_side = [&y](const std::vector<int>& facet) {  // (-1)^4 sign det(Y_s)
    exact::UpwardRounding up;
    return sign_of(det4({y[facet[0]].data(), y[facet[1]].data(), y[facet[2]].data(), y[facet[3]].data()}));
  };
  auto both_lifts = [](const std::vector<int>& ks) {
    std::vector<int> ids;
    for (int k : ks) ids.push_back(2 * k), ids.push_back(2 * k + 1);
    return ids;
  };
  L.cap = [&](const std::vector<int>& facet) {
    LiftedSphere::Cap cap;
    exact::UpwardRounding up;
    std::vector<std::vector<IntervalNumber>> a;
    for (int id : facet) a.emplace_back(y[id].begin(), y[id].end());
    const double R = circumradius_upper(a);
    if (!std::isfinite(R)) return cap;
    cap.radius = (IntervalNumber(4) * exact::sqrt(IntervalNumber(2)) * IntervalNumber(R)).sup() +
                 lifts[facet[0] / 2].delta + delta_max;  // rounded upward
    if (std::isfinite(cap.radius)) cap.ids = both_lifts(grid.ball(points.point(facet[0] / 2), cap.radius));
    return cap;
  };
  L.near = [&](const std::vector<int>& ridge, double chord) {
    return both_lifts(grid.ball(points.point(ridge[0] / 2), 2 * std::sqrt(2.0) * chord + 2 * delta_max));
  };

  // Each candidate's lifts: the sign pattern that keeps its quaternions together first, the
  // other seven only when that one is not certified.
  std::vector<std::vector<int>> unique(candidates);
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  auto lifted = [](const std::vector<int>& s, unsigned signs) {  // bit i: -q for s[i + 1]
    std::vector<int> ids{2 * s[0]};
    for (std::size_t i = 1; i < s.size(); ++i) ids.push_back(2 * s[i] + ((signs >> (i - 1)) & 1));
    return ids;
  };
  std::vector<unsigned> primary(unique.size(), 0);
  std::vector<std::vector<int>> batch;
  for (std::size_t c = 0; c < unique.size(); ++c) {
    const auto& s = unique[c];
    for (std::size_t i = 1; i < s.size(); ++i) {
      double dot = 0;
      for (int j = 0; j < 4; ++j) dot += L.approx[2 * s[0]][j] * L.approx[2 * s[i]][j];
      if (dot < 0) primary[c] |= 1u << (i - 1);
    }
    batch.push_back(lifted(s, primary[c]));
  }
  std::map<std::vector<int>, HullDecision> decided;
  decide_facets(L, batch, decided, threads);
  batch.clear();
  for (std::size_t c = 0; c < unique.size(); ++c)
    if (decided.at(canonical(L, lifted(unique[c], primary[c]))).kind != HullDecision::Kind::certified)
      for (unsigned signs = 0; signs < 8; ++signs)
        if (signs != primary[c]) batch.push_back(lifted(unique[c], signs));
  decide_facets(L, batch, decided, threads);
  const std::optional<OpenRidge> open = wrap_and_count(L, decided, threads);

  auto signed_points = [](const std::vector<int>& ids) {
    json a = json::array();
    for (int id : ids) a.push_back({id / 2, id % 2 ? -1 : 1});
    return a;
  };
  std::map<std::vector<int>, json> certified;  // point indices -> witness
  std::string twice;
  for (const auto& [ids, d] : decided) {
    if (d.kind != HullDecision::Kind::certified) continue;
    std::vector<int> s;
    for (int id : ids) s.push_back(id / 2);
    if (std::adjacent_find(s.begin(), s.end()) != s.end()) continue;  // +-q of one point: never certified
    if (certified.count(s) && twice.empty()) twice = certified[s]["simplex"].dump();
    certified[s] = {{"kind", "intrinsic_voronoi_vertex"},
                    {"simplex", s},
                    {"lift", signed_points(ids)},
                    {"points_tested", d.tested},
                    {"test_radius", std::isfinite(d.radius) ? json(num(d.radius)) : json("all points")},
                    {"detail", "every other lifted point +-q lies strictly on one side of the hyperplane through the "
                               "simplex's lifted quaternions: the cap beyond it, and its antipode, are empty, the "
                               "pair the lift of an empty geodesic ball of SO(3)"}};
  }
  for (const auto& [s, w] : certified) D.simplices.push_back({s, w});
  for (const auto& s : unique) {
    if (certified.count(s)) continue;
    json lifts_json = json::array();
    std::string why;
    for (unsigned signs = 0; signs < 8 && why.empty(); ++signs) {
      const auto ids = canonical(L, lifted(s, signs));
      const HullDecision& d = decided.at(ids);
      if (d.kind == HullDecision::Kind::rejected)
        lifts_json.push_back({{"lift", signed_points(ids)},
                              {"points_on_both_sides", signed_points({d.both_sides[0], d.both_sides[1]})}});
      else
        why = d.tie >= 0 ? "lifted point " + signed_points({d.tie})[0].dump() +
                               " is exactly on the boundary of an empty cap (a tie: not protected)"
              : d.unknown >= 0 ? "the side of lifted point " + signed_points({d.unknown})[0].dump() +
                                     " was not decided with double-precision enclosures: a possible tie, not protected"
                               : "no other point to decide the side of the empty cap";
    }
    if (why.empty())
      D.rejected.push_back({s,
                            {{"kind", "not_intrinsic"},
                             {"simplex", s},
                             {"lifts", lifts_json},
                             {"detail", "for each of the eight sign patterns of the lift, two lifted points lie "
                                        "strictly on opposite sides of the hyperplane through it: no empty cap, so no "
                                        "empty geodesic ball, passes through the simplex"}}});
    else
      D.undecided.push_back({s, why});
  }
  if (n < 3) D.reason = "fewer than 3 points";
  else if (D.simplices.empty()) D.reason = "no simplex of Del_M certified";
  else if (!twice.empty()) D.reason = "two lifts of the simplex " + twice + " are both certified: Del_M is not a simplicial complex";
  else if (open) {
    D.reason = "the certified simplices do not close up: the face " + signed_points(open->ridge).dump() +
               " (point, sign of its quaternion) lies in " + std::to_string(open->facets) + " of them (" +
               std::to_string(D.undecided.size()) + " candidate(s) undecided)";
  }
  D.complete = D.reason.empty();
  return D;
}

}  // namespace delcert::certify::detail
