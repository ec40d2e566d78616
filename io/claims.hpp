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
//
// Version 3 ("delcert-claims v3", written by `delcert refine --sizing curvature`) adds per-point
// bounds against a sizing field ε(p), each the name of a text file (relative to claims.json's
// directory) holding one exact rational per point, in the order of the points:
//     "star_radius_per_point": "eps.txt",  // every star simplex s at p has R_p(s) < ε(p)   (check 10)
//     "covering_per_point": "eps.txt"      // every x in M whose nearest point is p has |x - p| < ε(p) (check 11)
// A file, not an inline JSON array: at 10^6 points an array of strings is ~20 MB held as a DOM of
// 10^6 JSON strings (~100 bytes each) before a single value is read, and an error in it could only
// be located by the JSON parser's line; the text file is read line by line into rationals and every
// error names its line. Both keys may name the same file (it is read once). A per-point claim and
// the uniform one of the same name are exclusive. Versions 1 and 2 read exactly as before.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <string>
#include <vector>

namespace delcert::io {

struct Claims {
  std::optional<mpq_class> star_radius;       // > 0
  std::optional<mpq_class> covering;          // > 0
  std::optional<mpq_class> sparsity;          // >= 0
  std::optional<mpq_class> gamma0;            // in (0, 1]
  std::optional<mpq_class> power_protection;  // >= 0, squared distance
  bool secure = false;                        // "secure": true (version 2 only)
  // Version 3: the file names as written in claims.json ("" when absent) and the values read, one
  // per point, each > 0. The number of values is checked against the points by the reader of both.
  std::string star_radius_per_point_file, covering_per_point_file;
  std::vector<mpq_class> star_radius_per_point, covering_per_point;
  std::string star_radius_per_point_path, covering_per_point_path;  // as opened (for messages); not written
  bool any() const {
    return star_radius || covering || sparsity || gamma0 || power_protection || secure ||
           !star_radius_per_point_file.empty() || !covering_per_point_file.empty();
  }
  bool operator==(const Claims&) const = default;
};

// Throws io::InputError("file:line: ...") naming the offending key. A version 3 per-point file is
// opened relative to the directory of `file`.
Claims parse_claims(const std::string& json_text, const std::string& file);
Claims read_claims(const std::string& path);

// The claims.json text (version 2): the keys in the order above (absent claims left out), every value
// written exactly by rational_to_string, indented by two, ending in a newline. parse_claims reads
// it back to the same values.
// Version 3 (when a per-point file is named): the same, with "star_radius_per_point" and
// "covering_per_point" after "covering"; the values are written separately by format_per_point.
std::string format_claims(const Claims& claims);

// A version 3 per-point file: "# delcert per-point eps: one exact rational per point, in the order
// of the points" then one value per line (rational_to_string). Lines that are empty or start with
// '#' are skipped by the reader.
std::string format_per_point(const std::vector<mpq_class>& values);
// Reads one; throws io::InputError(path, line, ...) for a value that is not a positive exact rational.
std::vector<mpq_class> parse_per_point(const std::string& text, const std::string& path);

}  // namespace delcert::io
