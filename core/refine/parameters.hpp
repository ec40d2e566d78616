// The constants of a refinement run — ε, Γ0, α, β, δ0 — held as exact rationals from the command
// line to claims.json and validated in one place (validate), and μ0. The floating-point algorithm
// uses doubles derived from them in one place (as_doubles).
#pragma once

#include <gmpxx.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace delcert::refine {

// μ0 = 1/9, the sparsity constant of the termination theorem: every inserted point is farther than
// μ0 ε from the points before it, and the claimed protection is δ̌^2 = δ0^2 (μ0 ε)^2. Kept as its
// reciprocal so that μ0 ε in floating point is ε / 9, one correctly rounded division.
inline constexpr int kMu0Reciprocal = 9;
inline double mu0_times(double x) { return x / kMu0Reciprocal; }
mpq_class mu0_times(const mpq_class& x);  // exact, canonical

// An exact parameter and the text it was given as: report.json and the console echo the text as
// typed ("1/10" stays "1/10"), claims.json writes the value.
struct ExactParameter {
  mpq_class value;
  std::string text;  // rational_to_string(value) when made from a value

  ExactParameter() = default;
  explicit ExactParameter(const mpq_class& q);
  // Throws std::invalid_argument when `text` is not a rational literal (parse_rational).
  static ExactParameter parse(std::string_view text);
};

// The paper's constants. ε and δ0 may be left to the refiner; RefineResult::parameters holds
// them resolved.
struct Constants {
  std::optional<ExactParameter> eps;  // absent: two significant digits above the input's largest R_p
  ExactParameter gamma0{mpq_class(3, 20)};
  ExactParameter alpha{mpq_class(3, 10)};
  ExactParameter beta{mpq_class(11, 10)};
  std::optional<ExactParameter> delta0;  // absent: default_delta0(Γ0, m)
};

// A constant out of its range. what() is "OPTION: REASON", as `delcert refine` reports it.
class ParameterError : public std::invalid_argument {
 public:
  ParameterError(const std::string& option, const std::string& reason)
      : std::invalid_argument(option + ": " + reason), option_(option), reason_(reason) {}
  const std::string& option() const { return option_; }  // "--gamma0"
  const std::string& reason() const { return reason_; }

 private:
  std::string option_, reason_;
};

// Throws ParameterError for the first constant out of range, in the order ε, Γ0, α, β, δ0:
// ε > 0, Γ0 in (0, 1], α in (0, 1), β > 0, δ0 in [0, 1), decided on the exact values; ε and β
// must moreover be positive finite doubles, since the algorithm runs in floating point.
void validate(const Constants& c);
void validate_eps(const ExactParameter& eps);  // the ε part of validate

// The doubles the floating-point algorithm works with: each mpq_class::get_d() of the exact value
// (rounded towards zero). The one place they are made. Needs ε and δ0 resolved.
struct ConstantsAsDoubles {
  double eps = 0, gamma0 = 0, alpha = 0, beta = 0, delta0 = 0;
};
ConstantsAsDoubles as_doubles(const Constants& c);

// The default δ0: Γ0^ceil((m+1)/2), so that δ0^2 <= Γ0^(m+1) (hypothesis H3). H3 keeps an
// elementary weight from moving a weighted centre by more than the simplex's own size
// (Lemma 4.1 (3)); with a larger δ0 almost every nearby (m+1)-simplex becomes a hitting set at
// realistic ε and Pick_valid rejects nearly every candidate.
mpq_class default_delta0(const mpq_class& gamma0, int m);

// Sets δ0 to default_delta0(Γ0, m) when it is absent.
void resolve_delta0(Constants& c, int m);

// The constants as typed (command-line text, or the Python module's): an absent ε or δ0 was not given.
struct ConstantTexts {
  std::optional<std::string> eps, delta0;
  std::string gamma0 = "0.15", alpha = "0.3", beta = "1.1";
};
// An exact rational option ("0.1", "1/10", "1e-1"); throws io::InputError naming `option` otherwise.
ExactParameter parse_rational_option(const std::string& option, const std::string& text);
// --eps as `sample` and `refine` read it: parse_rational_option, then validate_eps; throws
// io::InputError naming --eps.
ExactParameter parse_eps_option(const std::string& text);
// The constants parsed exactly (δ0 defaulted for intrinsic dimension m) and validated; throws
// io::InputError naming the option (--eps, --gamma0, ...). When several are wrong, the first
// reported is the one `delcert refine` has always reported: Γ0 is read first when it gives the
// default δ0, ε is checked as soon as it is read, the ranges of the others after all are read.
Constants parse_constants(const ConstantTexts& texts, int m);

// The sizing field (`delcert refine --sizing`): how the target ε varies over M.
//   uniform    ε(x) = ε everywhere (the paper's; the default, output byte-identical to before).
//   curvature  ε(x) = min(ε, max(floor, c / κ_max(x))), κ_max the largest normal curvature of M at
//              x (Manifold::max_normal_curvature, from F's exact Hessians): ε is the cap where M is
//              flat, floor bounds the work where it is sharply curved. Practical mode only.
// c = 1/2 by default: a star cell of radius R < ε(x) <= 1/(2 κ_max) has its vertices within a
// geodesic angle of about κ_max R <= 1/2 rad of the tangent plane at its centre, and a chord of
// length ε(x) sags by about κ ε(x)^2 / 8 <= ε(x)/16 below M: the tangent planes of a star's
// vertices stay within ~30 degrees of each other, where the tangential complex is still consistent
// after the usual refinement (docs/refinement.md, "Sizing field"). The floor defaults to ε / 10.
enum class SizingKind { uniform, curvature };
const char* to_string(SizingKind k);

struct SizingField {
  SizingKind kind = SizingKind::uniform;
  ExactParameter c{mpq_class(1, 2)};
  std::optional<ExactParameter> floor;  // absent: ε / 10 (resolve_sizing)
};
// The default floor: ε / 10.
inline constexpr int kDefaultFloorDivisor = 10;
// Sets the floor to ε / 10 when absent; throws ParameterError (--sizing-c, --eps-floor) when c <= 0,
// the floor <= 0 or above ε, or either not a positive finite double. Needs ε resolved.
void resolve_sizing(SizingField& s, const ExactParameter& eps);

// The decimal with two significant digits just above x (x > 0): 0.4712 -> 0.48 (the smallest such
// decimal whose double exceeds x). The derived ε.
mpq_class decimal_above(double x);

}  // namespace delcert::refine
