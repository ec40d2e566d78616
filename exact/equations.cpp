#include "exact/equations.hpp"

#include <algorithm>

namespace delcert::exact {

Polynomial at_canonical_scale(const Polynomial& p) {
  if (p.is_zero()) return p;
  mpq_class factor(1);
  const Polynomial::IntegerForm f = p.integer_form();
  if (mpz_sizeinbase(f.denominator.get_mpz_t(), 2) <= PolynomialLimits::max_coefficient_bits) {
    mpz_class g(0);
    for (const auto& n : f.numerators) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), n.get_mpz_t());
    factor = mpq_class(f.denominator, g);  // g > 0: p has a non-zero coefficient
    factor.canonicalize();
  }
  mpq_class largest(0);
  for (const auto& t : p.terms()) largest = std::max(largest, mpq_class(abs(t.coefficient * factor)));
  // e = floor(log2 largest), exactly: from the bit lengths, then corrected by one comparison.
  long e = static_cast<long>(mpz_sizeinbase(largest.get_num_mpz_t(), 2)) -
           static_cast<long>(mpz_sizeinbase(largest.get_den_mpz_t(), 2));
  mpq_class two_e(1);
  if (e >= 0) mpq_mul_2exp(two_e.get_mpq_t(), two_e.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(two_e.get_mpq_t(), two_e.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  if (largest < two_e) two_e /= 2;  // now 2^e <= largest < 2^(e+1)
  return p.scaled(factor / two_e);
}

}  // namespace delcert::exact
