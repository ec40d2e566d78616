#include "exact/simplex_predicates.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

std::vector<const double*> pointers(const std::vector<std::vector<double>>& pts) {
  std::vector<const double*> out;
  for (const auto& p : pts) out.push_back(p.data());
  return out;
}

// Applies a random signed permutation and a dyadic translation (an exact isometry).
std::vector<std::vector<double>> embed(const std::vector<std::vector<double>>& pts, int N, testing::Rng& rng) {
  std::vector<int> perm(N);
  std::iota(perm.begin(), perm.end(), 0);
  for (int i = N - 1; i > 0; --i) std::swap(perm[i], perm[rng.integer(0, i)]);
  std::vector<double> sgn(N), shift(N);
  for (int i = 0; i < N; ++i) {
    sgn[i] = rng.integer(0, 1) ? 1 : -1;
    shift[i] = rng.integer(-64, 64) / 16.0;
  }
  std::vector<std::vector<double>> out;
  for (const auto& p : pts) {
    std::vector<double> x(N, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) x[perm[i]] = sgn[perm[i]] * p[i];
    for (int i = 0; i < N; ++i) x[i] += shift[i];
    out.push_back(x);
  }
  return out;
}

void expect_thickness(const std::vector<std::vector<double>>& pts, int N, const Q& gamma2, FilterContext& ctx) {
  auto v = pointers(pts);
  const Q ref = testing::ref_thickness2(v, N);
  const int expected = testing::sign(ref - gamma2);
  FilterContext exact;
  exact.force_exact = true;
  EXPECT_EQ(thickness_sign(v, N, RationalConstant(gamma2), ctx), expected);
  EXPECT_EQ(thickness_sign(v, N, RationalConstant(gamma2), exact), expected);
  EXPECT_EQ(thickness_squared_exact(v, N), ref);
}

TEST(Thickness, RandomSimplicesMatchReference) {
  testing::Rng rng(404);
  FilterContext ctx;
  int n = 0;
  for (int N : {2, 3, 4, 6, 9}) {
    for (int j = 1; j <= std::min(N, 5); ++j) {
      for (int t = 0; t < 60; ++t) {
        std::vector<std::vector<double>> pts(j + 1, std::vector<double>(N));
        for (auto& p : pts)
          for (auto& x : p) x = rng.normal();
        const Q ref = testing::ref_thickness2(pointers(pts), N);
        // thresholds: random, exactly at the value, and just around it
        expect_thickness(pts, N, Q(rng.integer(0, 1000), 4000), ctx);
        expect_thickness(pts, N, ref, ctx);
        expect_thickness(pts, N, ref + Q(1, mpz_class(1) << 150), ctx);
        if (ref > 0) expect_thickness(pts, N, ref - Q(1, mpz_class(1) << 150), ctx);
        n += 4;
      }
    }
  }
  EXPECT_GT(n, 3000);
  const auto& c = ctx.stats[PredicateKind::thickness];
  EXPECT_GT(c.calls, 0u);
}

TEST(Thickness, FilterDecidesRandomInput) {
  testing::Rng rng(405);
  FilterContext ctx;
  for (int t = 0; t < 2000; ++t) {
    std::vector<std::vector<double>> pts(4, std::vector<double>(9));
    for (auto& p : pts)
      for (auto& x : p) x = rng.normal();
    thickness_sign(pointers(pts), 9, RationalConstant(Q(1, 100)), ctx);
  }
  const auto& c = ctx.stats[PredicateKind::thickness];
  EXPECT_EQ(c.calls, 2000u);
  EXPECT_LE(c.filter_failures, 5u);
}

TEST(Thickness, KnownValues) {
  FilterContext ctx;
  testing::Rng rng(1);
  // Right triangle with legs a, b: Upsilon = ab / (2 (a^2 + b^2)).
  for (auto [a, b] : {std::pair{1.0, 1.0}, std::pair{2.0, 1.0}, std::pair{0.75, 0.5}, std::pair{3.0, 0.125}}) {
    const Q ups = Q(to_rational(a) * to_rational(b)) / (2 * (to_rational(a) * to_rational(a) + to_rational(b) * to_rational(b)));
    for (int N : {2, 3, 5, 9}) {
      auto pts = embed({{0, 0}, {a, 0}, {0, b}}, N, rng);
      EXPECT_EQ(thickness_squared_exact(pointers(pts), N), ups * ups);
      EXPECT_EQ(thickness_sign(pointers(pts), N, RationalConstant(ups * ups), ctx), 0);
      EXPECT_EQ(thickness_sign(pointers(pts), N, RationalConstant(ups * ups * Q(101, 100)), ctx), -1);
      EXPECT_EQ(thickness_sign(pointers(pts), N, RationalConstant(ups * ups * Q(99, 100)), ctx), 1);
    }
  }
  // Orthogonal corner (0, a e1, b e2, c e3): D(0)^2 = 1 / (1/a^2 + 1/b^2 + 1/c^2).
  {
    const double a = 1, b = 2, c = 2;
    const Q d0 = 1 / (Q(1) / (a * a) + Q(1) / (b * b) + Q(1) / (c * c));
    const Q delta2 = Q(b * b + c * c);
    const Q ups2 = std::min({d0, Q(a * a), Q(b * b), Q(c * c)}) / (9 * delta2);
    auto pts = embed({{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}}, 6, rng);
    EXPECT_EQ(thickness_squared_exact(pointers(pts), 6), ups2);
    EXPECT_EQ(thickness_sign(pointers(pts), 6, RationalConstant(ups2), ctx), 0);
  }
  // A single vertex has Upsilon = 1; an edge has Upsilon = 1.
  std::vector<std::vector<double>> v{{0.5, 0.25}};
  EXPECT_EQ(thickness_sign(pointers(v), 2, RationalConstant(Q(1)), ctx), 0);
  EXPECT_EQ(thickness_sign(pointers(v), 2, RationalConstant(Q(1, 2)), ctx), 1);
  std::vector<std::vector<double>> e{{0.5, 0.25}, {1, 3}};
  EXPECT_EQ(thickness_sign(pointers(e), 2, RationalConstant(Q(1)), ctx), 0);
  EXPECT_EQ(thickness_sign(pointers(e), 2, RationalConstant(Q(2)), ctx), -1);
}

TEST(Thickness, DegenerateSimplices) {
  FilterContext ctx;
  testing::Rng rng(2);
  // collinear triangle, coplanar tetrahedron, repeated vertices, all vertices equal, a
  // 3-simplex whose four vertices are collinear (every facet degenerate too).
  const std::vector<std::vector<std::vector<double>>> shapes{
      {{0, 0}, {1, 1}, {3, 3}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.75, 0}},
      {{1, 2, 3}, {1, 2, 3}, {0, 1, 0}},
      {{1, 1}, {1, 1}, {1, 1}},
      {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {-0.5, -0.5, -0.5}},
      {{0.1, 0.2}, {0.1, 0.2}},
  };
  for (const auto& s : shapes) {
    for (int N : {3, 4, 7}) {
      auto pts = embed(s, N, rng);
      EXPECT_EQ(thickness_squared_exact(pointers(pts), N), 0);
      EXPECT_EQ(thickness_sign(pointers(pts), N, RationalConstant(Q(1, 1000)), ctx), -1);
      EXPECT_EQ(thickness_sign(pointers(pts), N, RationalConstant(Q(0)), ctx), 0);
      expect_thickness(pts, N, Q(1, 7), ctx);
    }
  }
  EXPECT_THROW(thickness_sign(std::vector<const double*>{}, 3, RationalConstant(Q(0)), ctx), std::invalid_argument);
  std::vector<std::vector<double>> tri{{0, 0}, {1, 0}, {0, 1}};
  EXPECT_THROW(thickness_sign(pointers(tri), 2, RationalConstant(Q(-1)), ctx), std::invalid_argument);
}

TEST(SquaredDistance, RandomAndTies) {
  testing::Rng rng(8);
  FilterContext ctx, exact;
  exact.force_exact = true;
  for (int t = 0; t < 3000; ++t) {
    const int N = rng.integer(1, 9);
    std::vector<std::vector<double>> p(4, std::vector<double>(N));
    for (auto& x : p)
      for (auto& v : x) v = (t % 3 == 0) ? rng.integer(-4, 4) * 0.25 : rng.normal();
    if (t % 5 == 0) p[3] = p[2], p[2] = p[0];  // |a-b| vs |a-d'|, often ties with small integers
    const Q ab = squared_distance_exact(p[0].data(), p[1].data(), N);
    const Q cd = squared_distance_exact(p[2].data(), p[3].data(), N);
    Q ref_ab = 0;
    for (int i = 0; i < N; ++i) ref_ab += (to_rational(p[0][i]) - to_rational(p[1][i])) * (to_rational(p[0][i]) - to_rational(p[1][i]));
    EXPECT_EQ(ab, ref_ab);
    const int e = testing::sign(ab - cd);
    EXPECT_EQ(compare_squared_distances(p[0].data(), p[1].data(), p[2].data(), p[3].data(), N, ctx), e);
    EXPECT_EQ(compare_squared_distances(p[0].data(), p[1].data(), p[2].data(), p[3].data(), N, exact), e);
    const Q r2(rng.integer(0, 100), rng.integer(1, 30));
    EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(r2), N, ctx), testing::sign(ab - r2));
    EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(ab), N, ctx), 0);
    EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(ab), N, exact), 0);
    EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(-r2 - 1), N, exact), 1);
    EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(ab + r2 + 1), N, exact), -1);
  }
  EXPECT_GT(ctx.stats[PredicateKind::squared_distance].zero_results, 0u);
}

// Tiny coordinates (squares underflow into subnormals or to zero) and huge ones (squares
// overflow): the floating-point fast path of the filter must stay an enclosure or step aside.
TEST(SquaredDistance, ExtremeMagnitudes) {
  testing::Rng rng(9);
  FilterContext ctx;
  for (int e : {-560, -540, -530, -520, -500, 0, 490, 505, 511, 515}) {
    for (int t = 0; t < 300; ++t) {
      const int N = rng.integer(1, 9);
      std::vector<std::vector<double>> p(4, std::vector<double>(N));
      for (auto& x : p)
        for (auto& v : x) v = std::ldexp(rng.integer(-8, 8) + (t % 2 ? rng.normal() : 0.0), e);
      const Q ab = squared_distance_exact(p[0].data(), p[1].data(), N);
      const Q cd = squared_distance_exact(p[2].data(), p[3].data(), N);
      EXPECT_EQ(compare_squared_distances(p[0].data(), p[1].data(), p[2].data(), p[3].data(), N, ctx),
                testing::sign(ab - cd));
      EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(ab), N, ctx), 0);
      EXPECT_EQ(compare_squared_distance(p[0].data(), p[1].data(), RationalConstant(cd), N, ctx), testing::sign(ab - cd));
      if (N >= 2) {
        std::vector<std::vector<double>> tri(p.begin(), p.begin() + 3);
        const Q ref = testing::ref_thickness2(pointers(tri), N);
        EXPECT_EQ(thickness_sign(pointers(tri), N, RationalConstant(Q(1, 50)), ctx), testing::sign(ref - Q(1, 50)));
      }
    }
  }
}

TEST(AmbientPower, RationalCentreAndBoxes) {
  testing::Rng rng(12);
  FilterContext ctx, exact;
  exact.force_exact = true;
  for (int t = 0; t < 3000; ++t) {
    const int N = rng.integer(2, 9);
    std::vector<double> p(N), q(N);
    std::vector<Q> x(N);
    for (int i = 0; i < N; ++i) {
      p[i] = rng.normal();
      q[i] = rng.normal();
      x[i] = Q(rng.integer(-1000, 1000), rng.integer(1, 97));
    }
    if (t % 4 == 0) {
      // x on the bisector of p and q: the midpoint plus a vector orthogonal to q - p.
      for (int i = 0; i < N; ++i) x[i] = (to_rational(p[i]) + to_rational(q[i])) / 2;
      const int a = rng.integer(0, N - 1), b = (a + 1) % N;
      const Q s(rng.integer(1, 9), 7);
      x[a] += s * (to_rational(q[b]) - to_rational(p[b]));
      x[b] -= s * (to_rational(q[a]) - to_rational(p[a]));
    }
    Q ref = 0;
    for (int i = 0; i < N; ++i) {
      ref += (x[i] - to_rational(q[i])) * (x[i] - to_rational(q[i]));
      ref -= (x[i] - to_rational(p[i])) * (x[i] - to_rational(p[i]));
    }
    RationalPoint X(x);
    EXPECT_EQ(ambient_power_sign(X, p.data(), q.data(), ctx), testing::sign(ref));
    EXPECT_EQ(ambient_power_sign(X, p.data(), q.data(), exact), testing::sign(ref));
    if (t % 4 == 0) {
      EXPECT_EQ(testing::sign(ref), 0);
    }
    // A small box around x decides the same sign when it does decide.
    Box box;
    for (const auto& e : X.enclosure()) box.push_back({e.lo - 1e-9, e.hi + 1e-9});
    const int b = ambient_power_sign_on_box(box, p.data(), q.data());
    if (b != 0) {
      EXPECT_EQ(b, testing::sign(ref));
    }
    if (ref > Q(1, 1000) || ref < Q(-1, 1000)) {
      EXPECT_EQ(b, testing::sign(ref));
    }
  }
  EXPECT_GT(ctx.stats[PredicateKind::ambient_power].filter_failures, 0u);
}

}  // namespace
}  // namespace delcert::exact
