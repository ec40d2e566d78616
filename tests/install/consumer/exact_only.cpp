// Links delcert::exact alone (tests/install/consumer/): directed rounding works, and an exact
// polynomial evaluates exactly.
#include <cstdio>
#include <string>
#include <vector>

#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

int main() {
  using namespace delcert;
  if (const std::string why = exact::directed_rounding_failure(); !why.empty()) {
    std::fprintf(stderr, "exact_only: directed rounding does not work: %s\n", why.c_str());
    return 1;
  }
  const exact::Polynomial p = exact::Polynomial::parse("x1^2 + x2^2 - 1", 2);
  if (p.to_string() != exact::Polynomial::parse("-1 + x2^2 + x1^2", 2).to_string() || p.degree() != 2) {
    std::fprintf(stderr, "exact_only: unexpected polynomial %s\n", p.to_string().c_str());
    return 1;
  }
  std::printf("exact_only: %s\n", p.to_string().c_str());
  return 0;
}
