// claims.json: what a producer promises about its output (docs/design.md §9, docs/certificate.md).
// Each claim becomes a check in the certificate. Every value is an exact rational written as a
// JSON string ("0.05", "1/20", "2.5e-3") or a JSON integer; JSON floating-point numbers are
// refused because they are already rounded to binary.
//
//   {
//     "format": "delcert-claims v2",
//     "star_radius": "0.3",       // every star simplex has R_p(s) < star_radius    (a distance; check 10)
//     "covering": "0.25",         // P is an eps-sample: d(x, P) < covering, x in M (a distance; check 11)
//     "sparsity": "0.1",          // every two points are at distance > sparsity    (a distance)
//     "gamma0": "0.05",           // every simplex of the complex is gamma0-good    (0 < gamma0 <= 1)
//     "power_protection": "1e-4", // every star simplex is power-protected by more than this
//                                 // (a SQUARED distance, the paper's delta-check^2)
//     "secure": true              // every m-simplex is secure (paper Definition 3.1) with eps
//   }                             // the certified covering radius (check 7); false = no claim
//
// Version 1 ("delcert-claims v1") had one "eps", which meant the star radius: it is still read,
// as star_radius. Version 2 refuses "eps" (it named two different promises). All claims are
// optional; unknown keys are an error (so a typo cannot silently drop a claim).
#pragma once

#include <gmpxx.h>

#include <optional>
#include <string>

namespace delcert::io {

struct Claims {
  std::optional<mpq_class> star_radius;       // > 0
  std::optional<mpq_class> covering;          // > 0
  std::optional<mpq_class> sparsity;          // >= 0
  std::optional<mpq_class> gamma0;            // in (0, 1]
  std::optional<mpq_class> power_protection;  // >= 0, squared distance
  bool secure = false;                        // "secure": true (version 2 only)
  bool any() const { return star_radius || covering || sparsity || gamma0 || power_protection || secure; }
  bool operator==(const Claims&) const = default;
};

// Throws io::InputError("file:line: ...") naming the offending key.
Claims parse_claims(const std::string& json_text, const std::string& file);
Claims read_claims(const std::string& path);

// The claims.json text (version 2): the keys in the order above (absent claims left out), every value
// written exactly by rational_to_string, indented by two, ending in a newline. parse_claims reads
// it back to the same values.
std::string format_claims(const Claims& claims);

}  // namespace delcert::io
