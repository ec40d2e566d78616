#include "exact/tangent_predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "exact/interval.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

std::vector<const double*> pointers(const std::vector<std::vector<double>>& pts) {
  std::vector<const double*> out;
  for (const auto& p : pts) out.push_back(p.data());
  return out;
}

// Checks one cell of a chart against the brute-force reference and the exact-only evaluation,
// for every query in `queries` (local indices). Returns the number of checks.
int check_cell(const TangentChart& chart, const std::vector<int>& verts, const std::vector<int>& queries,
               FilterContext& ctx, testing::Rng& rng) {
  const TangentSpace& T = chart.space();
  FilterContext exact_ctx;
  exact_ctx.force_exact = true;
  std::vector<const double*> cell_pts;
  for (int v : verts) cell_pts.push_back(chart.coordinates(v).data());

  const int ref_orient = testing::ref_orientation(T, cell_pts);
  EXPECT_EQ(chart.orientation(verts, ctx), ref_orient);
  EXPECT_EQ(chart.orientation(verts, exact_ctx), ref_orient);
  EXPECT_EQ(tangent_orientation(T, cell_pts, ctx), ref_orient);
  const TangentCell cell = chart.cell(verts, ctx);
  const TangentCell exact_cell = chart.cell(verts, exact_ctx);
  EXPECT_EQ(cell.orientation(), ref_orient);
  EXPECT_EQ(exact_cell.orientation(), ref_orient);
  EXPECT_EQ(cell.degenerate(), ref_orient == 0);

  auto zc = testing::ref_centre(T, cell_pts);
  EXPECT_EQ(zc.has_value(), ref_orient != 0);
  if (zc) {
    // centre_exact is p + U zc, and R^2 (ambient) equals the weighted power of the projections
    // (the claim of docs/design.md §3.2 that CGAL's weights -|q - q'|^2 give ambient distances).
    auto c = cell.centre_exact();
    const auto p = T.point();
    for (int i = 0; i < T.ambient_dimension(); ++i) {
      Q ci = to_rational(p[i]);
      for (int a = 0; a < T.intrinsic_dimension(); ++a) ci += T.basis(i, a) * (*zc)[a];
      EXPECT_EQ(c[i], ci);
    }
    const Q r2 = cell.squared_radius_exact();
    for (const double* v : cell_pts) {
      EXPECT_EQ(testing::weighted_power(T, *zc, testing::project(T, v)), r2);
      Q d = 0;
      for (int i = 0; i < T.ambient_dimension(); ++i) d += (c[i] - to_rational(v[i])) * (c[i] - to_rational(v[i]));
      EXPECT_EQ(d, r2);
    }
  }
  int checks = 0;
  for (int q : queries) {
    const double* qp = chart.coordinates(q).data();
    auto ref = testing::ref_power(T, cell_pts, qp);
    const int expected = ref ? testing::sign(*ref) : 0;
    EXPECT_EQ(cell.power_sign(q, ctx), expected);
    EXPECT_EQ(exact_cell.power_sign(q, exact_ctx), expected);
    EXPECT_EQ(chart.power_sign(verts, q, ctx), expected);
    EXPECT_EQ(tangent_power_sign(T, cell_pts, qp, ctx), expected);
    EXPECT_EQ(tangent_power_sign(T, cell_pts, qp, exact_ctx), expected);
    if (ref) {
      EXPECT_EQ(cell.power_exact(q), *ref);
      // Thresholds: exactly at the value (0), a random rational, and just around the value.
      const RationalConstant at(*ref);
      EXPECT_EQ(cell.power_sign(q, at, ctx), 0);
      EXPECT_EQ(exact_cell.power_sign(q, at, exact_ctx), 0);
      EXPECT_EQ(tangent_power_sign(T, cell_pts, qp, at, ctx), 0);
      const Q tiny(1, mpz_class(1) << 200);
      EXPECT_EQ(cell.power_sign(q, RationalConstant(*ref - tiny), ctx), 1);
      EXPECT_EQ(cell.power_sign(q, RationalConstant(*ref + tiny), ctx), -1);
      const Q delta(rng.integer(0, 2000), rng.integer(1, 1000) * 1000);
      const int e = testing::sign(*ref - delta);
      EXPECT_EQ(cell.power_sign(q, RationalConstant(delta), ctx), e);
      EXPECT_EQ(exact_cell.power_sign(q, RationalConstant(delta), exact_ctx), e);
      EXPECT_EQ(tangent_power_sign(T, cell_pts, qp, RationalConstant(delta), ctx), e);
      // Negative thresholds exercise signed integer conversions on the exact path.
      const Q neg = -delta - Q(1, 3);
      EXPECT_EQ(exact_cell.power_sign(q, RationalConstant(neg), exact_ctx), testing::sign(*ref - neg));
      EXPECT_EQ(tangent_power_sign(T, cell_pts, qp, RationalConstant(neg), exact_ctx), testing::sign(*ref - neg));
    } else {
      EXPECT_EQ(cell.power_sign(q, RationalConstant(Q(1, 10)), ctx), 0);
      EXPECT_THROW((void)cell.power_exact(q), std::domain_error);
    }
    ++checks;
  }
  return checks;
}

TEST(TangentPredicates, SignConventionOnASphere) {
  // p = (0,0,1): T_p is the plane z = 1, U = (2 e1, 2 e2). Cell p, (1,0,1), (0,1,1): centre
  // (1/2, 1/2, 1), R^2 = 1/2.
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> p{0, 0, 1};
  TangentSpace T(F, p);
  const std::vector<std::vector<double>> pts{{1, 0, 1},     {0, 1, 1}, {0.5, 0.5, 1}, {2, 2, 1},
                                             {1, 1, 1},     {0.5, 0.5, 1.5}, {0.5, 0.5, 2}};
  TangentChart chart(T, pointers(pts));
  FilterContext ctx;
  const std::vector<int> verts{0, 1, 2};
  TangentCell cell = chart.cell(verts, ctx);
  EXPECT_FALSE(cell.degenerate());
  EXPECT_EQ(cell.power_sign(3, ctx), -1);  // the centre itself: inside
  EXPECT_EQ(cell.power_sign(4, ctx), 1);   // far away in the plane
  EXPECT_EQ(cell.power_sign(5, ctx), 0);   // on the circle
  EXPECT_EQ(cell.power_sign(6, ctx), -1);  // |c - q|^2 = 1/4 < 1/2
  EXPECT_EQ(cell.power_sign(7, ctx), 1);   // |c - q|^2 = 1 > 1/2
  EXPECT_EQ(cell.power_sign(7, RationalConstant(Q(1, 2)), ctx), 0);
  EXPECT_EQ(cell.power_sign(7, RationalConstant(Q(49, 100)), ctx), 1);
  EXPECT_EQ(cell.power_sign(7, RationalConstant(Q(51, 100)), ctx), -1);
  EXPECT_EQ(cell.squared_radius_exact(), Q(1, 2));
  EXPECT_EQ(cell.power_exact(7), Q(1, 2));
  auto c = cell.centre_exact();
  EXPECT_EQ(c, (std::vector<Q>{Q(1, 2), Q(1, 2), Q(1)}));
  // Orientation in the basis U = (2 e1, 2 e2): (p, (1,0,1), (0,1,1)) is counter-clockwise.
  EXPECT_EQ(cell.orientation(), 1);
  EXPECT_EQ(chart.orientation(std::vector<int>{0, 2, 1}, ctx), -1);
  EXPECT_EQ(chart.orientation(std::vector<int>{1, 0, 2}, ctx), -1);
  EXPECT_EQ(chart.orientation(std::vector<int>{1, 2, 0}, ctx), 1);
  // Braced lists work too.
  EXPECT_EQ(chart.orientation({1, 2, 0}, ctx), 1);
  EXPECT_EQ(chart.cell({0, 1, 2}, ctx).power_sign(3, ctx), -1);
  EXPECT_EQ(chart.power_sign({0, 1, 2}, 4, ctx), 1);
  EXPECT_TRUE(rounding_is_nearest());
}

TEST(TangentPredicates, RandomInputsMatchReferenceOnAllManifolds) {
  testing::Rng rng(20240601);
  int total = 0;
  for (const auto& M : testing::test_manifolds()) {
    SCOPED_TRACE(M.name);
    ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    FilterContext ctx;
    for (int trial = 0; trial < 8; ++trial) {
      auto p = testing::sample_near(M, rng);
      TangentSpace T(F, p);
      std::vector<std::vector<double>> nbrs;
      const double h = rng.uniform(0.05, 0.4);
      for (int i = 0; i < 10; ++i) {
        auto q = p;
        for (auto& v : q) v += h * rng.normal();
        nbrs.push_back(q);
      }
      TangentChart chart(T, pointers(nbrs));
      for (int c = 0; c < 12; ++c) {
        std::vector<int> ids(chart.size());
        std::iota(ids.begin(), ids.end(), 0);
        for (int i = 0; i <= M.m; ++i) std::swap(ids[i], ids[i + rng.integer(0, chart.size() - 1 - i)]);
        std::vector<int> verts(ids.begin(), ids.begin() + M.m + 1);
        if (c % 2 == 0 && std::find(verts.begin(), verts.end(), 0) == verts.end()) verts[rng.integer(0, M.m)] = 0;
        std::vector<int> queries(ids.begin() + M.m + 1, ids.begin() + std::min<int>(M.m + 5, chart.size()));
        total += check_cell(chart, verts, queries, ctx, rng);
      }
    }
    // Random input: the interval filter decides (almost) everything.
    const auto& pw = ctx.stats[PredicateKind::power];
    EXPECT_GT(pw.calls, 0u);
    EXPECT_LE(pw.filter_failures * 50, pw.calls) << "power filter failures " << pw.filter_failures << " / " << pw.calls;
  }
  EXPECT_GT(total, 2000);
}

// Points exactly on a common ambient sphere around a centre c in T_p: c = p + a with a = U z,
// vertices and queries c + sigma(a) for signed permutations sigma (|sigma(a)| = |a|). Every
// query on the sphere has power exactly 0; perturbed queries are decided exactly.
TEST(TangentPredicates, CosphericalSignedPermutations) {
  testing::Rng rng(77);
  int zeros = 0, nonzero = 0;
  for (const auto& M : testing::test_manifolds()) {
    if (!M.quadratic_form) continue;
    SCOPED_TRACE(M.name);
    ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    FilterContext ctx;
    for (int trial = 0; trial < 10; ++trial) {
      std::vector<double> p(M.N);
      for (auto& v : p) v = rng.integer(-3, 3);
      std::optional<TangentSpace> T;
      try {
        T.emplace(F, p);
      } catch (const std::domain_error&) {
        continue;  // singular point of F
      }
      // a = U z: an integer vector (p integer => U integer).
      std::vector<double> a(M.N, 0.0);
      bool zero = true;
      while (zero) {
        std::vector<int> z(M.m);
        for (auto& v : z) v = rng.integer(-2, 2);
        for (int i = 0; i < M.N; ++i) {
          Q s = 0;
          for (int k = 0; k < M.m; ++k) s += T->basis(i, k) * z[k];
          ASSERT_EQ(s.get_den(), 1);
          a[i] = s.get_d();
          if (s != 0) zero = false;
        }
      }
      std::vector<double> c(M.N);
      for (int i = 0; i < M.N; ++i) c[i] = p[i] + a[i];  // exact: small integers
      auto signed_perm = [&] {
        std::vector<int> perm(M.N);
        std::iota(perm.begin(), perm.end(), 0);
        for (int i = M.N - 1; i > 0; --i) std::swap(perm[i], perm[rng.integer(0, i)]);
        std::vector<double> x(M.N);
        for (int i = 0; i < M.N; ++i) x[i] = c[i] + (rng.integer(0, 1) ? 1 : -1) * a[perm[i]];
        return x;
      };
      std::vector<std::vector<double>> pts;
      for (int i = 0; i < M.m + 6; ++i) pts.push_back(signed_perm());
      for (int i = 0; i < 4; ++i) {  // perturbed: off the sphere by an exact small amount
        auto x = signed_perm();
        x[rng.integer(0, M.N - 1)] += (rng.integer(0, 1) ? 0.5 : -0.5);
        pts.push_back(x);
      }
      TangentChart chart(*T, pointers(pts));
      std::vector<int> verts{0};
      for (int i = 1; i <= M.m; ++i) verts.push_back(i);
      std::vector<int> queries;
      for (int q = M.m + 1; q < chart.size(); ++q) queries.push_back(q);
      check_cell(chart, verts, queries, ctx, rng);
      TangentCell cell = chart.cell(verts, ctx);
      if (!cell.degenerate()) {
        for (int q = M.m + 1; q < M.m + 7; ++q) {
          EXPECT_EQ(cell.power_sign(q, ctx), 0);
          ++zeros;
        }
        for (int q = M.m + 7; q < chart.size(); ++q) nonzero += cell.power_sign(q, ctx) != 0;
      }
    }
    // Small integer coordinates make most intervals exact points, so the filter itself can
    // certify many of these zeros; the thresholds 2^-200 away from the value need the exact path.
    EXPECT_GT(ctx.stats[PredicateKind::power].zero_results, 0u);
    EXPECT_GT(ctx.stats[PredicateKind::power_threshold].filter_failures, 0u);
  }
  EXPECT_GT(zeros, 50);
  EXPECT_GT(nonzero, 10);
}

// Exactly cospherical configurations with one query coordinate moved by one ulp: the exact
// power is tiny but not zero, so the filter's enclosures must not be too narrow (a wrong
// certain sign would disagree with the reference).
TEST(TangentPredicates, OneUlpFromCospherical) {
  testing::Rng rng(1234);
  int decided_nonzero = 0;
  for (const auto& M : testing::test_manifolds()) {
    if (!M.quadratic_form) continue;
    SCOPED_TRACE(M.name);
    ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    FilterContext ctx;
    for (int trial = 0; trial < 12; ++trial) {
      // p with ~10 significant bits; a = U z dyadic; points c + sigma(a) exactly when representable.
      std::vector<double> p(M.N);
      for (auto& v : p) v = std::ldexp(rng.integer(-1024, 1023), -10);
      std::optional<TangentSpace> T;
      try {
        T.emplace(F, p);
      } catch (const std::domain_error&) {
        continue;
      }
      std::vector<Q> a(M.N);
      for (int i = 0; i < M.N; ++i)
        for (int k = 0; k < M.m; ++k) a[i] += T->basis(i, k) * (k + 1);
      std::vector<std::vector<double>> pts;
      bool ok = true;
      for (int t = 0; t < M.m + 4 && ok; ++t) {
        std::vector<int> perm(M.N);
        std::iota(perm.begin(), perm.end(), 0);
        for (int i = M.N - 1; i > 0; --i) std::swap(perm[i], perm[rng.integer(0, i)]);
        std::vector<double> x(M.N);
        for (int i = 0; i < M.N; ++i) {
          const Q xi = to_rational(p[i]) + a[i] + (rng.integer(0, 1) ? 1 : -1) * a[perm[i]];
          x[i] = xi.get_d();
          ok = ok && to_rational(x[i]) == xi;
        }
        if (t >= M.m) {  // queries: one coordinate one ulp off
          const int i = rng.integer(0, M.N - 1);
          x[i] = std::nextafter(x[i], rng.integer(0, 1) ? INFINITY : -INFINITY);
        }
        pts.push_back(x);
      }
      if (!ok) continue;
      TangentChart chart(*T, pointers(pts));
      std::vector<int> verts{0};
      for (int i = 1; i <= M.m; ++i) verts.push_back(i);
      std::vector<int> queries;
      for (int q = M.m + 1; q < chart.size(); ++q) queries.push_back(q);
      check_cell(chart, verts, queries, ctx, rng);
      TangentCell cell = chart.cell(verts, ctx);
      for (int q : queries) decided_nonzero += cell.power_sign(q, ctx) != 0;
    }
  }
  EXPECT_GT(decided_nonzero, 20);
}

// Points exactly in T_p (weight 0), cocircular in the tangent plane, plus collinear and
// repeated points, on a sphere and on the Clifford torus.
TEST(TangentPredicates, PointsOnTheTangentFlatCocircularCollinearRepeated) {
  struct Case {
    std::vector<std::string> eqs;
    int N;
    std::vector<double> p;
  };
  const std::vector<Case> cases{
      {{"x1^2 + x2^2 + x3^2 - 1"}, 3, {0, 0, 0.5}},
      {{"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, 4, {0.5, 0, 0.5, 0}},
  };
  testing::Rng rng(5);
  for (const auto& cs : cases) {
    ImplicitSystem F = ImplicitSystem::parse(cs.eqs, cs.N);
    TangentSpace T(F, cs.p);
    ASSERT_EQ(T.intrinsic_dimension(), 2);
    // Here U has orthogonal columns of equal length, so p + U y with |y - y0| constant are
    // cocircular in T_p (around c = p + U y0). y0 = (3, 4)/8... keep everything dyadic.
    auto at = [&](double y1, double y2) {
      std::vector<double> x(cs.N);
      for (int i = 0; i < cs.N; ++i) x[i] = cs.p[i] + T.basis(i, 0).get_d() * y1 + T.basis(i, 1).get_d() * y2;
      return x;
    };
    const double s = 0.125;
    // Circle of radius 5s around (3s, 4s): contains (0,0) = p and the points below.
    std::vector<std::vector<double>> pts{
        at(3 * s + 5 * s, 4 * s),          // 1 on circle
        at(3 * s, 4 * s + 5 * s),          // 2 on circle
        at(3 * s - 3 * s, 4 * s + 4 * s),  // 3 on circle
        at(3 * s + 4 * s, 4 * s - 3 * s),  // 4 on circle
        at(3 * s, 4 * s),                  // 5 centre: inside
        at(3 * s + 6 * s, 4 * s),          // 6 outside
        at(s, 2 * s),                      // 7 collinear with p and 8: (s,2s), (2s,4s)
        at(2 * s, 4 * s),                  // 8
        cs.p,                              // 9 repeated p
        at(3 * s + 5 * s, 4 * s),          // 10 repeated 1
    };
    TangentChart chart(T, pointers(pts));
    FilterContext ctx;
    TangentCell cell = chart.cell(std::vector<int>{0, 1, 2}, ctx);
    ASSERT_FALSE(cell.degenerate());
    EXPECT_EQ(cell.power_sign(3, ctx), 0);
    EXPECT_EQ(cell.power_sign(4, ctx), 0);
    EXPECT_EQ(cell.power_sign(5, ctx), -1);
    EXPECT_EQ(cell.power_sign(6, ctx), 1);
    EXPECT_EQ(cell.power_sign(9, ctx), 0);   // p itself
    EXPECT_EQ(cell.power_sign(10, ctx), 0);  // a vertex again
    // Collinear and repeated cells are degenerate: orientation 0, power 0.
    for (auto verts : {std::vector<int>{0, 7, 8}, std::vector<int>{0, 1, 10}, std::vector<int>{0, 9, 1},
                       std::vector<int>{7, 8, 0}}) {
      EXPECT_EQ(chart.orientation(verts, ctx), 0);
      TangentCell d = chart.cell(verts, ctx);
      EXPECT_TRUE(d.degenerate());
      EXPECT_EQ(d.power_sign(5, ctx), 0);
      EXPECT_EQ(d.power_sign(5, RationalConstant(Q(0)), ctx), 0);
      EXPECT_THROW((void)d.centre_exact(), std::domain_error);
    }
    std::vector<int> all(chart.size());
    std::iota(all.begin(), all.end(), 0);
    for (int t = 0; t < 40; ++t) {
      std::vector<int> v{rng.integer(0, 10), rng.integer(0, 10), rng.integer(0, 10)};
      check_cell(chart, v, all, ctx, rng);
    }
    EXPECT_GT(ctx.stats[PredicateKind::power].zero_results, 0u);
  }
}

// Ambient points whose projections to T_p are collinear: the ambient triangle is fine but the
// projected cell is degenerate, so there is no unique centre in T_p.
TEST(TangentPredicates, ProjectionDegenerateCell) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> p{0.5, 0.25, 0.75};
  TangentSpace T(F, p);
  // Normal direction at p: grad F = 2p, so p + U(t d) + s p has projection p + U(t d).
  auto at = [&](double t, double s) {
    std::vector<double> x(3);
    for (int i = 0; i < 3; ++i) x[i] = p[i] + t * (T.basis(i, 0).get_d() + 2 * T.basis(i, 1).get_d()) + s * p[i];
    return x;
  };
  std::vector<std::vector<double>> pts{at(0.5, 0.25), at(1, -0.5), at(0.25, 0.125)};
  TangentChart chart(T, pointers(pts));
  FilterContext ctx;
  testing::Rng rng(1);
  EXPECT_EQ(chart.orientation(std::vector<int>{0, 1, 2}, ctx), 0);
  EXPECT_EQ(chart.orientation(std::vector<int>{1, 2, 3}, ctx), 0);
  check_cell(chart, {0, 1, 2}, {3}, ctx, rng);
  check_cell(chart, {1, 2, 3}, {0}, ctx, rng);
}

TEST(TangentPredicates, OrientationIsAlternatingAndPowerIsSymmetric) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 + x6^2 - 1",
                                            "x7^2 + x8^2 + x9^2 - 1", "x1*x4 + x2*x5 + x3*x6",
                                            "x1*x7 + x2*x8 + x3*x9", "x4*x7 + x5*x8 + x6*x9"},
                                           9);
  testing::Rng rng(9);
  const auto M = testing::test_manifolds()[5];
  auto p = testing::sample_near(M, rng);
  TangentSpace T(F, p);
  std::vector<std::vector<double>> pts;
  for (int i = 0; i < 8; ++i) {
    auto q = p;
    for (auto& v : q) v += 0.2 * rng.normal();
    pts.push_back(q);
  }
  TangentChart chart(T, pointers(pts));
  FilterContext ctx;
  std::vector<int> v{0, 3, 5, 7};
  const int o = chart.orientation(v, ctx);
  ASSERT_NE(o, 0);
  TangentCell base = chart.cell(v, ctx);
  EXPECT_EQ(base.orientation(), o);
  std::sort(v.begin(), v.end());
  int parity_changes = 0;
  do {
    // parity of the permutation relative to sorted order
    int inv = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) inv += v[i] > v[j];
    parity_changes++;
    const int expected = (inv % 2 == 0) ? o : -o;
    EXPECT_EQ(chart.orientation(v, ctx), expected);
    TangentCell c = chart.cell(v, ctx);
    EXPECT_EQ(c.orientation(), expected);
    for (int q : {1, 2, 4, 6, 8}) EXPECT_EQ(c.power_sign(q, ctx), base.power_sign(q, ctx));
  } while (std::next_permutation(v.begin(), v.end()));
  EXPECT_EQ(parity_changes, 24);
}

TEST(TangentPredicates, BatchGuardAndForceExactGiveTheSameAnswers) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, 4);
  testing::Rng rng(31);
  const auto M = testing::test_manifolds()[2];
  auto p = testing::sample_near(M, rng);
  TangentSpace T(F, p);
  std::vector<std::vector<double>> pts;
  for (int i = 0; i < 12; ++i) pts.push_back(testing::sample_near(M, rng));
  TangentChart chart(T, pointers(pts));
  std::vector<int> plain, batched, exact;
  FilterContext a, b, c;
  c.force_exact = true;
  for (int i = 1; i + 1 < chart.size(); ++i) {
    TangentCell cell = chart.cell(std::vector<int>{0, i, i + 1}, a);
    for (int q = 1; q < chart.size(); ++q) plain.push_back(cell.power_sign(q, a));
  }
  EXPECT_TRUE(rounding_is_nearest());
  {
    UpwardRounding batch;
    EXPECT_TRUE(rounding_is_upward());
    for (int i = 1; i + 1 < chart.size(); ++i) {
      TangentCell cell = chart.cell(std::vector<int>{0, i, i + 1}, b);
      for (int q = 1; q < chart.size(); ++q) batched.push_back(cell.power_sign(q, b));
    }
    EXPECT_TRUE(rounding_is_upward());
  }
  EXPECT_TRUE(rounding_is_nearest());
  for (int i = 1; i + 1 < chart.size(); ++i) {
    TangentCell cell = chart.cell(std::vector<int>{0, i, i + 1}, c);
    for (int q = 1; q < chart.size(); ++q) exact.push_back(cell.power_sign(q, c));
  }
  EXPECT_EQ(plain, batched);
  EXPECT_EQ(plain, exact);
  EXPECT_EQ(c.stats[PredicateKind::power].filter_failures, c.stats[PredicateKind::power].calls);
  EXPECT_EQ(a.stats[PredicateKind::power].calls, b.stats[PredicateKind::power].calls);
}

// Faces through p of every dimension 1..m against the brute-force reference; for k = m the
// face test agrees with the cell test.
TEST(TangentPredicates, FacesThroughPMatchReference) {
  testing::Rng rng(2718);
  int checks = 0;
  for (const auto& M : testing::test_manifolds()) {
    SCOPED_TRACE(M.name);
    ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    FilterContext ctx, exact_ctx;
    exact_ctx.force_exact = true;
    for (int trial = 0; trial < 3; ++trial) {
      auto p = testing::sample_near(M, rng);
      TangentSpace T(F, p);
      std::vector<std::vector<double>> nbrs;
      for (int i = 0; i < 9; ++i) {
        auto q = p;
        for (auto& v : q) v += 0.2 * rng.normal();
        nbrs.push_back(q);
      }
      // repeated points and points exactly in T_p along one direction (collinear projections)
      nbrs.push_back(nbrs[0]);
      {
        std::vector<double> a(M.N), b(M.N);
        for (int i = 0; i < M.N; ++i) {
          a[i] = p[i] + 0.25 * T.basis(i, 0).get_d() / std::abs(T.basis(T.free_columns()[0], 0).get_d());
          b[i] = p[i] + 0.5 * T.basis(i, 0).get_d() / std::abs(T.basis(T.free_columns()[0], 0).get_d());
        }
        nbrs.push_back(a);
        nbrs.push_back(b);
      }
      TangentChart chart(T, pointers(nbrs));
      for (int k = 1; k <= M.m; ++k) {
        for (int t = 0; t < 4; ++t) {
          std::vector<int> verts{0};
          while (static_cast<int>(verts.size()) <= k) verts.push_back(rng.integer(1, chart.size() - 1));
          if (t == 0 && k == 2) verts = {0, 11, 12};  // collinear in T_p
          std::swap(verts[0], verts[rng.integer(0, k)]);
          std::vector<const double*> fp;
          for (int v : verts) fp.push_back(chart.coordinates(v).data());
          TangentFace face = chart.face(verts, ctx);
          TangentFace exact_face = chart.face(verts, exact_ctx);
          for (int q = 0; q < chart.size(); ++q) {
            auto ref = testing::ref_face_power(T, fp, chart.coordinates(q).data());
            EXPECT_EQ(face.degenerate(), !ref.has_value());
            const int e = ref ? testing::sign(*ref) : 0;
            EXPECT_EQ(face.power_sign(q, ctx), e);
            EXPECT_EQ(exact_face.power_sign(q, exact_ctx), e);
            if (ref) {
              EXPECT_EQ(face.power_exact(q), *ref);
              EXPECT_EQ(face.power_sign(q, RationalConstant(*ref), ctx), 0);
              const Q delta(rng.integer(-50, 50), 997);
              EXPECT_EQ(face.power_sign(q, RationalConstant(delta), ctx), testing::sign(*ref - delta));
              EXPECT_EQ(exact_face.power_sign(q, RationalConstant(delta), exact_ctx), testing::sign(*ref - delta));
            }
            if (k == M.m) {
              EXPECT_EQ(face.power_sign(q, ctx), chart.cell(verts, ctx).power_sign(q, ctx));
            }
            ++checks;
          }
        }
      }
    }
  }
  EXPECT_GT(checks, 1000);
  FilterContext ctx;
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> p{0, 0, 1};
  TangentSpace T(F, p);
  std::vector<std::vector<double>> pts{{1, 0, 1}, {0, 1, 1}, {0.5, 0, 1.25}};
  TangentChart chart(T, pointers(pts));
  EXPECT_THROW(chart.face({1, 2}, ctx), std::invalid_argument);  // must contain p
  EXPECT_THROW(chart.face({0}, ctx), std::invalid_argument);
  // Edge (p, (1,0,1)): centre (1/2, 0, 1), R^2 = 1/4. (1/2, 0, 5/4) is at distance 1/4: inside.
  TangentFace edge = chart.face({0, 1}, ctx);
  EXPECT_EQ(edge.power_exact(3), Q(1, 16) - Q(1, 4));
  EXPECT_EQ(edge.power_sign(3, ctx), -1);
  EXPECT_EQ(edge.power_sign(2, ctx), 1);  // (0,1,1): distance^2 5/4 > 1/4
}

TEST(TangentPredicates, BadArgumentsAreRejected) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> p{0, 0, 1};
  TangentSpace T(F, p);
  std::vector<std::vector<double>> pts{{1, 0, 1}, {0, 1, 1}};
  TangentChart chart(T, pointers(pts));
  FilterContext ctx;
  EXPECT_THROW(chart.orientation(std::vector<int>{0, 1}, ctx), std::invalid_argument);
  EXPECT_THROW(chart.orientation(std::vector<int>{0, 1, 3}, ctx), std::out_of_range);
  TangentCell cell = chart.cell(std::vector<int>{0, 1, 2}, ctx);
  EXPECT_THROW(cell.power_sign(-1, ctx), std::out_of_range);
  std::vector<std::vector<double>> bad{{1, std::nan(""), 0}};
  EXPECT_THROW(TangentChart(T, pointers(bad)), std::invalid_argument);
}

}  // namespace
}  // namespace delcert::exact
