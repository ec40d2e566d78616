#include "exact/tangent_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

// J_F(p) U = 0 exactly (J from the original rational equations, not from the integer form used
// inside TangentSpace), U has rank m, entries are dyadic, and gram() = U^T U.
void expect_valid_basis(const ImplicitSystem& F, const TangentSpace& T) {
  const int N = T.ambient_dimension(), m = T.intrinsic_dimension(), k = F.codimension();
  const auto J = F.jacobian_exact(T.point());
  for (int i = 0; i < k; ++i)
    for (int a = 0; a < m; ++a) {
      Q s = 0;
      for (int j = 0; j < N; ++j) s += J[i * N + j] * T.basis(j, a);
      ASSERT_EQ(s, 0) << "J U != 0 at row " << i << " column " << a;
    }
  std::vector<Q> U(N * m);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < m; ++a) {
      U[i * m + a] = T.basis(i, a);
      EXPECT_TRUE(is_dyadic(T.basis(i, a)));
    }
  // rank m of U (transposed to m x N rows)
  std::vector<Q> Ut(m * N);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < m; ++a) Ut[a * N + i] = U[i * m + a];
  EXPECT_EQ(testing::rank(Ut, m, N), m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      Q g = 0;
      for (int i = 0; i < N; ++i) g += U[i * m + a] * U[i * m + b];
      EXPECT_EQ(T.gram(a, b), g);
    }
  // Free-column structure: u_a restricted to the free coordinates is det(J_P) * identity, > 0.
  const auto& free = T.free_columns();
  ASSERT_EQ(static_cast<int>(free.size()), m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      if (a == b) {
        EXPECT_GT(T.basis(free[b], a), 0);
      } else {
        EXPECT_EQ(T.basis(free[b], a), 0);
      }
      EXPECT_EQ(T.basis(free[a], a), T.basis(free[0], 0));
    }
}

TEST(TangentSpace, ExactKernelBasisOnAllBuiltinManifolds) {
  testing::Rng rng(11);
  for (const auto& M : testing::test_manifolds()) {
    SCOPED_TRACE(M.name);
    ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    EXPECT_EQ(F.intrinsic_dimension(), M.m);
    for (int trial = 0; trial < 30; ++trial) {
      auto p = testing::sample_near(M, rng);
      // Also points off M: T_p is defined by ker J_F(p) at p itself.
      if (trial % 3 == 1)
        for (auto& v : p) v += 1e-3 * rng.normal();
      TangentSpace T(F, p);
      EXPECT_EQ(T.ambient_dimension(), M.N);
      EXPECT_EQ(T.intrinsic_dimension(), M.m);
      expect_valid_basis(F, T);
    }
  }
}

// basis_enclosure and gram_enclosure are enclose() of the rationals, on every built-in manifold
// and at points scaled to adversarial magnitudes (2^-1030 ... 2^1000: subnormal entries, entries
// and Gram entries past the double range, where the enclosure goes through the rational), built
// under upward rounding as the certifier builds them.
TEST(TangentSpace, EnclosuresAreTheTightestOfTheRationals) {
  testing::Rng rng(12);
  for (const auto& M : testing::test_manifolds()) {
    SCOPED_TRACE(M.name);
    const ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    for (int trial = 0; trial < 40; ++trial) {
      auto p = testing::sample_near(M, rng);
      const int e = trial < 10 ? 0 : -1030 + 2030 * (trial - 10) / 29;  // 0, then -1030 .. 1000
      // (the minors of SO(3)'s codimension-6 Jacobian fall below 2^-1074 from about 2^-180)
      for (auto& v : p) v = std::ldexp(v + 1e-3 * rng.normal(), e);
      std::optional<TangentSpace> T;
      try {
        UpwardRounding up;  // as in the certifier's stars: the enclosures must not depend on it
        T.emplace(F, p);
      } catch (const std::domain_error&) {
        continue;  // a point whose coordinates underflowed to 0 can be singular
      }
      const int N = T->ambient_dimension(), m = T->intrinsic_dimension();
      for (int i = 0; i < N; ++i)
        for (int a = 0; a < m; ++a) {
          const Interval want = enclose(T->basis(i, a)), got = T->basis_enclosure(i, a);
          EXPECT_TRUE(got.lo == want.lo && got.hi == want.hi) << "U(" << i << ", " << a << ") at 2^" << e;
        }
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
          const Interval want = enclose(T->gram(a, b)), got = T->gram_enclosure(a, b);
          EXPECT_TRUE(got.lo == want.lo && got.hi == want.hi) << "G(" << a << ", " << b << ") at 2^" << e;
        }
    }
  }
}

// residual_enclosures holds the exact |F_i(x)| and is tight (a few ulps), on every built-in
// manifold, with rational coefficients, at 2^-1074 ... 2^1000 (F past the double range included).
TEST(ImplicitSystem, ResidualEnclosuresHoldTheExactResiduals) {
  testing::Rng rng(13);
  auto check = [](const ImplicitSystem& F, const std::vector<double>& x) {
    const std::vector<mpq_class> exact = F.evaluate_exact(x);
    std::vector<Interval> got = F.residual_enclosures(x);
    {
      UpwardRounding up;  // as the certifier calls it: the same intervals in either mode
      const std::vector<Interval> up_got = F.residual_enclosures(x);
      for (std::size_t i = 0; i < got.size(); ++i)
        EXPECT_TRUE(up_got[i].lo == got[i].lo && up_got[i].hi == got[i].hi) << i;
    }
    ASSERT_EQ(got.size(), exact.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      const mpq_class a = abs(exact[i]);
      const Interval want = enclose(a);
      EXPECT_TRUE(got[i].lo <= want.lo && want.hi <= got[i].hi) << i << ": [" << std::hexfloat << got[i].lo << ", " << got[i].hi << "] want [" << want.lo << ", " << want.hi << "]" << std::defaultfloat;
      if (std::isfinite(want.hi) && want.hi < 0x1p1000 && want.lo > 0x1p-1000) {  // normal range: a few ulps
        EXPECT_LE(got[i].hi - got[i].lo, 8 * (want.hi - want.lo) + 8 * std::numeric_limits<double>::epsilon() * want.hi);
      }
      if (a == 0) {
        EXPECT_TRUE(got[i].lo == 0 && got[i].hi == 0);
      }
    }
  };
  for (const auto& M : testing::test_manifolds()) {
    SCOPED_TRACE(M.name);
    const ImplicitSystem F = ImplicitSystem::parse(M.equations, M.N);
    for (int trial = 0; trial < 40; ++trial) {
      auto p = testing::sample_near(M, rng);
      const int e = trial < 10 ? 0 : -1074 + 2074 * (trial - 10) / 29;
      for (auto& v : p) v = std::ldexp(v + (trial % 2) * 1e-3 * rng.normal(), e);
      check(F, p);
    }
  }
  const ImplicitSystem G = ImplicitSystem::parse({"x1^2/3 + x2^2/7 + x3^2 - 5/11"}, 3);
  check(G, {0.25, -0.5, 0.5});
  check(G, {0, 0, 0});
  check(ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3), {1, 0, 0});  // exactly 0
}

TEST(TangentSpace, SphereBasisIsTheExpectedCofactorBasis) {
  // F = |x|^2 - 1: J = 2 p^T; pivot = the largest |p_i|; u_f = 2 p_k e_f - 2 p_f e_k.
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> p{0.25, -0.5, 0.75};
  TangentSpace T(F, p);
  ASSERT_EQ(T.pivot_columns(), std::vector<int>{2});
  ASSERT_EQ(T.free_columns(), (std::vector<int>{0, 1}));
  EXPECT_EQ(T.basis(0, 0), Q(3, 2));
  EXPECT_EQ(T.basis(1, 0), 0);
  EXPECT_EQ(T.basis(2, 0), Q(-1, 2));
  EXPECT_EQ(T.basis(0, 1), 0);
  EXPECT_EQ(T.basis(1, 1), Q(3, 2));
  EXPECT_EQ(T.basis(2, 1), Q(1));
}

TEST(TangentSpace, RationalCoefficientsAreScaledOut) {
  // 0.1 x1^2 + x2^2/3 + x3^2 - 1/7: the integer form changes nothing about the kernel.
  ImplicitSystem F = ImplicitSystem::parse({"0.1*x1^2 + x2^2/3 + x3^2 - 1/7"}, 3);
  testing::Rng rng(5);
  for (int t = 0; t < 20; ++t) {
    std::vector<double> p{rng.normal(), rng.normal(), rng.normal()};
    TangentSpace T(F, p);
    expect_valid_basis(F, T);
  }
}

TEST(TangentSpace, RankDeficientJacobianIsRejected) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> origin{0, 0, 0};
  EXPECT_THROW(TangentSpace(F, origin), std::domain_error);
  // Two equations with dependent gradients at p: x1 = 0 and x1 + x1^2 = 0 at x1 = 0.
  ImplicitSystem G = ImplicitSystem::parse({"x1", "x1 + x1^2"}, 3);
  const std::vector<double> p{0, 0.5, 0.25};
  EXPECT_THROW(TangentSpace(G, p), std::domain_error);
}

TEST(TangentSpace, ExhaustivePivotSearchWhenDoubleJacobianOverflows) {
  // J = [0, 200 * 100^199 (overflows in double), 1]: the double pivot order is unusable, the
  // first exact minor (column 0) is zero, and the exhaustive search must find another one.
  ImplicitSystem F = ImplicitSystem::parse({"x2^200 + x3 + x1*x3"}, 3);
  const std::vector<double> p{0, 100, 0};
  TangentSpace T(F, p);
  expect_valid_basis(F, T);
  EXPECT_NE(T.pivot_columns()[0], 0);
}

TEST(TangentSpace, NoEquationsGivesIdentity) {
  ImplicitSystem F(std::vector<Polynomial>{}, 3);
  const std::vector<double> p{1, 2, 3};
  TangentSpace T(F, p);
  EXPECT_EQ(T.intrinsic_dimension(), 3);
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(T.basis(i, a), i == a ? 1 : 0);
}

TEST(TangentSpace, ProjectionAndWeight) {
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, 4);
  testing::Rng rng(3);
  for (int t = 0; t < 20; ++t) {
    auto p = testing::sample_near(testing::test_manifolds()[2], rng);
    TangentSpace T(F, p);
    std::vector<double> x(4);
    for (auto& v : x) v = rng.normal();
    auto q = T.project_exact(x);
    // q - p in ker J and x - q orthogonal to every basis vector.
    const auto J = F.jacobian_exact(p);
    for (int i = 0; i < 2; ++i) {
      Q s = 0;
      for (int j = 0; j < 4; ++j) s += J[i * 4 + j] * (q[j] - to_rational(p[j]));
      EXPECT_EQ(s, 0);
    }
    for (int a = 0; a < 2; ++a) {
      Q s = 0;
      for (int j = 0; j < 4; ++j) s += T.basis(j, a) * (to_rational(x[j]) - q[j]);
      EXPECT_EQ(s, 0);
    }
    Q n2 = 0;
    for (int j = 0; j < 4; ++j) n2 += (to_rational(x[j]) - q[j]) * (to_rational(x[j]) - q[j]);
    EXPECT_EQ(T.weight_exact(x), -n2);
  }
}

TEST(TangentSpace, BadInputIsReported) {
  EXPECT_THROW(ImplicitSystem::parse({"x1", "x2", "x3"}, 3), std::invalid_argument);  // k >= N
  EXPECT_THROW(ImplicitSystem(std::vector<Polynomial>{Polynomial::parse("x1", 2)}, 3), std::invalid_argument);
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const std::vector<double> short_point{1, 0};
  EXPECT_THROW(TangentSpace(F, short_point), std::invalid_argument);
  const std::vector<double> nan_point{1, 0, std::nan("")};
  EXPECT_THROW(TangentSpace(F, nan_point), std::invalid_argument);
}

}  // namespace
}  // namespace delcert::exact
