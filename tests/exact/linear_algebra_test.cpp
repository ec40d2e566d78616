#include "exact/linear_algebra.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "exact/interval.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {
namespace {

using Q = mpq_class;

// The n x n Hilbert matrix 1 / (i + j + 1): its determinant is 1 / an integer known in closed form.
std::vector<Q> hilbert(int n) {
  std::vector<Q> a(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a[i * n + j] = Q(1, i + j + 1);
  return a;
}

std::vector<Q> product(const std::vector<Q>& a, const std::vector<Q>& b, int n) {
  std::vector<Q> c(n * n, Q(0));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) c[i * n + j] += a[i * n + k] * b[k * n + j];
  return c;
}

std::vector<Q> identity(int n, const Q& scale = 1) {
  std::vector<Q> c(n * n, Q(0));
  for (int i = 0; i < n; ++i) c[i * n + i] = scale;
  return c;
}

TEST(LinearAlgebra, DeterminantOfHilbertMatricesIsExact) {
  const char* inverse_det[] = {"1", "12", "2160", "6048000", "266716800000", "186313420339200000",
                               "2067909047925770649600000", "365356847125734485878112256000000"};
  for (int n = 1; n <= kMaxLinearSize; ++n) {
    const auto a = hilbert(n);
    EXPECT_EQ(determinant(a.data(), n), Q(1) / Q(inverse_det[n - 1])) << "n = " << n;
  }
  EXPECT_EQ(determinant<3>(hilbert(3).data()), Q(1, 2160));
}

TEST(LinearAlgebra, DeterminantSignsAndEdgeSizes) {
  // A row swap of diag(1..8) (the loop variant of the minor table): -8!.
  std::vector<Q> a = identity(8);
  for (int i = 0; i < 8; ++i) a[i * 8 + i] = i + 1;
  for (int j = 0; j < 8; ++j) std::swap(a[2 * 8 + j], a[5 * 8 + j]);
  EXPECT_EQ(determinant(a.data(), 8), Q(-40320));
  // A singular matrix (third row = first + second) and the empty determinant.
  const std::vector<Q> s = {1, 2, 3, 4, 5, 6, 5, 7, 9};
  EXPECT_EQ(determinant(s.data(), 3), Q(0));
  EXPECT_EQ(determinant(s.data(), 0), Q(1));
  EXPECT_THROW(determinant(s.data(), kMaxLinearSize + 1), std::invalid_argument);
  // Integer entries: double evaluation is exact here.
  const std::vector<double> d = {2, -1, 0, -1, 2, -1, 0, -1, 2};
  EXPECT_EQ(determinant(d.data(), 3), 4.0);
}

TEST(LinearAlgebra, IntervalDeterminantEnclosesTheExactValue) {
  UpwardRounding upward;
  for (int n = 1; n <= kMaxLinearSize; ++n) {
    const auto a = hilbert(n);
    std::vector<IntervalNumber> ia;
    for (const Q& x : a) ia.push_back(to_interval_number(enclose(x)));
    const IntervalNumber d = determinant(ia.data(), n);
    const Q exact = determinant(a.data(), n);
    EXPECT_LE(Q(d.inf()), exact) << "n = " << n;
    EXPECT_GE(Q(d.sup()), exact) << "n = " << n;
  }
}

TEST(LinearAlgebra, CramerSolveGivesTheExactSolution) {
  // A y = h with y = (1, -2, 3/4) by construction.
  const std::vector<Q> A = {2, 1, -1, -3, -1, 2, -2, 1, 2};
  const std::vector<Q> y0 = {1, -2, Q(3, 4)};
  std::vector<Q> h(3, Q(0));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) h[i] += A[i * 3 + j] * y0[j];
  const Q d = determinant(A.data(), 3);
  ASSERT_NE(d, 0);
  std::vector<Q> y(3);
  cramer_solve(A.data(), h.data(), d, 3, y.data());
  EXPECT_EQ(y, y0);
  // In intervals: an enclosure of the same solution.
  UpwardRounding upward;
  std::vector<IntervalNumber> Ai, hi;
  for (const Q& x : A) Ai.push_back(to_interval_number(enclose(x)));
  for (const Q& x : h) hi.push_back(to_interval_number(enclose(x)));
  std::vector<IntervalNumber> yi(3);
  cramer_solve(Ai.data(), hi.data(), determinant(Ai.data(), 3), 3, yi.data());
  for (int j = 0; j < 3; ++j) {
    EXPECT_LE(Q(yi[j].inf()), y0[j]);
    EXPECT_GE(Q(yi[j].sup()), y0[j]);
  }
}

TEST(LinearAlgebra, AdjugateTimesMatrixIsTheDeterminant) {
  for (int n = 1; n <= 5; ++n) {
    auto a = hilbert(n);
    a[0] += 3;  // not symmetric in its adjugate's index order test below
    a[n * n - 1] -= Q(1, 7);
    if (n > 1) a[1] += 2;
    std::vector<Q> adj(n * n);
    adjugate(a.data(), n, adj.data());
    EXPECT_EQ(product(a, adj, n), identity(n, determinant(a.data(), n))) << "n = " << n;
    EXPECT_EQ(product(adj, a, n), identity(n, determinant(a.data(), n))) << "n = " << n;
  }
}

TEST(LinearAlgebra, RationalSolveAndInverse) {
  for (int n = 1; n <= 6; ++n) {
    const auto a = hilbert(n);
    std::vector<Q> y0(n), h(n, Q(0));
    for (int i = 0; i < n; ++i) y0[i] = Q(i * i - 3, i + 2);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) h[i] += a[i * n + j] * y0[j];
    const auto y = solve(a, h, n);
    ASSERT_TRUE(y.has_value());
    EXPECT_EQ(*y, y0) << "n = " << n;
    const auto inv = inverse(a, n);
    ASSERT_TRUE(inv.has_value());
    EXPECT_EQ(product(a, *inv, n), identity(n)) << "n = " << n;
  }
  // A zero first pivot needs a row exchange.
  const std::vector<Q> p = {0, 1, 1, 0};
  EXPECT_EQ(*solve(p, {Q(2), Q(3)}, 2), (std::vector<Q>{3, 2}));
  EXPECT_EQ(*inverse(p, 2), p);
  // Singular: nothing, in both.
  const std::vector<Q> s = {1, 2, 3, 4, 5, 6, 5, 7, 9};
  EXPECT_FALSE(solve(s, {Q(1), Q(1), Q(1)}, 3).has_value());
  EXPECT_FALSE(inverse(s, 3).has_value());
}

}  // namespace
}  // namespace delcert::exact
