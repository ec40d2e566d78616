// Check 7 (secure simplices): reusing the star analysis' enclosures of the tangent basis gives
// exactly the same answers as recomputing the exact tangent space, including on the exact
// fallback path (an interval comparison that cannot decide an exact equality).
#include <gtest/gtest.h>

#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::certify::test {
namespace {

TEST(SecureSimplices, EnclosuresFromTheStarAnalysisGiveTheSameAnswersAndFallBackExactly) {
  // At p = (0, 0, 1) on the unit sphere the exact tangent basis is U = (2 e_x, 2 e_y), so the
  // projected squared distance from p to q1 = (0.1, 0, 1) is exactly 0.1^2 (the double 0.1),
  // a rational that the interval evaluation encloses but cannot compare exactly with
  // shortest^2 = 0.1^2: the cell {p, q1, q2} needs the exact fallback, whose answer is that the
  // edge is not shorter than mu0 eps (equality).
  io::PointSet P;
  P.dimension = 3;
  P.push_back(std::vector<double>{0, 0, 1});
  P.push_back(std::vector<double>{0.1, 0, 1});
  P.push_back(std::vector<double>{0, 0.1, 1});
  P.push_back(std::vector<double>{-0.1, 0, 1});
  P.push_back(std::vector<double>{0, -0.1, 1});
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);
  detail::PointGrid grid(P, 2);
  StarSettings S{&P, &system, &grid, 2, std::nullopt, std::nullopt};
  exact::FilterContext ctx;
  StarReport star = analyse_star(S, 0, nullptr, ctx);
  ASSERT_EQ(star.basis_enclosure.size(), 6u);
  ASSERT_EQ(star.gram_enclosure.size(), 4u);
  std::vector<Simplex> cells = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 1, 4}};
  for (const mpq_class& delta : {mpq_class(1, 1000), mpq_class(1, 2)}) {
    SecureParams sp{mpq_class(1), delta, mpq_class(1, 100), exact::to_rational(0.1), {}, {}, {}, {}};
    sp.prepare();
    SecureReport fresh = analyse_secure(S, 0, cells, sp, ctx);
    SecureReport reused = analyse_secure(S, 0, cells, sp, ctx, &star);
    EXPECT_GT(fresh.exact_fallbacks, 0);
    EXPECT_EQ(fresh.secure, reused.secure);
    EXPECT_EQ(fresh.insecure, reused.insecure);
    EXPECT_EQ(fresh.undecided, reused.undecided);
    EXPECT_EQ(fresh.exact_fallbacks, reused.exact_fallbacks);
    EXPECT_EQ(fresh.failures, reused.failures);
    EXPECT_EQ(fresh.secure + fresh.insecure, 4);
    if (delta == mpq_class(1, 1000)) {
      EXPECT_EQ(fresh.secure, 4);  // every edge is exactly 0.1 or longer: nothing too short
    } else {
      EXPECT_EQ(fresh.insecure, 4);  // delta = 1/2: the neighbours are not delta-protected
    }
  }
}

}  // namespace
}  // namespace delcert::certify::test
