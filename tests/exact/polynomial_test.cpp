#include "exact/polynomial.hpp"

#include "exact/equations.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace delcert::exact {
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

// "1/2/3" was read as 1/(2/3) = 3/2 here and as (1/2)/3 = 1/6 by the polynomial parser: it has no
// one meaning and is refused by both.
TEST(ParseRational, OneSlashAtMost) {
  try {
    parse_rational("1/2/3");
    FAIL() << "1/2/3 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not a rational"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_rational("1//2"), std::invalid_argument);
  EXPECT_THROW(parse_rational("1/2/"), std::invalid_argument);
  EXPECT_EQ(parse_rational("10/4"), mpq_class(5, 2));
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

// The message of the PolynomialParseError thrown for `text`, or "" if it parses.
std::string parse_error(const std::string& text, int n) {
  try {
    Polynomial::parse(text, n);
  } catch (const PolynomialParseError& e) {
    return e.what();
  }
  return "";
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
std::string repeat(const std::string& s, int k) {
  std::string out;
  for (int i = 0; i < k; ++i) out += s;
  return out;
}

// Exponents were uint32 and wrapped: ((x1^4096)^4096)^256 = x1^(2^32) was read as 1.
TEST(PolynomialLimits, ExponentsNeverWrap) {
  const std::string e = parse_error("x1^2 + x2^2 + x3^2 - ((x1^4096)^4096)^256", 3);
  EXPECT_TRUE(contains(e, "exponent 4096 too large")) << e;
  EXPECT_TRUE(contains(e, "256")) << e;
  // The exponent is compared as a digit string, whatever its length.
  EXPECT_TRUE(contains(parse_error("x1^99999999999999999999999", 1), "too large"));
  // A product of two admissible powers above the degree limit.
  EXPECT_TRUE(contains(parse_error("x1^200 * x1^57", 1), "degree 257"));
  EXPECT_TRUE(contains(parse_error("(x1^128)^3", 1), "degree 384"));
  // Just inside: degree 256.
  Polynomial p = Polynomial::parse("(x1^128)^2 * 1 + x1^200 * x1^56 - x1^256", 1);
  EXPECT_EQ(p, Polynomial::parse("x1^256", 1));
  EXPECT_EQ(p.degree(), 256);
  EXPECT_EQ(Polynomial::parse("2^256", 1).terms()[0].coefficient, mpq_class(mpz_class(1) << 256));
  // Outside the parser, an exponent that would pass 2^32 - 1 throws instead of wrapping.
  Polynomial big = Polynomial::variable(0, 1).pow(1u << 31);
  EXPECT_THROW(big * big, std::overflow_error);
}

// Variable indices were truncated to 9 digits: x0000000031 was read as x3.
TEST(PolynomialLimits, VariableIndexIsReadWhole) {
  EXPECT_TRUE(contains(parse_error("x0000000031^2 - 1", 3), "leading zeros")) << parse_error("x0000000031^2 - 1", 3);
  EXPECT_TRUE(contains(parse_error("x03", 3), "leading zeros"));
  EXPECT_TRUE(contains(parse_error("x31", 3), "variable x31 out of range x1..x3"));
  EXPECT_TRUE(contains(parse_error("x1000000003", 3), "variable x1000000003 out of range"));
  EXPECT_TRUE(contains(parse_error("x99999999999999999999999999", 3), "out of range"));
  EXPECT_TRUE(contains(parse_error("x0", 3), "variable x0 out of range"));
  EXPECT_EQ(Polynomial::parse("x10", 10), Polynomial::variable(9, 10));
}

TEST(PolynomialLimits, ChainedDivisionIsRefused) {
  EXPECT_TRUE(contains(parse_error("x1/2/3", 1), "ambiguous"));
  EXPECT_TRUE(contains(parse_error("1/2/3", 1), "ambiguous"));
  EXPECT_EQ(Polynomial::parse("(x1/2)/3", 1), Polynomial::parse("x1/6", 1));
  EXPECT_EQ(Polynomial::parse("x1/2*x1/3", 1), Polynomial::parse("x1^2/6", 1));
}

// (x1^9999)^9999 was expanded by 10^8 rational products; (x1+x2+x3+1)^400 had 10^7 terms.
// Every limit is checked before the work it bounds, so these are refused at once.
TEST(PolynomialLimits, TermsAndDegreeAreBoundedBeforeExpanding) {
  EXPECT_TRUE(contains(parse_error("x1^2 + x2^2 + x3^2 - (x1^9999)^9999 - 1", 3), "too large"));
  EXPECT_TRUE(contains(parse_error("(x1+x2+x3+1)^400", 3), "too large"));
  // Degree 200 is admissible, but C(203, 3) = 1373701 monomials are not.
  const std::string t = parse_error("(x1+x2+x3+1)^200", 3);
  EXPECT_TRUE(contains(t, "too large")) << t;
  EXPECT_TRUE(contains(t, "10000 terms")) << t;
  // A power is bounded by the products of e of its terms, C(t + e - 1, e): C(41, 3) = 10660.
  EXPECT_TRUE(contains(parse_error("(x1+x2+x3+1)^38", 3), "more than 10000 terms"));
  // The term products of the whole expansion: (x1+x2+x3+1)^33 needs under 10^6 of them (its
  // 7140 terms are exact multinomial coefficients), ^34 would need 1032987 and is refused unworked.
  Polynomial p33 = Polynomial::parse("(x1+x2+x3+1)^33", 3);
  EXPECT_EQ(p33.terms().size(), 7140u);
  std::vector<mpq_class> ones{1, 1, 1};
  EXPECT_EQ(p33.evaluate(std::span<const mpq_class>(ones)), mpq_class(mpz_class(1) << 66));  // 4^33
  const std::string p = parse_error("(x1+x2+x3+1)^34", 3);
  EXPECT_TRUE(contains(p, "too large") && contains(p, "1000000 term products")) << p;
  // Terms just inside and just outside the limit: 100 x 100 = 10000 distinct monomials.
  auto sum_of_powers = [](const char* x, int k) {
    std::string t = "(";
    for (int i = 0; i < k; ++i) t += (i ? "+" : "") + std::string(x) + "^" + std::to_string(i);
    return t + ")";
  };
  const std::string a100 = sum_of_powers("x1", 100), b100 = sum_of_powers("x2", 100);
  EXPECT_EQ(Polynomial::parse(a100 + "*" + b100, 3).terms().size(), 10000u);
  EXPECT_TRUE(contains(parse_error(a100 + "*" + sum_of_powers("x2", 101), 3), "more than 10000 terms"));
  // Sums are checked too.
  EXPECT_TRUE(contains(parse_error(a100 + "*" + b100 + " + x3", 3), "10001 terms"));
}

TEST(PolynomialLimits, CoefficientsTextAndLiterals) {
  // 10^1000 has 3322 bits: its 6th power is within 20000 bits, its 7th is not.
  EXPECT_EQ(parse_error("(1e1000*x1 + 1)^6", 1), "");
  EXPECT_TRUE(contains(parse_error("(1e1000*x1 + 1)^7", 1), "20000 bits"));
  EXPECT_TRUE(contains(parse_error("1e99999*x1", 1), "too large"));
  // A literal at the limit is read (as a decimal fraction, within the coefficient bits); one
  // character more is not.
  const std::size_t L = PolynomialLimits::max_literal_length;
  EXPECT_EQ(Polynomial::parse("x1 - 0." + std::string(L - 2, '0') + "", 1).terms().size(), 1u);
  EXPECT_TRUE(contains(parse_error("x1 - 0." + std::string(L - 1, '0'), 1), "literal too large"));
  // The writer's own text of a coefficient near the bit limit reads back (a fuzzing finding:
  // 2^-19000 prints as a decimal of about 19,000 characters).
  const Polynomial tiny = Polynomial::parse("x1 - (1/2^200)^95", 1);
  EXPECT_EQ(Polynomial::parse(tiny.to_string(), 1), tiny);
  // The whole text.
  std::string longest = "x1" + std::string(PolynomialLimits::max_text_length - 2, ' ');
  EXPECT_EQ(parse_error(longest, 1), "");
  EXPECT_TRUE(contains(parse_error(longest + " ", 1), "too large"));
}

// 50,000 nested parentheses overflowed the stack (exit 139). Nesting is counted and refused.
TEST(PolynomialLimits, DeepNestingIsRefusedWithoutRecursingFurther) {
  const int max = PolynomialLimits::max_nesting;
  EXPECT_EQ(parse_error(repeat("(", max) + "x1" + repeat(")", max), 1), "");
  EXPECT_TRUE(contains(parse_error(repeat("(", max + 1) + "x1" + repeat(")", max + 1), 1), "too deeply nested"));
  EXPECT_TRUE(contains(parse_error(repeat("(", 45000) + "x1" + repeat(")", 45000), 1), "too deeply nested"));
  EXPECT_EQ(parse_error(repeat("-", max) + "x1", 1), "");
  EXPECT_TRUE(contains(parse_error(repeat("-", 50000) + "x1", 1), "too deeply nested"));
  EXPECT_TRUE(contains(parse_error(repeat("-(", 30000) + "x1" + repeat(")", 30000), 1), "too deeply nested"));
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

// The canonical scale (the spec reader's): c p and p give the same polynomial for every rational
// c > 0, however large or small; signs are kept; a dyadic polynomial with largest |coefficient|
// in [1, 2) and integer-gcd 1 after clearing is left as it is.
TEST(Polynomial, CanonicalScaleForgetsOnlyAPositiveFactor) {
  const auto p = Polynomial::parse("x1^2 + x2^2 + x3^2 - 1", 3);
  EXPECT_EQ(at_canonical_scale(p), p);
  const mpz_class two1000 = mpz_class(1) << 1000;
  for (const mpq_class& c : {mpq_class(two1000), mpq_class(mpz_class(1), two1000), exact::parse_rational("1e400"),
                             exact::parse_rational("1e-400"), mpq_class(3, 7), mpq_class(6)}) {
    EXPECT_EQ(at_canonical_scale(p.scaled(c)), p) << c.get_str().substr(0, 40);
    EXPECT_EQ(at_canonical_scale(p.scaled(-c)), -p);  // the sign is kept
  }
  // Largest |coefficient| in [1, 2), the ratios kept exactly.
  const auto torus = Polynomial::parse("(x1^2 + x2^2 + x3^2 + 3)^2 - 16*(x1^2 + x2^2)", 3);
  const auto t = at_canonical_scale(torus);
  EXPECT_EQ(t, torus.scaled(mpq_class(1, 8)));  // largest |coefficient| 10
  const auto q = at_canonical_scale(Polynomial::parse("0.1*x1^2 + x2 - 3/7", 2));  // 7 x1^2 + 70 x2 - 30, over 64
  EXPECT_EQ(q, Polynomial::parse("7/64*x1^2 + 70/64*x2 - 30/64", 2));
  EXPECT_TRUE(at_canonical_scale(Polynomial(2)).is_zero());
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
}  // namespace delcert::exact
