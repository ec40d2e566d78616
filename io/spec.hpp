// Manifold specs (JSON). A spec describes M as the zero set of a polynomial system
// F: R^N -> R^(N-m) with exact rational coefficients (docs/design.md §2, §9).
//
//   {
//     "format": "delcert-manifold v1",
//     "name": "sphere-2",
//     "intrinsic_dimension": 2, "ambient_dimension": 3,
//     "equations": ["x1^2 + x2^2 + x3^2 - 1"],           // N - m polynomials in x1..xN
//     "selector": "x1*x5*x9 - ...",                       // optional: keep the component where it is > 0
//     "reach": {"value": "1", "kind": "exact"},           // optional; value "q" or "sqrt(q)", kind exact|lower_bound
//     "metric": {"type": "sphere", "center": ["0","0","0"], "radius": "1"},   // optional closed form
//              | {"type": "product_of_circles", "radii": ["1","1"]}           // circles in (x1,x2),(x3,x4),...
//              | {"type": "so3"}                                              // x1..x9 = a rotation, row-major
//              | {"type": "product", "factors": [{"type": "sphere", "coordinates": [1, 2, 3], "radius": "1"},
//                                                {"type": "sphere", "coordinates": [4, 5], "radius": "2"}]}
//                                      // S^2 x S^1; factor types sphere (k + 1 coordinates, centred at 0)
//                                      // and so3 (9 coordinates); the blocks are disjoint and cover x1..xN
//     "parametrization": {...same shapes as metric, plus "torus_of_revolution" with
//                         "major_radius", "minor_radius"},                     // optional, for sampling
//     "bounding_box": [["-1.5","1.5"], ...],              // optional, N intervals, for generic sampling
//     "residual_tolerance": "1e-9",                        // optional: max |F_i(p)| accepted for input points
//     "expected": {"euler_characteristic": 2, "betti_z2": [1,0,1], "betti_z3": [1,0,1]}   // optional
//   }
//
// builtin:NAME reads the spec compiled into the program from fixtures/manifolds/NAME.json.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "exact/polynomial.hpp"

namespace delcert::io {

struct ReachSpec {
  std::string text;      // as written, e.g. "sqrt(2)"
  mpq_class squared;     // reach^2, exact
  bool exact = true;     // false: a lower bound
};

// One factor of a product shape: a round sphere of radius r centred at the origin of its k + 1
// coordinates (a circle when k = 1), or SO(3) on nine coordinates (row-major).
struct ShapeFactor {
  enum class Kind { sphere, so3 };
  Kind kind = Kind::sphere;
  std::vector<int> coordinates;  // 0-based, in the order given (disjoint across factors)
  mpq_class radius;              // sphere
  int dimension() const { return kind == Kind::so3 ? 3 : static_cast<int>(coordinates.size()) - 1; }
};

// Closed-form shapes shared by "metric" and "parametrization".
struct ShapeSpec {
  enum class Kind { sphere, product_of_circles, torus_of_revolution, so3, product };
  Kind kind = Kind::sphere;
  std::vector<ShapeFactor> factors;  // product: disjoint coordinate blocks covering x1..xN
  std::vector<mpq_class> center;  // sphere
  mpq_class radius;               // sphere
  std::vector<mpq_class> radii;   // product_of_circles, in coordinate pairs (x1,x2), (x3,x4), ...
  mpq_class major_radius, minor_radius;  // torus_of_revolution, axis x3
};

struct ExpectedTopology {
  std::optional<long> euler_characteristic;
  std::vector<long> betti_z2, betti_z3;  // empty when not given
};

struct ManifoldSpec {
  std::string source;  // the path or builtin:NAME it was read from
  std::string name;
  int intrinsic_dimension = 0;  // m
  int ambient_dimension = 0;    // N
  std::vector<std::string> equation_text;
  std::vector<exact::Polynomial> equations;  // N - m of them
  std::optional<exact::Polynomial> selector;  // component where selector > 0
  std::string selector_text;
  std::optional<ReachSpec> reach;
  std::optional<ShapeSpec> metric;
  std::optional<ShapeSpec> parametrization;
  std::vector<std::pair<double, double>> bounding_box;  // empty or N intervals
  mpq_class residual_tolerance{1, 1000000000};           // 1e-9
  ExpectedTopology expected;
};

// `source` is a file path or builtin:NAME. Throws InputError naming the file, the line and the
// field. The reader is strict: unknown keys (at any level), duplicate keys, JSON numbers with a
// fraction, integers out of range and polynomials beyond PolynomialLimits are refused.
ManifoldSpec read_spec(const std::string& source);
ManifoldSpec parse_spec(const std::string& json_text, const std::string& source);
// The bytes read_spec parses: the file's content, or the compiled-in text of builtin:NAME. A
// caller that also hashes the spec reads it once with this and passes the same text to
// parse_spec (a second read of a FIFO or of a file being rewritten would hash other bytes).
std::string read_spec_text(const std::string& source);

// The command-line override of residual_tolerance (delcert-certify --residual-tolerance): a
// positive rational written as an integer, a decimal ("1e-6") or a fraction ("1/1000000"), read
// exactly. Throws InputError naming `option` otherwise (zero, negative, malformed, "inf", "nan").
mpq_class parse_residual_tolerance(const std::string& text, const std::string& option = "--residual-tolerance");

// Names of the built-in specs, sorted.
std::vector<std::string> builtin_spec_names();
// The built-in name nearest to `name` by edit distance (case-insensitive), when it is near enough
// to be a misspelling (at most max(2, length / 3) edits); else "". read_spec_text names it when
// builtin:NAME is unknown, or when a file that does not exist is named like a built-in.
std::string nearest_builtin_spec_name(const std::string& name);
// The text of a built-in spec, or nullptr.
const char* builtin_spec_text(const std::string& name);

}  // namespace delcert::io
