// Check 9: Theorem 3.3 of the paper, evaluated on the measured (certified) quantities.
//
// Theorem 3.3: if P is (mu0~ eps)-sparse, every m-simplex of Del_TM is Upsilon0~-thick and has,
// at every vertex p, a delta^2-power-protected empty ball of radius < eps centred on T_p with
// delta >= delta0 mu0~ eps, delta0^2 mu0~^2 <= 1/7 and
//        eps <= Upsilon0~^2 mu0~^3 delta0^2 rch(M) / 1.5e6,
// then Del_TM = Del_RM = Del_M. With lambda = mu0~ eps (measured minimum distance), delta^2 the
// measured minimum power margin (capped at eps^2 / 7, which only weakens it), eps the larger of
// the star-radius bound and the certified covering radius (check 11; without it eps is no
// sampling radius and the theorem does not apply) and delta0 =
// delta / lambda, the last condition reads F >= 1 for
//        F = Upsilon0~^2 lambda delta^2 rch / (1.5e6 eps^4),
// decided exactly (squared, so that rch = sqrt(rch^2) needs no rounding). The same measured
// values give the parameters of Definition 3.1 for check 7 (Lemmas 4.6-4.7): delta = delta^2 /
// (8 eps), Upsilon0 = 6/49 Upsilon0~, mu0 eps = 20/21 lambda.
#pragma once

#include <gmpxx.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "certify/certificate.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

struct Measured {
  double min_distance = 0;          // certified lower bound of min |p - q| (lambda)
  double min_thickness = -1;        // certified lower bound of min Upsilon over m-simplices
  double min_margin = 0;            // certified lower bound of the min power margin (delta^2)
  double max_radius_squared = 0;    // certified upper bound of max R_p(s)^2
  std::optional<mpq_class> eps;     // the claimed eps, when the radius claim was certified
  std::optional<mpq_class> covering;  // the certified covering radius (check 11 CERTIFIED)
};

// Largest double <= sqrt(q).
double sqrt_lower(const mpq_class& q);

struct TheoremParams {
  bool usable = false;
  std::string why;                  // when not usable
  // eps >= the certified covering radius, so P is an eps-sample (the paper's eps is both a bound
  // on the star radii and a sampling radius): eps = max(star-radius eps, covering).
  bool eps_is_sampling_radius = false;
  std::string eps_source;  // where eps comes from (a claim, the measured star radii, check 11)
  mpq_class eps, lambda, upsilon, protection, protection_capped;
  mpq_class delta, upsilon0, shortest;  // Definition 3.1 parameters for check 7
  nlohmann::json json_parameters() const;
};

TheoremParams theorem_parameters(const Measured& measured);
CheckEntry theorem_report(const TheoremParams& params, const io::ManifoldSpec& spec);

}  // namespace delcert::certify
