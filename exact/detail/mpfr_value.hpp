// An MPFR number with scoped lifetime (init2 / clear), for exact/*.cpp. Private to exact/.
#pragma once

#include <mpfr.h>

namespace delcert::exact::detail {

struct Mpfr {
  mpfr_t x;
  explicit Mpfr(mpfr_prec_t p) { mpfr_init2(x, p); }
  ~Mpfr() { mpfr_clear(x); }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;
};

}  // namespace delcert::exact::detail
