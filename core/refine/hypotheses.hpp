// The hypotheses H0-H5 of the paper's §5 for given parameters: which hold, which fail, which
// cannot be decided because the paper leaves a constant unspecified, and the largest ε the
// decidable parts allow given the manifold's reach.
//
//   ε̃ = ε / rch(M),  ε̃0 = 1 / (2^4 (2^4 + 1)^2),  B = 4 + 2 (1 + 2^7 3^2 β^2)^2,
//   β' = β / (1 - 2^4 ε̃0),  V_m = volume of the unit m-ball,
//   H0  α < 1/2
//   H1  β >= 2 / ((1 - δ0^2)(1 - α - 4.5 ε̃0))
//   H2  Γ0 < min{ V_m α^m / (E^{m+1} β^m D),  1 / (B + 1) }      E needs ξ and A; D unspecified
//   H3  δ0^2 <= Γ0^{m+1}
//   H4  ε̃ <= min{ ξ / (2 (β + β') rch),  Γ0^{m+1} / (8 β) }     ξ unspecified
//   H5  ε̃ <= δ0^2 Γ0^{2m} / (1.1 10^9)
// ξ (depends on m and rch) and A (depends on m), from the "bound on sparse points" lemma, and D
// (depends on m and β), from the "volume of forbidden region" lemma, are only shown to exist.
// A hypothesis with an unspecified term is reported "not evaluable" when its specified part
// holds, and "fails" when its specified part already fails (the unspecified term can only make
// the bound smaller).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/refine/parameters.hpp"
#include "exact/tri.hpp"

namespace delcert::refine {

// A hypothesis holds (yes), fails (no) or is not evaluable (unknown).
// The words report.json writes: "holds", "fails", "not_evaluable".
const char* status_name(exact::Tri status);

struct HypothesisCheck {
  std::string name;       // "H0" .. "H5"
  std::string statement;  // the inequality as in the paper
  exact::Tri status = exact::Tri::unknown;
  std::string detail;     // the numbers, and what is missing
  std::optional<double> lhs, rhs;  // the evaluated sides of the decidable part, when there is one
};

struct HypothesesInput {
  int m = 2;
  // ε and δ0 set. H3 (δ0^2 <= Γ0^(m+1)), which the default δ0 meets with equality, is decided in
  // exact arithmetic; the rest on as_doubles(constants).
  Constants constants;
  std::optional<double> reach;  // rch(M); without it the ε-hypotheses cannot be evaluated
  bool reach_is_lower_bound = false;
};

struct HypothesesReport {
  std::vector<HypothesisCheck> checks;  // H0..H5 in order
  double eps0_tilde = 0;                // ε̃0
  double mu0 = 1.0 / kMu0Reciprocal;    // μ0 (the sparsity constant of the termination theorem)
  bool sparsity_lemma_holds = false;    // (1 - δ0^2)(1 - α - 4.5 ε̃0) / 4 > 1/9 (eq. sparsity.bound)
  double sparsity_lemma_lhs = 0;
  // Largest ε allowed by the decidable parts of H4 and H5 (and ε̃ < ε̃0), given the reach: an
  // upper bound on what the full hypotheses allow (the ξ term of H4 can only lower it).
  std::optional<double> max_eps;
  std::string max_eps_note;
  std::vector<std::string> unspecified;  // "ξ", "A", "D" with where they come from
  bool any_fails = false;
  bool all_hold = false;                 // every hypothesis decided and holding (never, in practice)
};

HypothesesReport evaluate_hypotheses(const HypothesesInput& in);

}  // namespace delcert::refine
