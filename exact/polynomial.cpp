#include "exact/polynomial.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <unordered_map>
#include <sstream>

namespace delcert::exact {

mpq_class parse_rational(std::string_view text) {
  auto fail = [&] { throw std::invalid_argument("not a rational number: '" + std::string(text) + "'"); };
  std::string s(text);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(s.begin());
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  if (s.empty()) fail();
  if (auto slash = s.find('/'); slash != std::string::npos) {
    if (s.find('/', slash + 1) != std::string::npos)  // "1/2/3": (1/2)/3 or 1/(2/3)?
      throw std::invalid_argument("not a rational number: '" + std::string(text) +
                                  "' has more than one '/'; write one fraction such as \"1/6\"");
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

using Limits = PolynomialLimits;

// Largest bit size (numerator + denominator) of a coefficient.
std::size_t coefficient_bits(const Polynomial& p) {
  std::size_t b = 0;
  for (const auto& t : p.terms())
    b = std::max(b, mpz_sizeinbase(t.coefficient.get_num_mpz_t(), 2) + mpz_sizeinbase(t.coefficient.get_den_mpz_t(), 2));
  return b;
}

// Number of monomials of total degree <= d in n variables, C(n + d, n), saturated at cap + 1.
std::size_t monomials_up_to(int n, int d, std::size_t cap) {
  // C(d + k, k) for k = 1..n, each step exact: C(d+k, k) = C(d+k-1, k-1) * (d+k) / k. The
  // intermediate product stays below (cap + 1) * (d + n) <= 10^4 * 400, far from overflow.
  unsigned long long c = 1;
  for (int k = 1; k <= n; ++k) {
    c = c * static_cast<unsigned long long>(d + k) / static_cast<unsigned long long>(k);
    if (c > cap) return cap + 1;
  }
  return static_cast<std::size_t>(c);
}

// An upper bound on the number of terms of p^k for p with t terms and degree d over n variables:
// the products of k of the t terms (multisets: C(t + k - 1, k)) and the monomials of degree
// <= k d, whichever is smaller; saturated at cap + 1.
std::size_t power_terms_bound(std::size_t t, int d, int n, int k, std::size_t cap) {
  if (k == 0) return 1;
  if (t == 0) return 0;
  // C(t - 1 + k, j) for j = 1..min(k, t - 1), exact as above; t <= cap + 1 and k <= 256.
  const unsigned long long top = t - 1 + static_cast<unsigned long long>(k);
  const unsigned long long steps = std::min<unsigned long long>(static_cast<unsigned long long>(k), t - 1);
  unsigned long long c = 1;
  for (unsigned long long j = 1; j <= steps && c <= cap; ++j) c = c * (top - steps + j) / j;
  return std::min<std::size_t>(std::min<unsigned long long>(c, cap + 1), monomials_up_to(n, k * d, cap));
}

// Recursive-descent parser:  expr := term (('+'|'-') term)* ; term := unary (('*'|'/') unary)* ;
// unary := ('+'|'-') unary | power ; power := atom ('^' integer)? ; atom := number | x<i> | '(' expr ')'
// Every operation is checked against PolynomialLimits before it is carried out.
class Parser {
 public:
  Parser(std::string_view s, int n) : s_(s), n_(n) {}

  Polynomial parse_all() {
    if (s_.size() > Limits::max_text_length)
      throw PolynomialParseError("polynomial too large: " + std::to_string(s_.size()) + " characters (the limit is " +
                                     std::to_string(Limits::max_text_length) + ")",
                                 0);
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
  // Parentheses and unary signs recurse; deeper nesting than the limit is refused before the
  // stack can overflow.
  struct Nest {
    Parser& p;
    Nest(Parser& parser, std::size_t at) : p(parser) {
      if (++p.depth_ > Limits::max_nesting)
        throw PolynomialParseError("polynomial too deeply nested: more than " + std::to_string(Limits::max_nesting) +
                                       " levels of parentheses and signs (the limit)",
                                   at);
    }
    ~Nest() { --p.depth_; }
  };
  void check_size(const Polynomial& p, std::size_t at) const {
    if (p.terms().size() > Limits::max_terms)
      throw PolynomialParseError("polynomial too large: " + std::to_string(p.terms().size()) +
                                     " terms (the limit is " + std::to_string(Limits::max_terms) + ")",
                                 at);
    if (std::size_t b = coefficient_bits(p); b > Limits::max_coefficient_bits)
      throw PolynomialParseError("polynomial too large: a coefficient of " + std::to_string(b) +
                                     " bits (the limit is " + std::to_string(Limits::max_coefficient_bits) + ")",
                                 at);
  }
  [[noreturn]] void too_many_products(std::size_t more, std::size_t at) const {
    throw PolynomialParseError("polynomial too large: expanding it takes more than " +
                                   std::to_string(Limits::max_products) + " term products (the limit; " +
                                   std::to_string(products_ + more) + " needed so far)",
                               at);
  }
  [[noreturn]] void too_many_terms(std::size_t bound, std::size_t at) const {
    throw PolynomialParseError("polynomial too large: a sub-expression may have " +
                                   (bound > Limits::max_terms ? "more than " + std::to_string(Limits::max_terms)
                                                              : std::to_string(bound)) +
                                   " terms (the limit is " + std::to_string(Limits::max_terms) + " terms)",
                               at);
  }
  // a * b, refused before it is computed if the result could exceed a limit.
  // `known_bound`: a bound on the result's terms the caller knows (power_of's).
  Polynomial multiply(const Polynomial& a, const Polynomial& b, std::size_t at,
                      std::size_t known_bound = static_cast<std::size_t>(-1)) {
    const int d = a.degree() + b.degree();
    if (d > Limits::max_degree)
      throw PolynomialParseError("polynomial too large: a product of degree " + std::to_string(d) +
                                     " (the limit on the total degree is " + std::to_string(Limits::max_degree) + ")",
                                 at);
    const std::size_t na = a.terms().size(), nb = b.terms().size();  // each <= max_terms: no overflow
    const std::size_t bits = coefficient_bits(a) + coefficient_bits(b);
    // Cost of the products: large coefficients multiply more slowly (the weight keeps the whole
    // expansion near a second); na * nb * weight <= 10^8 * 20 fits easily.
    const std::size_t cost = na * nb * (1 + bits / 2048);
    if (products_ + cost > Limits::max_products) too_many_products(cost, at);
    if (std::size_t bound = std::min({na * nb, monomials_up_to(n_, d, Limits::max_terms), known_bound});
        bound > Limits::max_terms)
      too_many_terms(bound, at);
    if (bits > Limits::max_coefficient_bits)
      throw PolynomialParseError("polynomial too large: a product with coefficients of more than " +
                                     std::to_string(Limits::max_coefficient_bits) + " bits (the limit)",
                                 at);
    products_ += cost;
    Polynomial r = a * b;
    check_size(r, at);
    return r;
  }
  // base^e by square-and-multiply. The whole schedule is bounded first (terms of every
  // intermediate power by power_terms_bound, products by their sum), so that a power beyond the
  // limits is refused before any of it is computed; each product is then checked again.
  Polynomial power_of(Polynomial base, int e, std::size_t at) {
    const std::size_t t = base.terms().size();
    const int d = base.degree();
    auto bound = [&](int k) { return power_terms_bound(t, d, n_, k, Limits::max_terms); };
    if (std::size_t b = bound(e); b > Limits::max_terms) too_many_terms(b, at);
    std::size_t planned = 0;
    for (int k = e, have = 0, sq = 1; k; sq *= 2) {
      if (k & 1) planned += bound(have) * bound(sq), have += sq;
      k >>= 1;
      if (k) planned += bound(sq) * bound(sq);
      if (products_ + planned > Limits::max_products) too_many_products(planned, at);
    }
    Polynomial result = Polynomial::constant(mpq_class(1), n_);
    for (int k = e, have = 0, sq = 1; k; sq *= 2) {
      if (k & 1) result = multiply(result, base, at, bound(have + sq)), have += sq;
      k >>= 1;
      if (k) base = multiply(base, base, at, bound(2 * sq));
    }
    return result;
  }
  Polynomial expr() {
    Polynomial p = term();
    for (;;) {
      skip();
      std::size_t at = pos_;
      if (accept('+')) p += term();
      else if (accept('-')) p += -term();
      else return p;
      check_size(p, at);
    }
  }
  Polynomial term() {
    Polynomial p = unary();
    bool after_division = false;
    for (;;) {
      skip();
      std::size_t at = pos_;
      if (accept('*')) {
        p = multiply(p, unary(), at);
        after_division = false;
      } else {
        if (!accept('/')) return p;
        if (after_division)
          throw PolynomialParseError("ambiguous division a/b/c: write (a/b)/c or a/(b/c)", at);
        Polynomial d = unary();
        if (!d.is_constant()) throw PolynomialParseError("division by a non-constant expression", at);
        if (d.is_zero()) throw PolynomialParseError("division by zero", at);
        p = p.scaled(1 / d.terms()[0].coefficient);
        check_size(p, at);
        after_division = true;
      }
    }
  }
  Polynomial unary() {
    skip();
    const std::size_t at = pos_;
    if (accept('-')) {
      Nest nest(*this, at);
      return -unary();
    }
    if (accept('+')) {
      Nest nest(*this, at);
      return unary();
    }
    return power();
  }
  Polynomial power() {
    Polynomial base = atom();
    skip();
    const std::size_t at = pos_;
    if (accept('^')) {
      skip();
      std::size_t start = pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      if (start == pos_) throw PolynomialParseError("exponent must be a non-negative integer literal", start);
      // Compare the digit string with the limit without converting it (it may be any length).
      std::string_view digits = s_.substr(start, pos_ - start);
      while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
      const std::string limit = std::to_string(Limits::max_degree);
      if (digits.size() > limit.size() || (digits.size() == limit.size() && digits > limit))
        throw PolynomialParseError("exponent " + std::string(digits.substr(0, 20)) + (digits.size() > 20 ? "..." : "") +
                                       " too large (the limit on exponents and on the total degree is " + limit + ")",
                                   start);
      const int e = std::stoi(std::string(digits));
      if (static_cast<long>(base.degree()) * e > Limits::max_degree)
        throw PolynomialParseError("exponent " + std::to_string(e) + " too large: the power has degree " +
                                       std::to_string(static_cast<long>(base.degree()) * e) +
                                       " (the limit on the total degree is " + limit + ")",
                                   start);
      return power_of(std::move(base), e, at);
    }
    return base;
  }
  Polynomial atom() {
    skip();
    if (pos_ >= s_.size()) throw PolynomialParseError("unexpected end of expression", pos_);
    char c = s_[pos_];
    if (c == '(') {
      Nest nest(*this, pos_);
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
      // The whole digit string is the index: no truncation, no leading zeros ("x03" is refused
      // rather than guessed at).
      std::string_view digits = s_.substr(dstart, pos_ - dstart);
      std::string shown = std::string(digits.substr(0, 20)) + (digits.size() > 20 ? "..." : "");
      if (digits.size() > 1 && digits.front() == '0')
        throw PolynomialParseError("variable x" + shown + ": leading zeros are not allowed in a variable index", start);
      long idx = digits.size() > 9 ? -1 : std::stol(std::string(digits));
      if (idx < 1 || idx > n_)
        throw PolynomialParseError("variable x" + shown + " out of range x1..x" + std::to_string(n_) + " (N = " +
                                       std::to_string(n_) + " coordinates)",
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
      if (pos_ - start > Limits::max_literal_length)
        throw PolynomialParseError("number literal too large: " + std::to_string(pos_ - start) +
                                       " characters (the limit is " + std::to_string(Limits::max_literal_length) + ")",
                                   start);
      Polynomial p;
      try {
        p = Polynomial::constant(parse_rational(s_.substr(start, pos_ - start)), n_);
      } catch (const std::invalid_argument&) {
        throw PolynomialParseError("malformed number '" + std::string(s_.substr(start, pos_ - start)) + "'", start);
      }
      check_size(p, start);  // "1e99999" is short but large
      return p;
    }
    throw PolynomialParseError(std::string("unexpected character '") + c + "'", pos_);
  }

  std::string_view s_;
  int n_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  std::size_t products_ = 0;  // term products spent so far, against Limits::max_products
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

Polynomial Polynomial::affine(const mpq_class& c, std::span<const mpq_class> linear) {
  const int n = static_cast<int>(linear.size());
  Polynomial p(n);
  p.terms_.push_back(Term{c, Monomial{std::vector<std::uint32_t>(n, 0)}});
  for (int j = 0; j < n; ++j) {
    p.terms_.push_back(Term{linear[j], Monomial{std::vector<std::uint32_t>(n, 0)}});
    p.terms_.back().monomial.exponents[j] = 1;
  }
  p.normalize();  // order the terms, drop the zero coefficients
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
  Polynomial r = *this;
  r += Polynomial(o);
  return r;
}

Polynomial& Polynomial::operator+=(Polynomial&& o) {
  // Operands over fewer variables (e.g. a default-constructed zero) get their exponent vectors
  // padded, so that equal monomials compare equal and merge (padding keeps each side sorted).
  const int n = std::max(num_vars_, o.num_vars_);
  num_vars_ = n;
  for (auto& t : terms_) t.monomial.exponents.resize(n, 0);
  for (auto& t : o.terms_) t.monomial.exponents.resize(n, 0);
  auto decreasing = [](const Term& a, const Term& b) { return a.monomial > b.monomial; };
  const bool sorted = std::is_sorted(terms_.begin(), terms_.end(), decreasing) &&
                      std::is_sorted(o.terms_.begin(), o.terms_.end(), decreasing);
  const std::size_t mid = terms_.size();
  terms_.insert(terms_.end(), std::make_move_iterator(o.terms_.begin()), std::make_move_iterator(o.terms_.end()));
  o.terms_.clear();
  if (!sorted) {
    normalize();
    return *this;
  }
  std::inplace_merge(terms_.begin(), terms_.begin() + static_cast<std::ptrdiff_t>(mid), terms_.end(), decreasing);
  std::size_t w = 0;  // merge equal monomials (adjacent now) and drop zero coefficients, in place
  for (std::size_t r = 0; r < terms_.size(); ++r) {
    if (w > 0 && terms_[w - 1].monomial == terms_[r].monomial) {
      terms_[w - 1].coefficient += terms_[r].coefficient;
      continue;
    }
    if (w > 0 && terms_[w - 1].coefficient == 0) --w;
    if (w != r) terms_[w] = std::move(terms_[r]);
    ++w;
  }
  if (w > 0 && terms_[w - 1].coefficient == 0) --w;
  terms_.erase(terms_.begin() + static_cast<std::ptrdiff_t>(w), terms_.end());
  return *this;
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
  // Products are collected in a hash map by monomial: a product of |a| by |b| terms costs |a||b|
  // lookups among the result's terms, not a sort of |a||b| terms.
  Polynomial r(std::max(num_vars_, o.num_vars_));
  struct Hash {
    std::size_t operator()(const Monomial& m) const {
      std::size_t h = 0;
      for (auto e : m.exponents) h = h * 0x9E3779B97F4A7C15ull + e;
      return h;
    }
  };
  // Each product of coefficients is a rational product unless both operands have a small common
  // denominator (the usual case: integer coefficients), when it is an integer multiply-add into
  // the numerator over the product of the two denominators, several times faster.
  const IntegerForm fa = integer_form(), fb = o.integer_form();
  const bool integer_path = mpz_sizeinbase(fa.denominator.get_mpz_t(), 2) + mpz_sizeinbase(fb.denominator.get_mpz_t(), 2) <= 1024;
  std::unordered_map<Monomial, mpq_class, Hash> acc;
  acc.reserve(std::min<std::size_t>(terms_.size() * o.terms_.size(), 1u << 16));
  Monomial m{std::vector<std::uint32_t>(r.num_vars_, 0)};
  mpq_class c;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const Term& a = terms_[i];
    for (std::size_t j = 0; j < o.terms_.size(); ++j) {
      const Term& b = o.terms_[j];
      // Operands may have fewer variables than the result: missing exponents are 0.
      std::fill(m.exponents.begin(), m.exponents.end(), 0u);
      for (std::size_t v = 0; v < a.monomial.exponents.size(); ++v) m.exponents[v] = a.monomial.exponents[v];
      for (std::size_t v = 0; v < b.monomial.exponents.size(); ++v) {
        if (m.exponents[v] > UINT32_MAX - b.monomial.exponents[v])
          throw std::overflow_error("polynomial exponent above 2^32 - 1");  // never wrap
        m.exponents[v] += b.monomial.exponents[v];
      }
      auto [it, fresh] = acc.try_emplace(m);
      if (integer_path) {  // the numerator of the entry, denominator 1 until the end
        mpz_addmul(mpq_numref(it->second.get_mpq_t()), fa.numerators[i].get_mpz_t(), fb.numerators[j].get_mpz_t());
      } else {
        mpq_mul(c.get_mpq_t(), a.coefficient.get_mpq_t(), b.coefficient.get_mpq_t());
        it->second += c;
      }
    }
  }
  const mpz_class den = fa.denominator * fb.denominator;
  r.terms_.reserve(acc.size());
  for (auto& [mono, coef] : acc) {
    if (integer_path) {
      mpz_set(mpq_denref(coef.get_mpq_t()), den.get_mpz_t());
      coef.canonicalize();
    }
    if (coef != 0) r.terms_.push_back(Term{std::move(coef), mono});
  }
  r.normalize();  // sorts; the monomials are already distinct
  return r;
}

Polynomial Polynomial::pow(unsigned e) const {
  // Exponent overflow is caught by operator*.
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
    for (std::size_t v = 0; v < t.monomial.exponents.size(); ++v)
      if (t.monomial.exponents[v] > 0) factors_.push_back({static_cast<std::uint32_t>(v), t.monomial.exponents[v]});
    ends_.push_back(static_cast<std::uint32_t>(factors_.size()));
  }
}

DoublePolynomial::DoublePolynomial(int num_vars, std::span<const double> coefficients,
                                   std::span<const std::uint32_t> exponents)
    : num_vars_(num_vars) {
  coefficients_.reserve(coefficients.size());
  ends_.reserve(coefficients.size());
  factors_.reserve(static_cast<std::size_t>(
      std::count_if(exponents.begin(), exponents.begin() + coefficients.size() * num_vars, [](std::uint32_t e) { return e > 0; })));
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    coefficients_.push_back(coefficients[i]);
    for (int v = 0; v < num_vars; ++v)
      if (const std::uint32_t e = exponents[i * num_vars + v]; e > 0) factors_.push_back({static_cast<std::uint32_t>(v), e});
    ends_.push_back(static_cast<std::uint32_t>(factors_.size()));
  }
}

double DoublePolynomial::operator()(std::span<const double> x) const {
  // t = c * x_v * ... * x_v (e_v times, v increasing), summed in term order: skipping the zero
  // exponents changes none of the products.
  double sum = 0;
  const Factor* f = factors_.data();
  for (std::size_t i = 0; i < coefficients_.size(); ++i) {
    double t = coefficients_[i];
    for (const Factor* end = factors_.data() + ends_[i]; f != end; ++f) {
      const double xv = x[f->var];
      for (std::uint32_t k = 0; k < f->exponent; ++k) t *= xv;
    }
    sum += t;
  }
  return sum;
}

}  // namespace delcert::exact
