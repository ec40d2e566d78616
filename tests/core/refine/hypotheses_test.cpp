#include "core/refine/hypotheses.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace delcert::refine {
namespace {

using exact::Tri;

// A constant from a double, exactly (the double's own value).
ExactParameter of(double x) { return ExactParameter(mpq_class(x)); }
ExactParameter of(const char* text) { return ExactParameter::parse(text); }

const HypothesisCheck& find(const HypothesesReport& r, const std::string& name) {
  for (const auto& c : r.checks)
    if (c.name == name) return c;
  throw std::runtime_error("no " + name);
}

TEST(Hypotheses, ParametersChosenByThePaperRecipe) {
  // α < 1/2, β from H1, Γ0 below 1/(B+1), δ0^2 = Γ0^(m+1), ε below both specified bounds.
  HypothesesInput in;
  in.m = 2;
  in.constants.alpha = of(0.25);
  const double beta = 2.7;
  in.constants.beta = of(beta);
  const double B = 4 + 2 * std::pow(1 + 1152 * beta * beta, 2);
  const double gamma0 = 0.5 / (B + 1);
  in.constants.gamma0 = of(gamma0);
  in.constants.delta0 = of(gamma0 * gamma0);  // δ0^2 = Γ0^4 < Γ0^3, exactly
  in.reach = 2.0;
  in.constants.eps = of(1e-300);
  auto r = evaluate_hypotheses(in);
  ASSERT_EQ(r.checks.size(), 6u);
  EXPECT_EQ(find(r, "H0").status, Tri::yes);
  EXPECT_EQ(find(r, "H1").status, Tri::yes);
  EXPECT_EQ(find(r, "H2").status, Tri::unknown);  // E and D unspecified
  EXPECT_EQ(find(r, "H3").status, Tri::yes);
  EXPECT_EQ(find(r, "H4").status, Tri::unknown);  // ξ unspecified
  EXPECT_EQ(find(r, "H5").status, Tri::yes);
  EXPECT_FALSE(r.any_fails);
  EXPECT_FALSE(r.all_hold);
  EXPECT_TRUE(r.sparsity_lemma_holds);
  ASSERT_TRUE(r.max_eps);
  const double g = gamma0, d2 = (gamma0 * gamma0) * (gamma0 * gamma0);
  EXPECT_DOUBLE_EQ(*r.max_eps, 2.0 * std::min(std::pow(g, 3) / (8 * beta), d2 * std::pow(g, 4) / 1.1e9));
  EXPECT_EQ(r.unspecified.size(), 3u);
}

TEST(Hypotheses, RealisticParametersFailAndSayWhy) {
  HypothesesInput in;
  in.m = 3;
  in.constants.alpha = of("0.3");
  in.constants.beta = of("1.5");
  in.constants.gamma0 = of("0.1");
  in.constants.delta0 = of("0.1");
  in.constants.eps = of("0.3");
  in.reach = 1.0;
  auto r = evaluate_hypotheses(in);
  EXPECT_EQ(find(r, "H0").status, Tri::yes);
  EXPECT_EQ(find(r, "H1").status, Tri::no);  // β < 2/(...) ≈ 2.9
  EXPECT_EQ(find(r, "H2").status, Tri::no);  // Γ0 >= 1/(B+1)
  EXPECT_EQ(find(r, "H3").status, Tri::no);  // 0.01 > 1e-4
  EXPECT_EQ(find(r, "H4").status, Tri::no);
  EXPECT_EQ(find(r, "H5").status, Tri::no);
  EXPECT_TRUE(r.any_fails);
  ASSERT_TRUE(r.max_eps);
  EXPECT_LT(*r.max_eps, 1e-12);
  EXPECT_NE(find(r, "H1").detail.find("violates"), std::string::npos);
}

TEST(Hypotheses, H3WithEqualityIsDecidedExactly) {
  // The default δ0 = Γ0^2 for m = 3 meets H3 with equality; in doubles 0.1^2 * 0.1^2 > 0.1^4.
  HypothesesInput in;
  in.m = 3;
  in.constants.alpha = of("0.3");
  in.constants.beta = of("1.1");
  in.constants.gamma0 = of("0.1");
  in.constants.delta0 = of("0.01");
  in.constants.eps = of("0.3");
  ASSERT_GT((0.1 * 0.1) * (0.1 * 0.1), std::pow(0.1, 4));  // the rounded doubles say "fails"
  EXPECT_EQ(find(evaluate_hypotheses(in), "H3").status, Tri::yes);
  in.constants.delta0 = of("0.0100001");
  EXPECT_EQ(find(evaluate_hypotheses(in), "H3").status, Tri::no);
}

TEST(Hypotheses, WithoutReachTheEpsilonHypothesesAreNotEvaluable) {
  HypothesesInput in;
  in.m = 2;
  in.constants.alpha = of("0.6");  // H0 fails
  in.constants.beta = of("3");
  in.constants.gamma0 = of("1e-12");
  in.constants.delta0 = of("1e-20");
  in.constants.eps = of("0.1");
  auto r = evaluate_hypotheses(in);
  EXPECT_EQ(find(r, "H0").status, Tri::no);
  EXPECT_EQ(find(r, "H4").status, Tri::unknown);
  EXPECT_EQ(find(r, "H5").status, Tri::unknown);
  EXPECT_FALSE(r.max_eps);
  EXPECT_NE(r.max_eps_note.find("no reach"), std::string::npos);
}

// The words report.json writes for the three answers.
TEST(Hypotheses, StatusWords) {
  EXPECT_STREQ(status_name(Tri::yes), "holds");
  EXPECT_STREQ(status_name(Tri::no), "fails");
  EXPECT_STREQ(status_name(Tri::unknown), "not_evaluable");
}

}  // namespace
}  // namespace delcert::refine
