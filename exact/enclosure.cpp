#include "exact/enclosure.hpp"

#include <mpfi.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "exact/detail/mpfr_value.hpp"

namespace delcert::exact {

// MPFI rounds every endpoint outward, so each operation below returns an interval containing
// the exact result for all values of the operands (the library's documented contract).
struct Enclosure::Impl {
  mpfi_t v;
  explicit Impl(mpfr_prec_t prec) {
    detail::register_thread_caches();
    mpfi_init2(v, prec);
  }
  ~Impl() { mpfi_clear(v); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
};

namespace {

mpfr_prec_t checked_precision(int precision) {
  if (precision < MPFR_PREC_MIN || precision > 1 << 20)
    throw std::invalid_argument("enclosure precision must be between 2 and 2^20 bits");
  return static_cast<mpfr_prec_t>(precision);
}

using detail::Mpfr;

std::string format(mpfr_srcptr x, int digits, bool down) {
  char* s = nullptr;
  const int n = down ? mpfr_asprintf(&s, "%.*RDg", digits, x) : mpfr_asprintf(&s, "%.*RUg", digits, x);
  if (n < 0 || s == nullptr) throw std::runtime_error("mpfr_asprintf failed");
  std::string out(s);
  mpfr_free_str(s);
  return out;
}

}  // namespace

Enclosure::Enclosure() = default;

Enclosure::Enclosure(const mpq_class& exact, int precision)
    : impl_(std::make_unique<Impl>(checked_precision(precision))) {
  mpfi_set_q(impl_->v, exact.get_mpq_t());
}

Enclosure::Enclosure(double exact, int precision) : impl_(std::make_unique<Impl>(checked_precision(precision))) {
  if (!std::isfinite(exact)) throw std::invalid_argument("enclosure of a non-finite double");
  mpfi_set_d(impl_->v, exact);
}

Enclosure::Enclosure(long exact, int precision) : impl_(std::make_unique<Impl>(checked_precision(precision))) {
  mpfi_set_si(impl_->v, exact);
}

Enclosure Enclosure::between(const mpq_class& lo, const mpq_class& hi, int precision) {
  if (lo > hi) throw std::invalid_argument("Enclosure::between needs lo <= hi");
  Enclosure e;
  e.impl_ = std::make_unique<Impl>(checked_precision(precision));
  mpfi_interv_q(e.impl_->v, lo.get_mpq_t(), hi.get_mpq_t());
  return e;
}

Enclosure Enclosure::pi(int precision) {
  Enclosure e;
  e.impl_ = std::make_unique<Impl>(checked_precision(precision));
  mpfi_const_pi(e.impl_->v);
  return e;
}

Enclosure::Enclosure(const Enclosure& other) : impl_(std::make_unique<Impl>(mpfi_get_prec(other.impl_->v))) {
  mpfi_set(impl_->v, other.impl_->v);
}

Enclosure& Enclosure::operator=(const Enclosure& other) {
  if (this != &other) {
    auto fresh = std::make_unique<Impl>(mpfi_get_prec(other.impl_->v));
    mpfi_set(fresh->v, other.impl_->v);
    impl_ = std::move(fresh);
  }
  return *this;
}

Enclosure::Enclosure(Enclosure&& other) noexcept = default;
Enclosure& Enclosure::operator=(Enclosure&& other) noexcept = default;
Enclosure::~Enclosure() = default;

int Enclosure::precision() const { return static_cast<int>(mpfi_get_prec(impl_->v)); }

double Enclosure::lower() const { return mpfr_get_d(&impl_->v->left, MPFR_RNDD); }
double Enclosure::upper() const { return mpfr_get_d(&impl_->v->right, MPFR_RNDU); }

mpq_class Enclosure::lower_exact() const {
  if (!mpfr_number_p(&impl_->v->left)) throw std::domain_error("enclosure endpoint is not finite");
  mpq_class q;
  // An MPFR number is m * 2^e: exact as a rational.
  mpz_class m;
  const mpfr_exp_t e = mpfr_get_z_2exp(m.get_mpz_t(), &impl_->v->left);
  q = m;
  if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  return q;
}

mpq_class Enclosure::upper_exact() const {
  if (!mpfr_number_p(&impl_->v->right)) throw std::domain_error("enclosure endpoint is not finite");
  mpq_class q;
  mpz_class m;
  const mpfr_exp_t e = mpfr_get_z_2exp(m.get_mpz_t(), &impl_->v->right);
  q = m;
  if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  return q;
}

std::string Enclosure::lower_string() const { return format(&impl_->v->left, 17, true); }
std::string Enclosure::upper_string() const { return format(&impl_->v->right, 17, false); }

std::string Enclosure::to_string(int digits) const {
  return "[" + format(&impl_->v->left, digits, true) + ", " + format(&impl_->v->right, digits, false) + "]";
}

bool Enclosure::contains(const mpq_class& x) const { return mpfi_is_inside_q(x.get_mpq_t(), impl_->v) > 0; }
bool Enclosure::contains(mpfr_srcptr x) const { return mpfi_is_inside_fr(x, impl_->v) > 0; }
bool Enclosure::is_positive() const { return mpfr_sgn(&impl_->v->left) > 0; }
bool Enclosure::is_negative() const { return mpfr_sgn(&impl_->v->right) < 0; }
bool Enclosure::contains_zero() const { return mpfi_has_zero(impl_->v) > 0; }

double Enclosure::width() const {
  Mpfr w(mpfi_get_prec(impl_->v) + 2);
  mpfr_sub(w.x, &impl_->v->right, &impl_->v->left, MPFR_RNDU);
  return mpfr_get_d(w.x, MPFR_RNDU);
}

Enclosure Enclosure::with_precision(long precision) {
  Enclosure e;
  e.impl_ = std::make_unique<Impl>(static_cast<mpfr_prec_t>(precision));
  return e;
}

static mpfr_prec_t max_prec(const Enclosure::Impl& a, const Enclosure::Impl& b) {
  return std::max(mpfi_get_prec(a.v), mpfi_get_prec(b.v));
}

Enclosure operator+(const Enclosure& a, const Enclosure& b) {
  Enclosure r = Enclosure::with_precision(max_prec(*a.impl_, *b.impl_));
  mpfi_add(r.impl_->v, a.impl_->v, b.impl_->v);
  return r;
}

Enclosure operator-(const Enclosure& a, const Enclosure& b) {
  Enclosure r = Enclosure::with_precision(max_prec(*a.impl_, *b.impl_));
  mpfi_sub(r.impl_->v, a.impl_->v, b.impl_->v);
  return r;
}

Enclosure operator*(const Enclosure& a, const Enclosure& b) {
  Enclosure r = Enclosure::with_precision(max_prec(*a.impl_, *b.impl_));
  mpfi_mul(r.impl_->v, a.impl_->v, b.impl_->v);
  return r;
}

Enclosure operator/(const Enclosure& a, const Enclosure& b) {
  if (mpfi_has_zero(b.impl_->v) > 0)
    throw std::domain_error("division by an enclosure that contains 0: the divisor's sign is not certified");
  Enclosure r = Enclosure::with_precision(max_prec(*a.impl_, *b.impl_));
  mpfi_div(r.impl_->v, a.impl_->v, b.impl_->v);
  return r;
}

Enclosure operator-(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  mpfi_neg(r.impl_->v, a.impl_->v);
  return r;
}

// Intersects a's enclosure with [lo, hi] (lo, hi exact small integers); throws when empty.
static void clamp_domain(mpfi_ptr out, mpfi_srcptr a, long lo, long hi, bool has_hi, const char* what) {
  mpfi_set(out, a);
  Mpfr l(mpfi_get_prec(a)), h(mpfi_get_prec(a));
  mpfr_set_si(l.x, lo, MPFR_RNDN);
  if (mpfr_cmp(&out->right, l.x) < 0)
    throw std::domain_error(std::string(what) + " of an enclosure entirely outside its domain");
  if (mpfr_cmp(&out->left, l.x) < 0) mpfr_set(&out->left, l.x, MPFR_RNDD);
  if (has_hi) {
    mpfr_set_si(h.x, hi, MPFR_RNDN);
    if (mpfr_cmp(&out->left, h.x) > 0)
      throw std::domain_error(std::string(what) + " of an enclosure entirely outside its domain");
    if (mpfr_cmp(&out->right, h.x) > 0) mpfr_set(&out->right, h.x, MPFR_RNDU);
  }
}

Enclosure sqrt(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  clamp_domain(r.impl_->v, a.impl_->v, 0, 0, false, "sqrt");
  mpfi_sqrt(r.impl_->v, r.impl_->v);
  return r;
}

Enclosure acos(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  clamp_domain(r.impl_->v, a.impl_->v, -1, 1, true, "acos");
  mpfi_acos(r.impl_->v, r.impl_->v);
  return r;
}

Enclosure asin(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  clamp_domain(r.impl_->v, a.impl_->v, -1, 1, true, "asin");
  mpfi_asin(r.impl_->v, r.impl_->v);
  return r;
}

Enclosure atan(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  mpfi_atan(r.impl_->v, a.impl_->v);
  return r;
}

Enclosure atan2(const Enclosure& y, const Enclosure& x) {
  if (mpfi_has_zero(x.impl_->v) > 0 && mpfi_has_zero(y.impl_->v) > 0)
    throw std::domain_error("atan2 of an enclosure that contains the origin: the angle is undefined");
  Enclosure r = Enclosure::with_precision(max_prec(*y.impl_, *x.impl_));
  mpfi_atan2(r.impl_->v, y.impl_->v, x.impl_->v);
  return r;
}

Enclosure cos(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  mpfi_cos(r.impl_->v, a.impl_->v);
  return r;
}

Enclosure sin(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  mpfi_sin(r.impl_->v, a.impl_->v);
  return r;
}

Enclosure square(const Enclosure& a) {
  Enclosure r = Enclosure::with_precision(mpfi_get_prec(a.impl_->v));
  mpfi_sqr(r.impl_->v, a.impl_->v);
  return r;
}

Enclosure hull(const Enclosure& a, const Enclosure& b) {
  Enclosure r = Enclosure::with_precision(max_prec(*a.impl_, *b.impl_));
  mpfi_union(r.impl_->v, a.impl_->v, b.impl_->v);
  return r;
}

}  // namespace delcert::exact
