#include "certify/tangential/theorem.hpp"

#include <mpfr.h>

#include <cmath>

#include "exact/enclosure.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"

namespace delcert::certify {

using nlohmann::json;

double sqrt_lower(const mpq_class& q) {
  if (q <= 0) return 0;
  mpfr_t x;
  mpfr_init2(x, 53);
  mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDD);
  mpfr_sqrt(x, x, MPFR_RNDD);
  double d = mpfr_get_d(x, MPFR_RNDD);
  mpfr_clear(x);
  return d;
}

namespace {
std::string enc(const exact::Enclosure& e) { return e.to_string(6); }
}  // namespace

json TheoremParams::json_parameters() const {
  return {{"eps", exact::rational_to_string(eps)},
          {"eps_source", eps_source},
          {"eps_is_a_sampling_radius", eps_is_sampling_radius},
          {"lambda", exact::rational_to_string(lambda)},
          {"upsilon0_tilde", exact::rational_to_string(upsilon)},
          {"delta_check_squared", exact::rational_to_string(protection_capped)},
          {"delta", enc(exact::Enclosure(delta))},
          {"upsilon0", enc(exact::Enclosure(upsilon0))},
          {"mu0_eps", enc(exact::Enclosure(shortest))}};
}

TheoremParams theorem_parameters(const Measured& M) {
  TheoremParams T;
  if (!(M.min_distance > 0)) T.why = "no positive lower bound on the minimum distance";
  else if (!(M.min_thickness > 0)) T.why = "no positive lower bound on the thickness of the m-simplices";
  else if (!(M.min_margin > 0)) T.why = "no positive power-protection margin (an exact tie or an uncertified star)";
  else if (!std::isfinite(M.max_radius_squared)) T.why = "no star radius";
  if (!T.why.empty()) return T;
  T.usable = true;
  if (M.eps) {
    T.eps = *M.eps;
    T.eps_source = "the star_radius claim (certified)";
  } else {
    T.eps = exact::to_rational(std::nextafter(std::sqrt(M.max_radius_squared), INFINITY));
    T.eps_source = "measured: the smallest double above every certified R_p(s)";
  }
  if (M.covering) {
    T.eps_is_sampling_radius = true;
    if (*M.covering > T.eps)
      T.eps = *M.covering, T.eps_source = "the certified covering radius (check 11)";
    else
      T.eps_source += ", at least the certified covering radius (check 11)";
  }
  T.lambda = exact::to_rational(M.min_distance);
  T.upsilon = exact::to_rational(M.min_thickness);
  T.protection = exact::to_rational(M.min_margin);
  mpq_class cap = T.eps * T.eps / 7;  // delta0^2 mu0~^2 = delta^2 / eps^2 <= 1/7
  T.protection_capped = T.protection < cap ? T.protection : cap;
  T.delta = T.protection_capped / (8 * T.eps);
  T.upsilon0 = mpq_class(6, 49) * T.upsilon;
  T.shortest = mpq_class(20, 21) * T.lambda;
  return T;
}

CheckEntry theorem_report(const TheoremParams& T, const io::ManifoldSpec& spec) {
  CheckEntry e(CheckId::theorem);
  e.verdict = Verdict::report;
  if (!spec.reach) {
    e.summary = "undetermined: the manifold spec gives no reach";
    e.details["result"] = "undetermined";
    return e;
  }
  if (!T.usable) {
    e.summary = "not met: " + T.why;
    e.details["result"] = "not met";
    return e;
  }
  const mpq_class& rch2 = spec.reach->squared;
  mpq_class c = mpq_class(1500000);
  // F = U^2 lambda d2 rch / (c eps^4) >= 1  <=>  (U^2 lambda d2)^2 rch^2 >= (c eps^4)^2 (both sides >= 0).
  mpq_class eps4 = T.eps * T.eps * T.eps * T.eps;
  mpq_class lhs = T.upsilon * T.upsilon * T.lambda * T.protection_capped;
  bool met = lhs * lhs * rch2 >= c * eps4 * c * eps4;
  exact::Enclosure F = exact::Enclosure(lhs) * sqrt(exact::Enclosure(rch2)) / exact::Enclosure(mpq_class(c * eps4));
  exact::Enclosure bound = F * exact::Enclosure(T.eps);  // the theorem's upper bound on eps
  e.margin = {{"factor", {{"certified_lower_bound", F.lower_string()}, {"enclosure", enc(F)}}}};
  e.details = {{"result", met ? "met" : "not met"},
               {"reach", spec.reach->text + (spec.reach->exact ? "" : " (lower bound)")},
               {"parameters", T.json_parameters()},
               {"mu0_tilde", enc(exact::Enclosure(T.lambda) / exact::Enclosure(T.eps))},
               {"delta0_squared_mu0_tilde_squared", enc(exact::Enclosure(T.protection_capped) / exact::Enclosure(mpq_class(T.eps * T.eps)))},
               {"eps_bound", enc(bound)},
               {"condition", "eps <= Upsilon0~^2 mu0~^3 delta0^2 rch / 1.5e6  <=>  F = Upsilon0~^2 lambda delta^2 rch / (1.5e6 eps^4) >= 1"}};
  if (met && !T.eps_is_sampling_radius) {
    e.details["result"] = "not applicable";
    e.summary = "not applicable: F >= 1 (F in " + enc(F) + ") with eps a bound on the star radii only; P is not "
                "certified to be an eps-sample (check 11), which the theorem also needs";
  } else if (met) {
    e.summary = "met: Theorem 3.3 applies (F >= 1, F in " + enc(F) + "), so Del_TM = Del_RM = Del_M";
  } else {
    e.summary = "not met: the theorem needs eps <= " + bound.upper_string() + " but eps = " +
                num(exact::enclose(T.eps).hi) + " (short by a factor " + (exact::Enclosure(mpq_class(1)) / F).lower_string() +
                "); the equality Del_TM = Del_RM = Del_M is NOT implied. This is normal at realistic densities; "
                "checks 3-6 and 8 certify Del_TM directly";
    e.details["plainly"] = "The sample is far from the density at which the paper's sufficient condition holds. "
                           "Nothing here certifies Del_RM or Del_M.";
  }
  return e;
}

}  // namespace delcert::certify
