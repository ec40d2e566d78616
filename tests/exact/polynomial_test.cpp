#include "exact/polynomial.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace delcert {
namespace {

TEST(ParseRational, IntegersDecimalsFractionsAreExact) {
  EXPECT_EQ(parse_rational("7"), mpq_class(7));
  EXPECT_EQ(parse_rational("-3"), mpq_class(-3));
  EXPECT_EQ(parse_rational("0.1"), mpq_class(1, 10));
  EXPECT_EQ(parse_rational("2.5e-3"), mpq_class(1, 400));
  EXPECT_EQ(parse_rational("1E+2"), mpq_class(100));
  EXPECT_EQ(parse_rational("1/3"), mpq_class(1, 3));
  EXPECT_EQ(parse_rational("-0.5/3"), mpq_class(-1, 6));
  EXPECT_EQ(parse_rational(" .25 "), mpq_class(1, 4));
  EXPECT_THROW(parse_rational("1/0"), std::invalid_argument);
  EXPECT_THROW(parse_rational("abc"), std::invalid_argument);
  EXPECT_THROW(parse_rational("1.2.3"), std::invalid_argument);
  EXPECT_THROW(parse_rational("1e"), std::invalid_argument);
  EXPECT_THROW(parse_rational(""), std::invalid_argument);
}

TEST(RationalToString, FiniteDecimalsAndFractions) {
  EXPECT_EQ(rational_to_string(mpq_class(1, 10)), "0.1");
  EXPECT_EQ(rational_to_string(mpq_class(-1, 8)), "-0.125");
  EXPECT_EQ(rational_to_string(mpq_class(1, 3)), "1/3");
  EXPECT_EQ(rational_to_string(mpq_class(42)), "42");
  EXPECT_EQ(rational_to_string(mpq_class(250, 100)), "2.5");
}

TEST(Polynomial, ParsesToCanonicalForm) {
  auto p = Polynomial::parse("x1^2 + x2^2 + x3^2 - 1", 3);
  EXPECT_EQ(p.to_string(), "x1^2 + x2^2 + x3^2 - 1");
  EXPECT_EQ(p.degree(), 2);
  EXPECT_EQ(p.terms().size(), 4u);
  // Expansion and collection of like terms.
  auto q = Polynomial::parse("(x1 + x2)^2 - 2*x1*x2", 2);
  EXPECT_EQ(q, Polynomial::parse("x1^2 + x2^2", 2));
  // Unary minus, nested parentheses, fraction and decimal literals are exact.
  auto r = Polynomial::parse("-(0.1*x1 - 1/3) * 3", 1);
  EXPECT_EQ(r.terms()[0].coefficient, mpq_class(-3, 10));
  EXPECT_EQ(r.terms()[1].coefficient, mpq_class(1));
  // Division by a constant expression.
  EXPECT_EQ(Polynomial::parse("x1 / (2 + 2)", 1), Polynomial::parse("0.25*x1", 1));
  // 0.1 + 0.2 == 0.3 exactly, unlike doubles.
  EXPECT_TRUE((Polynomial::parse("0.1 + 0.2 - 0.3", 1)).is_zero());
}

TEST(Polynomial, TorusOfRevolutionExpandsCorrectly) {
  auto p = Polynomial::parse("(x1^2 + x2^2 + x3^2 + 3)^2 - 16*(x1^2 + x2^2)", 3);
  std::vector<mpq_class> on{3, 0, 0};  // (R + r, 0, 0) with R = 2, r = 1
  EXPECT_EQ(p.evaluate(std::span<const mpq_class>(on)), 0);
  std::vector<mpq_class> top{2, 0, 1};
  EXPECT_EQ(p.evaluate(std::span<const mpq_class>(top)), 0);
  std::vector<mpq_class> centre{0, 0, 0};
  EXPECT_EQ(p.evaluate(std::span<const mpq_class>(centre)), 9);
  EXPECT_EQ(p.degree(), 4);
}

TEST(Polynomial, ParseErrorsSayWhere) {
  auto offset_of = [](const char* text, int n) -> long {
    try {
      Polynomial::parse(text, n);
    } catch (const PolynomialParseError& e) {
      return static_cast<long>(e.offset);
    }
    return -1;
  };
  EXPECT_EQ(offset_of("x1 + x4", 3), 5);      // variable out of range
  EXPECT_EQ(offset_of("x1 + ", 3), 5);        // unexpected end
  EXPECT_EQ(offset_of("x1 / x2", 3), 3);      // division by a non-constant
  EXPECT_EQ(offset_of("x1 / (1 - 1)", 3), 3); // division by zero
  EXPECT_EQ(offset_of("x1^x2", 3), 3);        // exponent must be a literal
  EXPECT_EQ(offset_of("(x1 + 1", 3), 7);      // missing ')'
  EXPECT_EQ(offset_of("2 $ x1", 3), 2);
  EXPECT_EQ(offset_of("", 3), 0);
  EXPECT_EQ(offset_of("y1", 3), 0);
}

TEST(Polynomial, ExactDerivatives) {
  auto p = Polynomial::parse("x1^3*x2 - 0.5*x2^2 + 1/3*x1", 2);
  EXPECT_EQ(p.derivative(0), Polynomial::parse("3*x1^2*x2 + 1/3", 2));
  EXPECT_EQ(p.derivative(1), Polynomial::parse("x1^3 - x2", 2));
  EXPECT_TRUE(p.derivative(0).derivative(0).derivative(0).derivative(0).is_zero());
  auto det = Polynomial::parse("x1*(x5*x9 - x6*x8) - x2*(x4*x9 - x6*x7) + x3*(x4*x8 - x5*x7)", 9);
  EXPECT_EQ(det.derivative(0), Polynomial::parse("x5*x9 - x6*x8", 9));
  EXPECT_EQ(det.derivative(4), Polynomial::parse("x1*x9 - x3*x7", 9));
}

TEST(Polynomial, IntegerFormIsExactAndDivisionFree) {
  auto p = Polynomial::parse("1/6*x1^2 - 0.25*x2 + 2", 2);
  auto f = p.integer_form();
  EXPECT_EQ(f.denominator, 12);
  ASSERT_EQ(f.numerators.size(), 3u);
  std::vector<mpq_class> x{mpq_class(3, 7), mpq_class(-5, 2)};
  mpq_class num = p.evaluate_with<mpq_class>(std::span<const mpq_class>(x),
                                             [&](std::size_t i) { return mpq_class(f.numerators[i]); });
  EXPECT_EQ(num / f.denominator, p.evaluate(std::span<const mpq_class>(x)));
}

TEST(Polynomial, DoubleEvaluationAgreesWithExact) {
  auto p = Polynomial::parse("x1^2*x3 - 3*x2*x4 + 0.1*x4^3 - 7", 4);
  DoublePolynomial d(p);
  std::vector<double> x{0.5, -1.25, 2.0, 0.75};
  std::vector<mpq_class> xq(x.begin(), x.end());
  double exact = p.evaluate(std::span<const mpq_class>(xq)).get_d();
  EXPECT_NEAR(d(x), exact, 1e-14);
  EXPECT_NEAR(p.evaluate(std::span<const double>(x)), exact, 1e-14);
}

}  // namespace
}  // namespace delcert
