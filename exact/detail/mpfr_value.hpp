// An MPFR number with scoped lifetime (init2 / clear), for exact/*.cpp, and the guard that frees the
// calling thread's MPFR caches when the thread ends. Private to exact/.
#pragma once

#include <mpfr.h>

namespace delcert::exact::detail {

// MPFR keeps caches per thread (the constant pi, used by asin, acos, atan2, pi(); the constants of
// log and exp): a thread that used them and exits without mpfr_free_cache() leaks them
// (LeakSanitizer reports it for the certifier's worker threads). Every MPFR or MPFI number of
// exact/ is made after register_thread_caches(), whose thread-local guard frees the calling
// thread's caches when that thread ends (the main thread's at exit). One guard per thread: the
// function-local thread_local is constructed on the thread's first call.
struct MpfrThreadCaches {
  MpfrThreadCaches() = default;
  MpfrThreadCaches(const MpfrThreadCaches&) = delete;
  MpfrThreadCaches& operator=(const MpfrThreadCaches&) = delete;
  ~MpfrThreadCaches() { mpfr_free_cache(); }
};
inline void register_thread_caches() {
  static thread_local MpfrThreadCaches guard;
  (void)guard;
}

struct Mpfr {
  mpfr_t x;
  explicit Mpfr(mpfr_prec_t p) {
    register_thread_caches();
    mpfr_init2(x, p);
  }
  ~Mpfr() { mpfr_clear(x); }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;
};

}  // namespace delcert::exact::detail
