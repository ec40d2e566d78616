#include "core/refine/hypotheses.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace delcert::refine {
namespace {

const HypothesisCheck& find(const HypothesesReport& r, const std::string& name) {
  for (const auto& c : r.checks)
    if (c.name == name) return c;
  throw std::runtime_error("no " + name);
}

TEST(Hypotheses, ParametersChosenByThePaperRecipe) {
  // α < 1/2, β from H1, Γ0 below 1/(B+1), δ0^2 = Γ0^(m+1), ε below both specified bounds.
  HypothesesInput in;
  in.m = 2;
  in.alpha = 0.25;
  in.delta0 = 0;  // filled below
  in.beta = 2.7;
  const double B = 4 + 2 * std::pow(1 + 1152 * in.beta * in.beta, 2);
  in.gamma0 = 0.5 / (B + 1);
  in.delta0 = std::sqrt(std::pow(in.gamma0, 3));
  in.reach = 2.0;
  in.eps = 1e-300;
  auto r = evaluate_hypotheses(in);
  ASSERT_EQ(r.checks.size(), 6u);
  EXPECT_EQ(find(r, "H0").status, HypothesisStatus::holds);
  EXPECT_EQ(find(r, "H1").status, HypothesisStatus::holds);
  EXPECT_EQ(find(r, "H2").status, HypothesisStatus::not_evaluable);  // E and D unspecified
  EXPECT_EQ(find(r, "H3").status, HypothesisStatus::holds);
  EXPECT_EQ(find(r, "H4").status, HypothesisStatus::not_evaluable);  // ξ unspecified
  EXPECT_EQ(find(r, "H5").status, HypothesisStatus::holds);
  EXPECT_FALSE(r.any_fails);
  EXPECT_FALSE(r.all_hold);
  EXPECT_TRUE(r.sparsity_lemma_holds);
  ASSERT_TRUE(r.max_eps);
  const double g = in.gamma0, d2 = in.delta0 * in.delta0;
  EXPECT_DOUBLE_EQ(*r.max_eps, 2.0 * std::min(std::pow(g, 3) / (8 * in.beta), d2 * std::pow(g, 4) / 1.1e9));
  EXPECT_EQ(r.unspecified.size(), 3u);
}

TEST(Hypotheses, RealisticParametersFailAndSayWhy) {
  HypothesesInput in;
  in.m = 3;
  in.alpha = 0.3;
  in.beta = 1.5;
  in.gamma0 = 0.1;
  in.delta0 = 0.1;
  in.eps = 0.3;
  in.reach = 1.0;
  auto r = evaluate_hypotheses(in);
  EXPECT_EQ(find(r, "H0").status, HypothesisStatus::holds);
  EXPECT_EQ(find(r, "H1").status, HypothesisStatus::fails);  // β < 2/(...) ≈ 2.9
  EXPECT_EQ(find(r, "H2").status, HypothesisStatus::fails);  // Γ0 >= 1/(B+1)
  EXPECT_EQ(find(r, "H3").status, HypothesisStatus::fails);  // 0.01 > 1e-4
  EXPECT_EQ(find(r, "H4").status, HypothesisStatus::fails);
  EXPECT_EQ(find(r, "H5").status, HypothesisStatus::fails);
  EXPECT_TRUE(r.any_fails);
  ASSERT_TRUE(r.max_eps);
  EXPECT_LT(*r.max_eps, 1e-12);
  EXPECT_NE(find(r, "H1").detail.find("violates"), std::string::npos);
}

TEST(Hypotheses, H3WithEqualityIsDecidedExactly) {
  // The default δ0 = Γ0^2 for m = 3 meets H3 with equality; in doubles 0.1^2 * 0.1^2 > 0.1^4.
  HypothesesInput in;
  in.m = 3;
  in.alpha = 0.3;
  in.beta = 1.1;
  in.gamma0 = 0.1;
  in.delta0 = 0.1 * 0.1;
  in.eps = 0.3;
  ASSERT_GT(in.delta0 * in.delta0, std::pow(in.gamma0, 4));  // the rounded doubles say "fails"
  in.gamma0_text = "0.1";
  in.delta0_text = "0.01";
  EXPECT_EQ(find(evaluate_hypotheses(in), "H3").status, HypothesisStatus::holds);
  in.delta0_text = "0.0100001";
  EXPECT_EQ(find(evaluate_hypotheses(in), "H3").status, HypothesisStatus::fails);
}

TEST(Hypotheses, WithoutReachTheEpsilonHypothesesAreNotEvaluable) {
  HypothesesInput in;
  in.m = 2;
  in.alpha = 0.6;  // H0 fails
  in.beta = 3;
  in.gamma0 = 1e-12;
  in.delta0 = 1e-20;
  in.eps = 0.1;
  auto r = evaluate_hypotheses(in);
  EXPECT_EQ(find(r, "H0").status, HypothesisStatus::fails);
  EXPECT_EQ(find(r, "H4").status, HypothesisStatus::not_evaluable);
  EXPECT_EQ(find(r, "H5").status, HypothesisStatus::not_evaluable);
  EXPECT_FALSE(r.max_eps);
  EXPECT_NE(r.max_eps_note.find("no reach"), std::string::npos);
}

}  // namespace
}  // namespace delcert::refine
