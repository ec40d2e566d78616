// Multivariate polynomials with exact rational coefficients.
//
// A Polynomial is a finite sum of terms c * x1^e1 * ... * xN^eN with c an exact rational
// (GMP mpq). It is parsed from strings such as "x1^2 + x2^2 - 1/4" or "0.1*x1*x3 - 2.5",
// where every decimal literal is the exact rational it spells ("0.1" is 1/10).
//
// Evaluation is templated on the number type so that the same polynomial is evaluated in
// double (the producer), in interval arithmetic (the certifier's filter) and exactly (the
// certifier's fallback). For the exact, division-free path, integer_form() gives integer
// coefficients a_i and a positive integer denominator D with p = (sum a_i x^e_i) / D, so the
// sign of p(x) is the sign of sum a_i x^e_i, which needs only ring operations.
#pragma once

#include <gmpxx.h>

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace delcert::exact {

// A parse error carries the 0-based character offset where the problem was found.
struct PolynomialParseError : std::runtime_error {
  PolynomialParseError(const std::string& what, std::size_t offset)
      : std::runtime_error(what), offset(offset) {}
  std::size_t offset;
};

// Parses a rational literal: integer ("-3"), decimal ("0.125", "1e-3", "2.5E+2") or fraction
// ("1/3", "-0.5/3": two such decimals separated by ONE slash; "1/2/3" is refused, it has no one
// obvious meaning). Decimal exponents are limited to |e| <= 100000. Surrounding blanks are ignored.
// Throws std::invalid_argument ("not a rational number: ...") on anything else.
mpq_class parse_rational(std::string_view text);

// Limits of Polynomial::parse. A polynomial beyond them is refused with a PolynomialParseError
// whose message contains "too large" (or "too deeply nested") and names the limit; every check
// is made BEFORE the expensive operation, so a refusal costs well under a second. They are far
// above what a manifold spec needs (the built-in specs have degree <= 4 and <= 30 terms).
struct PolynomialLimits {
  static constexpr std::size_t max_text_length = 100000;     // characters of the whole expression
  // Characters of one number literal. At least the longest literal the writer (to_string) prints
  // for a coefficient within max_coefficient_bits, so that every polynomial's own text reads back:
  // a decimal expansion n / (2^a 5^b) has at most max(a, b) + 0.31 bits(n) + 0.7 max(a, b) + 3
  // characters, below 1.7 * 20,000 + 3 (a 1,000 limit failed on fuzzed input, fuzz/regressions).
  static constexpr std::size_t max_literal_length = 50000;
  static constexpr int max_degree = 256;                     // total degree of every sub-expression;
                                                             // also the largest exponent after '^'
  static constexpr std::size_t max_terms = 10000;            // terms of every sub-expression
  static constexpr std::size_t max_products = 1000000;       // term products in the whole expansion,
                                                             // each counted 1 + (bits of the two
                                                             // coefficients) / 2048 times
  static constexpr std::size_t max_coefficient_bits = 20000;  // bits of numerator + denominator
  static constexpr int max_nesting = 200;                    // parentheses and unary signs
};

// Exact decimal string of a rational if it has a finite decimal expansion, else "p/q".
std::string rational_to_string(const mpq_class& q);

struct Monomial {
  std::vector<std::uint32_t> exponents;  // one per variable, #vars
  auto operator<=>(const Monomial&) const = default;
};

struct Term {
  mpq_class coefficient;  // never zero inside a Polynomial
  Monomial monomial;
};

class Polynomial {
 public:
  Polynomial() = default;
  explicit Polynomial(int num_variables) : num_vars_(num_variables) {}

  // Parses `text` over the variables x1..x{num_variables}. Division is allowed only by a
  // non-zero constant sub-expression, and not twice in a row ("a/b/c" is refused as ambiguous:
  // write "(a/b)/c"); exponents are non-negative integer literals. A variable is 'x' followed by
  // its index in 1..num_variables written without leading zeros ("x07" is refused). Enforces
  // PolynomialLimits.
  static Polynomial parse(std::string_view text, int num_variables);
  static Polynomial constant(const mpq_class& c, int num_variables);
  static Polynomial variable(int index, int num_variables);  // x_{index+1}, 0-based index
  // c + sum_j linear[j] x_{j+1}, over linear.size() variables (one construction, no merges).
  static Polynomial affine(const mpq_class& c, std::span<const mpq_class> linear);

  int num_variables() const { return num_vars_; }
  const std::vector<Term>& terms() const { return terms_; }
  bool is_zero() const { return terms_.empty(); }
  bool is_constant() const;
  int degree() const;

  // Multiplication and powers throw std::overflow_error rather than let an exponent wrap.
  Polynomial operator+(const Polynomial& o) const;
  // In place, consuming o: a linear merge when both are normalised (always, for polynomials built
  // by this class), so that parsing a sum of k terms costs O(k^2) moves, not O(k^2 log k) copies.
  // operator+ is a copy followed by this merge.
  Polynomial& operator+=(Polynomial&& o);
  Polynomial operator-(const Polynomial& o) const;
  Polynomial operator*(const Polynomial& o) const;
  Polynomial operator-() const;
  Polynomial scaled(const mpq_class& c) const;
  Polynomial pow(unsigned e) const;
  bool operator==(const Polynomial& o) const;

  // Exact partial derivative with respect to x_{var+1} (0-based var).
  Polynomial derivative(int var) const;

  // Canonical text: terms in decreasing monomial order, exact rational coefficients. parse() reads
  // it back to the same polynomial whenever it is within PolynomialLimits::max_text_length; an
  // expanded text can be longer than the text it came from ("(x1+...+x9)^7" has 6435 terms), and
  // such a text is refused like any other over-long input.
  std::string to_string() const;

  // Integer form: p = (sum numerators[i] * x^terms()[i].monomial) / denominator, denominator > 0.
  struct IntegerForm {
    std::vector<mpz_class> numerators;  // aligned with terms()
    mpz_class denominator;
  };
  IntegerForm integer_form() const;

  // Evaluates with coefficients supplied by `coef(term_index)` (so that each number type can
  // convert the exact rational coefficient the way it needs: rounded, enclosed or exact).
  // Powers are computed by repeated multiplication: exact in exact types, and for intervals
  // an enclosure of the true value.
  template <class T, class CoefFn>
  T evaluate_with(std::span<const T> x, CoefFn&& coef) const {
    T sum(0);
    for (std::size_t i = 0; i < terms_.size(); ++i) {
      T t = coef(i);
      const auto& e = terms_[i].monomial.exponents;
      for (std::size_t v = 0; v < e.size(); ++v)
        for (std::uint32_t k = 0; k < e[v]; ++k) t = t * x[v];
      sum = sum + t;
    }
    return sum;
  }

  // Plain double evaluation (coefficients rounded to nearest double).
  double evaluate(std::span<const double> x) const;
  // Exact evaluation at a rational point.
  mpq_class evaluate(std::span<const mpq_class> x) const;

 private:
  void normalize();  // sort, merge equal monomials, drop zeros
  int num_vars_ = 0;
  std::vector<Term> terms_;
};

// A polynomial prepared for fast double evaluation: coefficients rounded once.
class DoublePolynomial {
 public:
  DoublePolynomial() = default;
  explicit DoublePolynomial(const Polynomial& p);
  // Terms given directly: coefficients[i] times prod_v x_v^exponents[i * num_vars + v].
  DoublePolynomial(int num_vars, std::span<const double> coefficients, std::span<const std::uint32_t> exponents);
  double operator()(std::span<const double> x) const;
  int num_variables() const { return num_vars_; }

 private:
  int num_vars_ = 0;
  std::vector<double> coefficients_;
  // The non-zero exponents only: term i owns factors_[ends_[i - 1] .. ends_[i]) (ends_[-1] = 0),
  // each (variable, exponent) in increasing variable order (the same products as the dense loop).
  struct Factor {
    std::uint32_t var, exponent;
  };
  std::vector<Factor> factors_;
  std::vector<std::uint32_t> ends_;
};

}  // namespace delcert::exact
