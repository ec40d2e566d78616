#include "exact/polynomial.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace delcert {

mpq_class parse_rational(std::string_view text) {
  auto fail = [&] { throw std::invalid_argument("not a rational number: '" + std::string(text) + "'"); };
  std::string s(text);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(s.begin());
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  if (s.empty()) fail();
  if (auto slash = s.find('/'); slash != std::string::npos) {
    mpq_class num = parse_rational(s.substr(0, slash));
    mpq_class den = parse_rational(s.substr(slash + 1));
    if (den == 0) throw std::invalid_argument("zero denominator in '" + s + "'");
    return num / den;
  }
  std::size_t i = 0;
  bool negative = false;
  if (s[i] == '+' || s[i] == '-') negative = (s[i++] == '-');
  std::string digits;
  long frac_digits = 0;
  bool any_digit = false, seen_point = false;
  for (; i < s.size(); ++i) {
    char c = s[i];
    if (std::isdigit(static_cast<unsigned char>(c))) {
      digits += c;
      any_digit = true;
      if (seen_point) ++frac_digits;
    } else if (c == '.' && !seen_point) {
      seen_point = true;
    } else {
      break;
    }
  }
  if (!any_digit) fail();
  long exp10 = 0;
  if (i < s.size()) {
    if (s[i] != 'e' && s[i] != 'E') fail();
    ++i;
    bool eneg = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) eneg = (s[i++] == '-');
    if (i >= s.size()) fail();
    long e = 0;
    for (; i < s.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(s[i]))) fail();
      e = e * 10 + (s[i] - '0');
      if (e > 100000) fail();
    }
    exp10 = eneg ? -e : e;
  }
  mpz_class n(digits, 10);
  exp10 -= frac_digits;
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(exp10 < 0 ? -exp10 : exp10));
  mpq_class q = exp10 >= 0 ? mpq_class(n * p) : mpq_class(n, p);
  q.canonicalize();
  return negative ? mpq_class(-q) : q;
}

std::string rational_to_string(const mpq_class& value) {
  mpq_class q = value;
  q.canonicalize();
  mpz_class den = q.get_den();
  // A finite decimal expansion exists iff the reduced denominator is 2^a 5^b.
  mpz_class d = den;
  unsigned long twos = mpz_remove(d.get_mpz_t(), d.get_mpz_t(), mpz_class(2).get_mpz_t());
  unsigned long fives = mpz_remove(d.get_mpz_t(), d.get_mpz_t(), mpz_class(5).get_mpz_t());
  if (d != 1 || den == 1) return den == 1 ? q.get_num().get_str() : q.get_str();
  unsigned long k = std::max(twos, fives);
  mpz_class scale;
  mpz_ui_pow_ui(scale.get_mpz_t(), 10, k);
  mpz_class scaled = q.get_num() * scale / den;  // exact
  bool neg = scaled < 0;
  if (neg) scaled = -scaled;
  std::string s = scaled.get_str();
  if (s.size() <= k) s = std::string(k + 1 - s.size(), '0') + s;
  std::string out(neg ? "-" : "");
  out.append(s, 0, s.size() - k);
  out.push_back('.');
  out.append(s, s.size() - k, k);
  return out;
}

namespace {

// Recursive-descent parser:  expr := term (('+'|'-') term)* ; term := unary (('*'|'/') unary)* ;
// unary := ('+'|'-') unary | power ; power := atom ('^' integer)? ; atom := number | x<i> | '(' expr ')'
class Parser {
 public:
  Parser(std::string_view s, int n) : s_(s), n_(n) {}

  Polynomial parse_all() {
    skip();
    if (pos_ >= s_.size()) throw PolynomialParseError("empty expression", pos_);
    Polynomial p = expr();
    skip();
    if (pos_ != s_.size())
      throw PolynomialParseError(std::string("unexpected character '") + s_[pos_] + "'", pos_);
    return p;
  }

 private:
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  Polynomial expr() {
    Polynomial p = term();
    for (;;) {
      if (accept('+')) p = p + term();
      else if (accept('-')) p = p - term();
      else return p;
    }
  }
  Polynomial term() {
    Polynomial p = unary();
    for (;;) {
      if (accept('*')) {
        p = p * unary();
      } else {
        skip();
        std::size_t at = pos_;
        if (!accept('/')) return p;
        Polynomial d = unary();
        if (!d.is_constant()) throw PolynomialParseError("division by a non-constant expression", at);
        if (d.is_zero()) throw PolynomialParseError("division by zero", at);
        p = p.scaled(1 / d.terms()[0].coefficient);
      }
    }
  }
  Polynomial unary() {
    if (accept('-')) return -unary();
    if (accept('+')) return unary();
    return power();
  }
  Polynomial power() {
    Polynomial base = atom();
    if (accept('^')) {
      skip();
      std::size_t start = pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      if (start == pos_) throw PolynomialParseError("exponent must be a non-negative integer literal", start);
      if (pos_ - start > 4) throw PolynomialParseError("exponent too large", start);
      base = base.pow(static_cast<unsigned>(std::stoul(std::string(s_.substr(start, pos_ - start)))));
    }
    return base;
  }
  Polynomial atom() {
    skip();
    if (pos_ >= s_.size()) throw PolynomialParseError("unexpected end of expression", pos_);
    char c = s_[pos_];
    if (c == '(') {
      ++pos_;
      Polynomial p = expr();
      if (!accept(')')) throw PolynomialParseError("missing ')'", pos_);
      return p;
    }
    if (c == 'x') {
      std::size_t start = pos_++;
      std::size_t dstart = pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      if (dstart == pos_) throw PolynomialParseError("variable must be x1..x" + std::to_string(n_), start);
      long idx = std::stol(std::string(s_.substr(dstart, std::min<std::size_t>(pos_ - dstart, 9))));
      if (idx < 1 || idx > n_)
        throw PolynomialParseError("variable x" + std::to_string(idx) + " out of range x1..x" + std::to_string(n_),
                                   start);
      return Polynomial::variable(static_cast<int>(idx - 1), n_);
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::size_t start = pos_;
      while (pos_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
        std::size_t save = pos_++;
        if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
        std::size_t ds = pos_;
        while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
        if (ds == pos_) pos_ = save;  // not an exponent after all
      }
      try {
        return Polynomial::constant(parse_rational(s_.substr(start, pos_ - start)), n_);
      } catch (const std::invalid_argument&) {
        throw PolynomialParseError("malformed number '" + std::string(s_.substr(start, pos_ - start)) + "'", start);
      }
    }
    throw PolynomialParseError(std::string("unexpected character '") + c + "'", pos_);
  }

  std::string_view s_;
  int n_;
  std::size_t pos_ = 0;
};

}  // namespace

Polynomial Polynomial::parse(std::string_view text, int num_variables) {
  return Parser(text, num_variables).parse_all();
}

Polynomial Polynomial::constant(const mpq_class& c, int n) {
  Polynomial p(n);
  if (c != 0) p.terms_.push_back(Term{c, Monomial{std::vector<std::uint32_t>(n, 0)}});
  return p;
}

Polynomial Polynomial::variable(int index, int n) {
  Polynomial p(n);
  Monomial m{std::vector<std::uint32_t>(n, 0)};
  m.exponents[index] = 1;
  p.terms_.push_back(Term{mpq_class(1), std::move(m)});
  return p;
}

bool Polynomial::is_constant() const {
  return terms_.empty() ||
         (terms_.size() == 1 && std::all_of(terms_[0].monomial.exponents.begin(),
                                            terms_[0].monomial.exponents.end(), [](auto e) { return e == 0; }));
}

int Polynomial::degree() const {
  int d = 0;
  for (const auto& t : terms_) {
    int s = 0;
    for (auto e : t.monomial.exponents) s += static_cast<int>(e);
    d = std::max(d, s);
  }
  return d;
}

void Polynomial::normalize() {
  // Decreasing monomial order (graded lexicographic would also do; plain lex keeps it simple).
  std::sort(terms_.begin(), terms_.end(), [](const Term& a, const Term& b) { return a.monomial > b.monomial; });
  std::vector<Term> out;
  for (auto& t : terms_) {
    if (!out.empty() && out.back().monomial == t.monomial) out.back().coefficient += t.coefficient;
    else out.push_back(std::move(t));
  }
  out.erase(std::remove_if(out.begin(), out.end(), [](const Term& t) { return t.coefficient == 0; }), out.end());
  terms_ = std::move(out);
}

Polynomial Polynomial::operator+(const Polynomial& o) const {
  Polynomial r(std::max(num_vars_, o.num_vars_));
  r.terms_ = terms_;
  r.terms_.insert(r.terms_.end(), o.terms_.begin(), o.terms_.end());
  // Operands over fewer variables (e.g. a default-constructed zero) get their exponent vectors
  // padded, so that equal monomials compare equal and merge.
  for (auto& t : r.terms_) t.monomial.exponents.resize(r.num_vars_, 0);
  r.normalize();
  return r;
}

Polynomial Polynomial::operator-() const { return scaled(mpq_class(-1)); }
Polynomial Polynomial::operator-(const Polynomial& o) const { return *this + (-o); }

Polynomial Polynomial::scaled(const mpq_class& c) const {
  Polynomial r(num_vars_);
  if (c == 0) return r;
  r.terms_ = terms_;
  for (auto& t : r.terms_) t.coefficient *= c;
  return r;
}

Polynomial Polynomial::operator*(const Polynomial& o) const {
  Polynomial r(std::max(num_vars_, o.num_vars_));
  for (const auto& a : terms_)
    for (const auto& b : o.terms_) {
      Monomial m{std::vector<std::uint32_t>(r.num_vars_, 0)};
      // Operands may have fewer variables than the result: missing exponents are 0.
      for (std::size_t v = 0; v < a.monomial.exponents.size(); ++v) m.exponents[v] += a.monomial.exponents[v];
      for (std::size_t v = 0; v < b.monomial.exponents.size(); ++v) m.exponents[v] += b.monomial.exponents[v];
      r.terms_.push_back(Term{a.coefficient * b.coefficient, std::move(m)});
    }
  r.normalize();
  return r;
}

Polynomial Polynomial::pow(unsigned e) const {
  Polynomial result = constant(mpq_class(1), num_vars_);
  Polynomial base = *this;
  while (e) {
    if (e & 1u) result = result * base;
    e >>= 1u;
    if (e) base = base * base;
  }
  return result;
}

bool Polynomial::operator==(const Polynomial& o) const {
  if (terms_.size() != o.terms_.size()) return false;
  for (std::size_t i = 0; i < terms_.size(); ++i)
    if (terms_[i].coefficient != o.terms_[i].coefficient || terms_[i].monomial != o.terms_[i].monomial) return false;
  return true;
}

Polynomial Polynomial::derivative(int var) const {
  Polynomial r(num_vars_);
  for (const auto& t : terms_) {
    auto e = t.monomial.exponents[var];
    if (e == 0) continue;
    Term d = t;
    d.coefficient *= e;
    d.monomial.exponents[var] = e - 1;
    r.terms_.push_back(std::move(d));
  }
  r.normalize();
  return r;
}

std::string Polynomial::to_string() const {
  if (terms_.empty()) return "0";
  std::ostringstream out;
  bool first = true;
  for (const auto& t : terms_) {
    mpq_class c = t.coefficient;
    bool neg = c < 0;
    if (neg) c = -c;
    out << (first ? (neg ? "-" : "") : (neg ? " - " : " + "));
    first = false;
    bool has_var = false;
    std::ostringstream mono;
    for (std::size_t v = 0; v < t.monomial.exponents.size(); ++v) {
      auto e = t.monomial.exponents[v];
      if (!e) continue;
      mono << (has_var ? "*" : "") << 'x' << (v + 1);
      if (e > 1) mono << '^' << e;
      has_var = true;
    }
    if (!has_var) out << rational_to_string(c);
    else if (c == 1) out << mono.str();
    else out << rational_to_string(c) << '*' << mono.str();
  }
  return out.str();
}

Polynomial::IntegerForm Polynomial::integer_form() const {
  IntegerForm f;
  f.denominator = 1;
  for (const auto& t : terms_) mpz_lcm(f.denominator.get_mpz_t(), f.denominator.get_mpz_t(), t.coefficient.get_den_mpz_t());
  for (const auto& t : terms_) f.numerators.push_back(t.coefficient.get_num() * (f.denominator / t.coefficient.get_den()));
  return f;
}

double Polynomial::evaluate(std::span<const double> x) const {
  return evaluate_with<double>(x, [&](std::size_t i) { return terms_[i].coefficient.get_d(); });
}

mpq_class Polynomial::evaluate(std::span<const mpq_class> x) const {
  return evaluate_with<mpq_class>(x, [&](std::size_t i) { return terms_[i].coefficient; });
}

DoublePolynomial::DoublePolynomial(const Polynomial& p) : num_vars_(p.num_variables()) {
  for (const auto& t : p.terms()) {
    coefficients_.push_back(t.coefficient.get_d());
    exponents_.insert(exponents_.end(), t.monomial.exponents.begin(), t.monomial.exponents.end());
  }
}

double DoublePolynomial::operator()(std::span<const double> x) const {
  double sum = 0;
  const std::uint32_t* e = exponents_.data();
  for (double c : coefficients_) {
    double t = c;
    for (int v = 0; v < num_vars_; ++v, ++e)
      for (std::uint32_t k = 0; k < *e; ++k) t *= x[v];
    sum += t;
  }
  return sum;
}

}  // namespace delcert
