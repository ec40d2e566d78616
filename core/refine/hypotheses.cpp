#include "core/refine/hypotheses.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace delcert::refine {

using exact::Tri;

const char* status_name(Tri s) {
  switch (s) {
    case Tri::yes: return "holds";
    case Tri::no: return "fails";
    case Tri::unknown: return "not_evaluable";
  }
  return "?";
}

namespace {

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

HypothesisCheck decided(std::string name, std::string statement, double lhs, double rhs, bool holds, std::string what) {
  HypothesisCheck c;
  c.name = std::move(name);
  c.statement = std::move(statement);
  c.status = exact::tri(holds);
  c.lhs = lhs;
  c.rhs = rhs;
  c.detail = what + ": " + num(lhs) + (holds ? " satisfies" : " violates") + " the bound " + num(rhs);
  return c;
}

}  // namespace

HypothesesReport evaluate_hypotheses(const HypothesesInput& in) {
  HypothesesReport r;
  const int m = in.m;
  const double eps0 = 1.0 / (16.0 * 17.0 * 17.0);
  r.eps0_tilde = eps0;
  const ConstantsAsDoubles dbl = as_doubles(in.constants);
  const double a = dbl.alpha, b = dbl.beta, g = dbl.gamma0, d2 = dbl.delta0 * dbl.delta0;
  const double B = 4 + 2 * std::pow(1 + 1152 * b * b, 2);
  const double gm1 = std::pow(g, m + 1);
  const bool has_reach = in.reach.has_value() && in.reach.value() > 0;
  const double eps_tilde = has_reach ? dbl.eps / in.reach.value() : 0.0;

  r.checks.push_back(decided("H0", "alpha < 1/2", a, 0.5, a < 0.5, "alpha"));
  {
    const double rhs = 2 / ((1 - d2) * (1 - a - 4.5 * eps0));
    const bool ok = (1 - a - 4.5 * eps0) > 0 && d2 < 1 && b >= rhs;
    r.checks.push_back(decided("H1", "beta >= 2 / ((1 - delta0^2) (1 - alpha - 4.5 eps0~))", b, rhs, ok, "beta"));
  }
  {
    HypothesisCheck c;
    c.name = "H2";
    c.statement = "Gamma0 < min{ V_m alpha^m / (E^(m+1) beta^m D), 1 / (B + 1) }, B = 4 + 2 (1 + 2^7 3^2 beta^2)^2";
    const double rhs = 1 / (B + 1);
    c.lhs = g;
    c.rhs = rhs;
    if (!(g < rhs)) {
      c.status = Tri::no;
      c.detail = "Gamma0 = " + num(g) + " violates the specified part Gamma0 < 1/(B+1) = " + num(rhs);
    } else {
      c.status = Tri::unknown;
      c.detail = "the specified part Gamma0 < 1/(B+1) = " + num(rhs) +
                 " holds; V_m alpha^m / (E^(m+1) beta^m D) needs E (from xi and A) and D, which the paper leaves unspecified";
    }
    r.checks.push_back(c);
  }
  {
    // Exact: both are rationals, and so are both sides.
    const mpq_class& gq = in.constants.gamma0.value;
    const mpq_class& dq = in.constants.delta0.value().value;
    mpq_class rhs(1);
    for (int i = 0; i <= m; ++i) rhs *= gq;
    const bool h3 = dq * dq <= rhs;
    r.checks.push_back(decided("H3", "delta0^2 <= Gamma0^(m+1)", d2, gm1, h3, "delta0^2 (decided exactly)"));
  }
  {
    HypothesisCheck c;
    c.name = "H4";
    c.statement = "eps~ <= min{ xi / (2 (beta + beta') rch), Gamma0^(m+1) / (8 beta) }, beta' = beta / (1 - 2^4 eps0~)";
    const double rhs = gm1 / (8 * b);
    c.rhs = rhs;
    if (!has_reach) {
      c.status = Tri::unknown;
      c.detail = "the manifold spec gives no reach, so eps~ = eps / rch is unknown; xi is unspecified";
    } else {
      c.lhs = eps_tilde;
      if (!(eps_tilde <= rhs)) {
        c.status = Tri::no;
        c.detail = "eps~ = " + num(eps_tilde) + " violates the specified part Gamma0^(m+1) / (8 beta) = " + num(rhs);
      } else {
        c.status = Tri::unknown;
        c.detail = "eps~ = " + num(eps_tilde) + " satisfies the specified part " + num(rhs) + "; xi is unspecified";
      }
    }
    r.checks.push_back(c);
  }
  {
    const double rhs = d2 * std::pow(g, 2 * m) / 1.1e9;
    if (!has_reach) {
      HypothesisCheck c;
      c.name = "H5";
      c.statement = "eps~ <= delta0^2 Gamma0^(2m) / (1.1 10^9)";
      c.status = Tri::unknown;
      c.rhs = rhs;
      c.detail = "the manifold spec gives no reach, so eps~ = eps / rch is unknown";
      r.checks.push_back(c);
    } else {
      r.checks.push_back(decided("H5", "eps~ <= delta0^2 Gamma0^(2m) / (1.1 10^9)", eps_tilde, rhs, eps_tilde <= rhs, "eps~"));
    }
  }
  if (has_reach && in.reach_is_lower_bound)
    for (auto& c : r.checks)
      if (c.name == "H4" || c.name == "H5") c.detail += " (the spec's reach is a lower bound: eps~ is an upper bound)";

  r.sparsity_lemma_lhs = (1 - d2) * (1 - a - 4.5 * eps0) / 4;
  r.sparsity_lemma_holds = r.sparsity_lemma_lhs > r.mu0;

  if (has_reach) {
    const double t = std::min({gm1 / (8 * b), d2 * std::pow(g, 2 * m) / 1.1e9, eps0});
    r.max_eps = t * in.reach.value();
    r.max_eps_note = "rch * min{Gamma0^(m+1)/(8 beta), delta0^2 Gamma0^(2m)/1.1e9, eps0~}: the decidable parts of H4 and H5; "
                     "the unspecified xi term of H4 can only lower it";
  } else {
    r.max_eps_note = "no reach in the manifold spec: no bound on eps can be given";
  }
  r.unspecified = {"xi: depends on m and rch (lemma 'bound on sparse points'); enters H2 through E and H4",
                   "A: depends on m (same lemma); enters H2 through E",
                   "D: depends on m and beta (lemma 'volume of forbidden region'); enters H2"};
  r.all_hold = true;
  for (const auto& c : r.checks) {
    if (c.status == Tri::no) r.any_fails = true;
    if (c.status != Tri::yes) r.all_hold = false;
  }
  return r;
}

}  // namespace delcert::refine
