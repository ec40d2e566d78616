// Differential soundness suite for every filtered predicate of exact/: the filtered path
// (interval filter, then the exact fallback) must give exactly the answer of the exact-only path
// (FilterContext::force_exact = true) on random and adversarial inputs.
//
// Predicates compared (exact/tangent_predicates.hpp, exact/simplex_predicates.hpp):
//   chart.orientation, chart.cell (orientation / degenerate), cell.power_sign (plain and with a
//   threshold: protection), chart.power_sign, chart.face (degenerate), face.power_sign (plain and
//   with a threshold), one-shot tangent_orientation / tangent_power_sign (plain, threshold),
//   thickness_sign, compare_squared_distances, compare_squared_distance, ambient_power_sign, and
//   ambient_power_sign_on_box (no exact path: a decided sign must be the exact sign at a point of
//   the box).
//
// Adversarial inputs: coordinates from 2^-1074 (subnormal) to DBL_MAX mixed in one input,
// points translated by huge offsets or scaled by 2^k, spec coefficients with huge numerators or
// denominators (tangent bases far beyond 2^512, so that the chart rows' products overflow),
// near-degenerate configurations (points a few ulps off a sphere, cocircular dyadic points,
// nearly collinear points, repeated points, thresholds equal to the exact value), N up to 9 and
// m from 1 to 4.
//
// Seeded (mt19937_64). The amount of work scales with DELCERT_TEST_SCALE (default 1; 0.1 under
// sanitizers; 20 for a long run). The number of comparisons per predicate is printed.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/predicates.hpp"
#include "support.hpp"
#include "tests/test_support.hpp"

namespace delcert::exact {
namespace {

using delcert::test::scaled;
using delcert::test::test_scale;

using testing::Rng;


// ---- tally of comparisons, printed at the end of the program ----

struct Tally {
  std::map<std::string, long> compared, mismatched;
  long skipped_systems = 0;
};
Tally& tally() {
  static Tally t;
  return t;
}

class PrintTally : public ::testing::Environment {
 public:
  void TearDown() override {
    long total = 0;
    std::printf("[differential exact] comparisons per predicate (DELCERT_TEST_SCALE=%g):\n", test_scale());
    for (const auto& [k, n] : tally().compared) {
      std::printf("  %-36s %10ld  mismatches %ld\n", k.c_str(), n, tally().mismatched[k]);
      total += n;
    }
    std::printf("  %-36s %10ld\n", "total", total);
    std::printf("  (random systems skipped as singular at p: %ld)\n", tally().skipped_systems);
  }
};
[[maybe_unused]] ::testing::Environment* const kTallyEnv = ::testing::AddGlobalTestEnvironment(new PrintTally);

std::string hex(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", x);
  return b;
}
std::string hex_point(const double* x, int N) {
  std::string s = "(";
  for (int i = 0; i < N; ++i) s += (i ? ", " : "") + hex(x[i]);
  return s + ")";
}

// Records one comparison; on a mismatch, a failure with the input (printed for the first few).
void compare(const std::string& kind, int filtered, int exact, const std::function<std::string()>& input) {
  ++tally().compared[kind];
  if (filtered == exact) return;
  const long n = ++tally().mismatched[kind];
  if (n <= 3)
    ADD_FAILURE() << kind << ": filtered " << filtered << " but exact " << exact << "\n" << input();
  else
    ADD_FAILURE() << kind << ": mismatch #" << n;
}

// ---- adversarial numbers ----

// A random double of magnitude 2^e for e uniform in [lo, hi] (subnormals below -1022; hi = 1024
// means up to DBL_MAX), random sign and mantissa.
double magnitude(Rng& rng, int lo, int hi) {
  const int e = rng.integer(lo, hi);
  const double mant = 1.0 + rng.uniform();  // [1, 2)
  double v = std::ldexp(mant, std::min(e, 1023));
  if (!std::isfinite(v)) v = DBL_MAX;
  if (rng.integer(0, 9) == 0) v = e >= 1023 ? DBL_MAX : (e <= -1074 ? 0x1.0p-1074 : std::ldexp(1.0, e));
  return rng.integer(0, 1) ? v : -v;
}

// Exponent ranges of an adversarial input (per input; coordinates are mixed within it).
struct Range {
  int lo, hi;
};
Range random_range(Rng& rng) {
  static const Range ranges[] = {{-1074, 1024}, {-1074, -1000}, {-60, 60}, {-1074, 511}, {400, 620},
                                 {900, 1024},   {-600, -400},   {-1074, 30}, {200, 511}};
  return ranges[rng.integer(0, static_cast<int>(std::size(ranges)) - 1)];
}

// Exact decimal text of +-(a * 10^e) or +-(a / 10^e), a small, e large: coefficients whose
// common denominator (which ImplicitSystem scales out) makes the tangent basis huge.
std::string coefficient(Rng& rng) {
  const int a = rng.integer(1, 99);
  const std::string sign = rng.integer(0, 1) ? "" : "-";
  switch (rng.integer(0, 5)) {
    case 0:
    case 1:
      return sign + std::to_string(a);
    case 2: {  // a / 10^e
      mpz_class d;
      mpz_ui_pow_ui(d.get_mpz_t(), 10, rng.integer(1, 330));
      return sign + std::to_string(a) + "/" + d.get_str();
    }
    case 3: {  // a * 10^e
      mpz_class d;
      mpz_ui_pow_ui(d.get_mpz_t(), 10, rng.integer(1, 300));
      return sign + mpz_class(a * d).get_str();
    }
    case 4: {  // a / 2^e
      mpz_class d;
      mpz_ui_pow_ui(d.get_mpz_t(), 2, rng.integer(1, 1100));
      return sign + std::to_string(a) + "/" + d.get_str();
    }
    default: {  // a / b, b odd and large: a non-dyadic coefficient
      mpz_class d;
      mpz_ui_pow_ui(d.get_mpz_t(), 3, rng.integer(1, 600));
      return sign + std::to_string(a) + "/" + d.get_str();
    }
  }
}

// ---- systems ----

struct System {
  std::string name;
  int N = 0, m = 0;
  std::vector<std::string> equations;
  bool on_manifold_sampler = false;  // testing::sample_near applies
};

std::vector<System> fixed_systems() {
  std::vector<System> out;
  for (const auto& M : testing::test_manifolds()) out.push_back({M.name, M.N, M.m, M.equations, true});
  out.push_back({"circle", 2, 1, {"x1^2 + x2^2 - 1"}, false});
  out.push_back({"sphere-4", 5, 4, {"x1^2 + x2^2 + x3^2 + x4^2 + x5^2 - 1"}, false});
  out.push_back({"clifford-torus-4", 8, 4, {"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5^2 + x6^2 - 1", "x7^2 + x8^2 - 1"}, false});
  out.push_back({"plane-in-R3", 3, 2, {"x3"}, false});
  out.push_back({"line-in-R9", 9, 1, {"x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9"}, false});
  return out;
}

// The equation of fixtures/soundness/overflow/spec.json (a quartic curve with a coefficient of
// size 1/10^309), read from the fixture so that the test follows it.
System overflow_fixture_system() {
  std::ifstream f(std::string(DELCERT_FIXTURES_DIR) + "/soundness/overflow/spec.json");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  const auto key = text.find("\"equations\"");
  if (key == std::string::npos) throw std::runtime_error("overflow fixture without equations");
  const auto a = text.find('"', text.find('[', key)) + 1;
  const auto b = text.find('"', a);
  return {"soundness/overflow", 2, 1, {text.substr(a, b - a)}, false};
}

// A random system of k = N - m equations: affine (F_i = c.x + c0) or quadric with a tiny cubic
// term, each coefficient adversarial.
System random_system(Rng& rng, bool force_controlled = false) {
  System S;
  S.N = rng.integer(2, 9);
  S.m = rng.integer(1, std::min(4, S.N - 1));
  const bool quadric = rng.integer(0, 1);
  S.name = std::string(quadric ? "random-quadric" : "random-affine") + " N=" + std::to_string(S.N) +
           " m=" + std::to_string(S.m);
  // Controlled (2/3 of the systems): small integer coefficients and one a / 2^e (or a / 10^e)
  // per equation, e chosen so that the k x k minors of the scaled Jacobian, i.e. the tangent basis entries,
  // are about 2^T with T in [520, 1020]: beyond 2^512 but finite as doubles. Wild: every
  // coefficient adversarial (the basis is often far beyond DBL_MAX).
  const int k = S.N - S.m;
  const bool controlled = force_controlled || rng.integer(0, 2) != 0;
  const int e2 = rng.integer(513, 1015 - 6 * k) / k;  // k! 18^k <= 2^(6k) covers the small factors
  S.name += controlled ? " controlled" : " wild";
  auto coef = [&](bool tiny) {
    if (!controlled) return coefficient(rng);
    const std::string a = (rng.integer(0, 1) ? "" : "-") + std::to_string(rng.integer(1, 9));
    if (!tiny) return a;
    mpz_class d;
    mpz_ui_pow_ui(d.get_mpz_t(), rng.integer(0, 3) ? 2 : 10, rng.integer(0, 3) ? e2 : e2 * 3 / 10);
    return a + "/" + d.get_str();
  };
  for (int i = 0; i < k; ++i) {
    std::string eq;
    const int tiny_at = rng.integer(1, S.N);
    for (int j = 1; j <= S.N; ++j) {
      if (rng.integer(0, 3) == 0 && j != i + 1) continue;  // sparse, but x_{i+1} always present
      const std::string x = "x" + std::to_string(j);
      eq += " + (" + coef(j == tiny_at) + ")*" + x;
      if (quadric) eq += " + (" + coef(false) + ")*" + x + "^2";
    }
    if (quadric && rng.integer(0, 1)) eq += " + (" + coef(true) + ")*x1^3";
    eq += " + (" + coef(false) + ")";
    S.equations.push_back(eq.substr(3));
  }
  return S;
}

// ---- point sets: p (local 0) and its neighbours ----

std::vector<double> nudge(std::vector<double> x, Rng& rng, int max_ulps = 3) {
  const int i = rng.integer(0, static_cast<int>(x.size()) - 1);
  const int k = rng.integer(1, max_ulps);
  for (int j = 0; j < k; ++j) x[i] = std::nextafter(x[i], rng.integer(0, 1) ? INFINITY : -INFINITY);
  if (!std::isfinite(x[i])) x[i] = std::copysign(DBL_MAX, x[i]);
  return x;
}

using Points = std::vector<std::vector<double>>;  // [0] = p

// Exact-only centre of a cell of the chart, rounded to doubles, or empty when degenerate.
std::vector<double> rounded_centre(const TangentCell& cell) {
  if (cell.degenerate()) return {};
  std::vector<double> c;
  for (const auto& q : cell.centre_exact()) {
    const double d = q.get_d();
    if (!std::isfinite(d)) return {};
    c.push_back(d);
  }
  return c;
}

// Mode names (for the failure messages and the tally of inputs).
const char* const kModes[] = {"local", "mixed-magnitude", "translated", "scaled", "degenerate", "ulp-cluster",
                              "overflow-prone"};
constexpr int kNumModes = 7;

// Neighbours of p whose chart-row products u_ia (x_i - p_i) are close to DBL_MAX with mixed
// signs: |x_i - p_i| ~ 2^1024 / max_a |U_ia| times a random factor in [1/8, 2]. When the basis
// entries exceed 2^512 this overflows in the floating-point dot products of the chart rows while
// |x - p|^2 stays finite (the false CERTIFIED of fixtures/soundness/overflow).
Points overflow_prone_points(const System& S, const TangentSpace& T, Rng& rng) {
  const int N = S.N, m = S.m;
  const Eigen::MatrixXd U = T.basis_approx();
  Points P = {std::vector<double>(T.point().begin(), T.point().end())};
  const int n = rng.integer(m + 2, m + 7);
  for (int j = 0; j < n; ++j) {
    std::vector<double> q = P[0];
    for (int i = 0; i < N; ++i) {
      double row = 0;
      for (int a = 0; a < m; ++a) row = std::max(row, std::fabs(U(i, a)));
      const double d = (row > 0 && std::isfinite(row)) ? std::ldexp(rng.uniform(0.25, 4.0), 1024 - std::ilogb(row) - 1)
                                                       : rng.normal();
      q[i] += rng.integer(0, 1) ? d : -d;
      if (!std::isfinite(q[i])) q[i] = std::copysign(DBL_MAX, q[i]);
    }
    P.push_back(q);
  }
  return P;
}

Points make_points(const System& S, int mode, Rng& rng) {
  const int N = S.N;
  Points P;
  std::vector<double> p(N);
  if (S.on_manifold_sampler) {
    for (const auto& M : testing::test_manifolds())
      if (M.name == S.name) p = testing::sample_near(M, rng);
  } else {
    for (auto& v : p) v = rng.normal();
  }
  const int n = rng.integer(S.m + 2, S.m + 9);
  const double h = std::ldexp(1.0, rng.integer(-40, 1));
  auto local = [&] {
    std::vector<double> q = p;
    for (auto& v : q) v += h * rng.normal();
    return q;
  };
  switch (mode) {
    case 0:  // local: small neighbourhood of p
      P.push_back(p);
      for (int i = 0; i < n; ++i) P.push_back(local());
      break;
    case 1: {  // every coordinate of every point of its own magnitude
      const Range r = random_range(rng);
      for (int i = 0; i <= n; ++i) {
        std::vector<double> q(N);
        for (auto& v : q) v = magnitude(rng, r.lo, r.hi);
        P.push_back(q);
      }
      break;
    }
    case 2: {  // local points translated by a huge common offset
      std::vector<double> off(N);
      const int K = rng.integer(20, 1023);
      for (auto& v : off) v = rng.integer(0, 2) ? std::ldexp(rng.normal(), K) : 0.0;
      P.push_back(p);
      for (int i = 0; i < n; ++i) P.push_back(local());
      for (auto& q : P)
        for (int i = 0; i < N; ++i) {
          q[i] += off[i];
          if (!std::isfinite(q[i])) q[i] = std::copysign(DBL_MAX, off[i]);
        }
      break;
    }
    case 3: {  // local points scaled by 2^K (exact unless it underflows or overflows)
      const int K = rng.integer(-1100, 1020);
      P.push_back(p);
      for (int i = 0; i < n; ++i) P.push_back(local());
      for (auto& q : P)
        for (auto& v : q) {
          v = std::ldexp(v, K);
          if (!std::isfinite(v)) v = std::copysign(DBL_MAX, v);
        }
      break;
    }
    case 4: {  // degenerate: repeats, nearly collinear, ulp moves
      P.push_back(p);
      for (int i = 0; i < n; ++i) {
        const int kind = rng.integer(0, 4);
        if (P.size() < 3 || kind == 0) {
          P.push_back(local());
        } else if (kind == 1) {  // a repeat
          P.push_back(P[rng.integer(0, static_cast<int>(P.size()) - 1)]);
        } else if (kind == 2) {  // on the segment between two earlier points (rounded)
          const auto& a = P[rng.integer(0, static_cast<int>(P.size()) - 1)];
          const auto& b = P[rng.integer(0, static_cast<int>(P.size()) - 1)];
          const double t = rng.uniform(-1, 2);
          std::vector<double> q(N);
          for (int k = 0; k < N; ++k) q[k] = a[k] + t * (b[k] - a[k]);
          P.push_back(q);
        } else {  // an earlier point a few ulps away
          P.push_back(nudge(P[rng.integer(0, static_cast<int>(P.size()) - 1)], rng));
        }
      }
      break;
    }
    default: {  // ulp cluster: every neighbour within a few ulps of p, p of any magnitude
      const Range r = random_range(rng);
      for (auto& v : p) v = magnitude(rng, r.lo, r.hi);
      P.push_back(p);
      for (int i = 0; i < n; ++i) P.push_back(nudge(nudge(p, rng, 4), rng, 4));
      break;
    }
  }
  return P;
}

// Cocircular dyadic points in the plane x3 = 0 of R^3 (from Pythagorean triples), scaled by
// 2^K and translated by a multiple of 2^T, all exact: exact zeros of the in-circle test. Some
// are then moved by one ulp.
Points cocircular_points(Rng& rng) {
  static const int triples[][2] = {{3, 4}, {4, 3}, {5, 0}, {0, 5}, {-3, 4}, {-4, -3}, {-5, 0}, {3, -4}, {0, -5}};
  const int K = rng.integer(-1000, 900);
  const double tx = rng.integer(0, 1) ? std::ldexp(static_cast<double>(rng.integer(-8, 8)), K + rng.integer(3, 40)) : 0.0;
  Points P;
  for (const auto& t : triples) P.push_back({std::ldexp(t[0], K) + tx, std::ldexp(t[1], K), 0.0});
  const int moved = rng.integer(0, 3);
  for (int i = 0; i < moved; ++i) {
    auto& q = P[rng.integer(0, static_cast<int>(P.size()) - 1)];
    q = nudge(q, rng, 1);
    q[2] = 0.0;
  }
  return P;
}

std::vector<int> random_subset(Rng& rng, int count, int size, bool with_p) {
  std::vector<int> v;
  if (with_p) v.push_back(0);
  while (static_cast<int>(v.size()) < size) v.push_back(rng.integer(with_p ? 1 : 0, count - 1));
  // shuffle
  for (int i = static_cast<int>(v.size()) - 1; i > 0; --i) std::swap(v[i], v[rng.integer(0, i)]);
  return v;
}

// Thresholds for the protection tests: 0, random of any magnitude, and `exact` (the exact
// value, an exact tie) with its neighbours.
std::vector<mpq_class> thresholds(Rng& rng, const mpq_class* exact) {
  std::vector<mpq_class> out = {0, to_rational(std::fabs(magnitude(rng, -1074, 1024)))};
  if (exact && *exact >= 0) {
    out.push_back(*exact);
    out.push_back(*exact * mpq_class(1, 1) + mpq_class(1, 1) / mpq_class(mpz_class(1) << 1100));
    if (*exact > 0) out.push_back(*exact - *exact / mpq_class(mpz_class(1) << 60));
  }
  return out;
}

std::string describe(const System& S, const Points& P, const char* mode) {
  std::string s = "system " + S.name + " (N=" + std::to_string(S.N) + ", m=" + std::to_string(S.m) + "), mode " + mode +
                  "\nequations:";
  for (const auto& e : S.equations) s += "\n  " + e;
  s += "\npoints (local index: coordinates):";
  for (std::size_t i = 0; i < P.size(); ++i) s += "\n  " + std::to_string(i) + ": " + hex_point(P[i].data(), S.N);
  return s;
}

// Every tangent-space predicate on one chart, filtered against exact-only.
void tangent_round(const System& S, const TangentSpace& T, const Points& P, const char* mode, Rng& rng,
                   int orientations = 6) {
  const int m = S.m, N = S.N;
  std::vector<const double*> others;
  for (std::size_t i = 1; i < P.size(); ++i) others.push_back(P[i].data());
  TangentChart chart(T, others);
  const int n = chart.size();
  FilterContext f, x;
  x.force_exact = true;
  auto in = [&] { return describe(S, P, mode); };
  auto with = [&](const std::vector<int>& v, int q) {
    return [&, v, q] {
      std::string s = in() + "\nvertices:";
      for (int i : v) s += " " + std::to_string(i);
      return s + (q >= 0 ? "  query: " + std::to_string(q) : "");
    };
  };
  auto ptrs = [&](const std::vector<int>& v) {
    std::vector<const double*> out;
    for (int i : v) out.push_back(P[i].data());
    return out;
  };
  // Orientations are cheap: many, half of them without p (rows compared with each other).
  for (int c = 0; c < orientations; ++c) {
    const auto v = random_subset(rng, n, m + 1, rng.integer(0, 1) != 0);
    compare("chart.orientation", chart.orientation(v, f), chart.orientation(v, x), with(v, -1));
    compare("tangent_orientation (one-shot)", tangent_orientation(T, ptrs(v), f), tangent_orientation(T, ptrs(v), x),
            with(v, -1));
  }
  const int cells = 3;
  for (int c = 0; c < cells; ++c) {
    const auto v = random_subset(rng, n, m + 1, rng.integer(0, 3) != 0);
    const TangentCell cf = chart.cell(v, f), cx = chart.cell(v, x);
    compare("chart.cell orientation", cf.orientation(), cx.orientation(), with(v, -1));
    compare("chart.cell degenerate", cf.degenerate(), cx.degenerate(), with(v, -1));
    // Queries: every local point, plus (in a second chart) points near the cell's sphere.
    for (int q = 0; q < n; ++q) {
      compare("cell.power_sign", cf.power_sign(q, f), cx.power_sign(q, x), with(v, q));
      if (q % 3 == 0)
        compare("chart.power_sign", chart.power_sign(v, q, f), chart.power_sign(v, q, x), with(v, q));
      mpq_class value;
      const bool have = !cx.degenerate();
      if (have) value = cx.power_exact(q);
      for (const auto& d : thresholds(rng, have ? &value : nullptr)) {
        const RationalConstant delta(d);
        compare("cell.power_sign threshold", cf.power_sign(q, delta, f), cx.power_sign(q, delta, x), with(v, q));
      }
      if (q % 2 == 0) {
        const auto cp = ptrs(v);
        compare("tangent_power_sign (one-shot)", tangent_power_sign(T, cp, P[q].data(), f),
                tangent_power_sign(T, cp, P[q].data(), x), with(v, q));
        const RationalConstant delta(have && value > 0 ? value : mpq_class(0));
        compare("tangent_power_sign threshold (one-shot)", tangent_power_sign(T, cp, P[q].data(), delta, f),
                tangent_power_sign(T, cp, P[q].data(), delta, x), with(v, q));
      }
    }
    // Points on (up to rounding) and a few ulps off the cell's ambient sphere: the reflection
    // of each vertex through the centre, and vertices moved by ulps.
    const auto centre = rounded_centre(cx);
    if (!centre.empty()) {
      Points extra;
      for (int i : v) {
        std::vector<double> r(N);
        bool ok = true;
        for (int k = 0; k < N; ++k) {
          r[k] = 2 * centre[k] - P[i][k];
          ok = ok && std::isfinite(r[k]);
        }
        if (ok) extra.push_back(r), extra.push_back(nudge(r, rng, 1));
        extra.push_back(nudge(P[i], rng, 1));
      }
      std::vector<const double*> all = others;
      for (const auto& e : extra) all.push_back(e.data());
      TangentChart chart2(T, all);
      const TangentCell cf2 = chart2.cell(v, f), cx2 = chart2.cell(v, x);
      compare("chart.cell orientation", cf2.orientation(), cx2.orientation(), with(v, -1));
      for (int q = n; q < chart2.size(); ++q) {
        compare("cell.power_sign near sphere", cf2.power_sign(q, f), cx2.power_sign(q, x), [&, q] {
          return with(v, -1)() + "\nquery near the sphere: " + hex_point(chart2.coordinates(q).data(), N);
        });
        if (!cx2.degenerate()) {
          const RationalConstant delta(mpq_class(abs(cx2.power_exact(q))));
          compare("cell.power_sign threshold near sphere", cf2.power_sign(q, delta, f), cx2.power_sign(q, delta, x),
                  [&, q] { return with(v, -1)() + "\nquery near the sphere: " + hex_point(chart2.coordinates(q).data(), N); });
        }
      }
    }
  }
  // Faces through p, k = 1..m.
  for (int k = 1; k <= m; ++k) {
    const auto v = random_subset(rng, n, k + 1, true);
    const TangentFace ff = chart.face(v, f), fx = chart.face(v, x);
    compare("chart.face degenerate", ff.degenerate(), fx.degenerate(), with(v, -1));
    for (int q = 0; q < n; ++q) {
      compare("face.power_sign", ff.power_sign(q, f), fx.power_sign(q, x), with(v, q));
      mpq_class value;
      const bool have = !fx.degenerate();
      if (have) value = fx.power_exact(q);
      if (q % 2 == 0)
        for (const auto& d : thresholds(rng, have ? &value : nullptr)) {
          const RationalConstant delta(d);
          compare("face.power_sign threshold", ff.power_sign(q, delta, f), fx.power_sign(q, delta, x), with(v, q));
        }
    }
  }
}

// Every simplex predicate on a point set (any N), filtered against exact-only.
void simplex_round(int N, const Points& P, const std::string& what, Rng& rng) {
  FilterContext f, x;
  x.force_exact = true;
  const int n = static_cast<int>(P.size());
  auto in = [&] {
    std::string s = what + "\npoints:";
    for (int i = 0; i < n; ++i) s += "\n  " + std::to_string(i) + ": " + hex_point(P[i].data(), N);
    return s;
  };
  auto pick = [&] { return P[rng.integer(0, n - 1)].data(); };
  // Thickness of j-simplices, j = 1..min(7, n - 1), against 0, 1, a random and the exact value.
  for (int t = 0; t < 3; ++t) {
    const int j = rng.integer(1, std::min(kMaxThicknessSimplexDimension, n - 1));
    std::vector<const double*> v;
    std::vector<int> idx;
    for (int i = 0; i <= j; ++i) {
      idx.push_back(rng.integer(0, n - 1));
      v.push_back(P[idx.back()].data());
    }
    const mpq_class ex = thickness_squared_exact(v, N);
    for (const mpq_class& g2 : {mpq_class(0), mpq_class(1), ex, mpq_class(ex + mpq_class(1, 1) / (mpz_class(1) << 200)),
                                mpq_class(ex * mpq_class(1023, 1024)), to_rational(rng.uniform())}) {
      const RationalConstant gc(g2);
      compare("thickness_sign", thickness_sign(v, N, gc, f), thickness_sign(v, N, gc, x), [&] {
        std::string s = in() + "\nsimplex:";
        for (int i : idx) s += " " + std::to_string(i);
        return s + "\ngamma^2 = " + g2.get_str();
      });
    }
  }
  // Squared distances: random quadruples and exact ties (the same pair reversed, translated).
  for (int t = 0; t < 6; ++t) {
    const double *a = pick(), *b = pick(), *c = pick(), *d = pick();
    auto msg = [&] { return in() + "\na b c d = " + hex_point(a, N) + " " + hex_point(b, N) + " " + hex_point(c, N) + " " + hex_point(d, N); };
    compare("compare_squared_distances", compare_squared_distances(a, b, c, d, N, f),
            compare_squared_distances(a, b, c, d, N, x), msg);
    compare("compare_squared_distances", compare_squared_distances(a, b, b, a, N, f),
            compare_squared_distances(a, b, b, a, N, x), msg);
    const mpq_class ex = squared_distance_exact(a, b, N);
    for (const mpq_class& r2 : {ex, mpq_class(ex + mpq_class(1, 1) / (mpz_class(1) << 1100)),
                                mpq_class(ex - ex / (mpz_class(1) << 70)), to_rational(std::fabs(magnitude(rng, -1074, 1024)))}) {
      const RationalConstant rc(r2);
      compare("compare_squared_distance", compare_squared_distance(a, b, rc, N, f),
              compare_squared_distance(a, b, rc, N, x), [&] { return msg() + "\nr^2 = " + r2.get_str(); });
    }
    // Ambient power at the exact midpoint (an exact tie), a nearby rational and a random point.
    std::vector<mpq_class> mid(N), near(N), rnd(N);
    for (int i = 0; i < N; ++i) {
      mid[i] = (to_rational(a[i]) + to_rational(b[i])) / 2;
      near[i] = mid[i] + mpq_class(rng.integer(-3, 3), 7) * (to_rational(a[i]) - to_rational(b[i])) / (mpz_class(1) << 60);
      rnd[i] = to_rational(c[i]) / 3;
    }
    for (const auto* xs : {&mid, &near, &rnd}) {
      const RationalPoint X(*xs);
      const int fs = ambient_power_sign(X, a, b, f), es = ambient_power_sign(X, a, b, x);
      compare("ambient_power_sign", fs, es, msg);
      // The box version has no exact path: a decided sign must be the exact sign at X.
      const int bs = ambient_power_sign_on_box(X.enclosure(), a, b);
      compare("ambient_power_sign_on_box (decided = exact)", bs == 0 ? es : bs, es, msg);
    }
  }
}

struct SystemCase {
  System S;
  ImplicitSystem F;
};

bool run_chart(const SystemCase& C, int mode, Rng& rng) {
  Points P = make_points(C.S, mode == 6 ? 0 : mode, rng);
  std::optional<TangentSpace> T;
  try {
    T.emplace(C.F, P[0]);
  } catch (const std::domain_error&) {
    ++tally().skipped_systems;  // p is a singular point of F (rank-deficient Jacobian)
    return false;
  }
  if (mode == 6) P = overflow_prone_points(C.S, *T, rng);
  tangent_round(C.S, *T, P, kModes[mode], rng, mode == 6 ? 60 : 6);
  simplex_round(C.S.N, P, describe(C.S, P, kModes[mode]), rng);
  return true;
}

TEST(Differential, FixedManifoldsAllModes) {
  Rng rng(0x5eed0001);
  std::vector<SystemCase> cases;
  for (const auto& S : fixed_systems()) cases.push_back({S, ImplicitSystem::parse(S.equations, S.N)});
  const int rounds = scaled(8);
  for (int r = 0; r < rounds; ++r)
    for (const auto& C : cases)
      for (int mode = 0; mode < kNumModes; ++mode) {
        SCOPED_TRACE(C.S.name + " mode " + kModes[mode]);
        run_chart(C, mode, rng);
        if (::testing::Test::HasFailure() && tally().mismatched.size() > 20) return;
      }
}

TEST(Differential, RandomSystemsWithHugeAndTinyCoefficients) {
  Rng rng(0x5eed0002);
  const int systems = scaled(60);
  for (int s = 0; s < systems; ++s) {
    System S = random_system(rng);
    const SystemCase C{S, ImplicitSystem::parse(S.equations, S.N)};
    for (int mode = 0; mode < kNumModes; ++mode) {
      SCOPED_TRACE(S.name + " mode " + kModes[mode]);
      run_chart(C, mode, rng);
    }
  }
}

// Charts whose basis entries lie between 2^512 and DBL_MAX, with neighbours placed so that the
// chart-row products straddle DBL_MAX (overflow-prone mode): many orientations and a few cells.
// This is the test that fails when interval_row trusts a finite result of an overflowed sum.
// Crafted: for a random column a of U, the first product u_ia d_i (i with u_ia != 0) is about
// -c1 2^1024 (it overflows negatively), the following ones are positive and below DBL_MAX,
// summing to c2 2^1024 with 1 < c2 < c1 when there are at least three of them: the exact
// b_a = U^T (x - p) is negative, while a sum that clamps the overflow at -DBL_MAX ends positive.
Points crafted_overflow_points(const System& S, const TangentSpace& T, Rng& rng) {
  const int N = S.N, m = S.m;
  const Eigen::MatrixXd U = T.basis_approx();
  Points P = {std::vector<double>(T.point().begin(), T.point().end())};
  const int n = rng.integer(m + 2, m + 6);
  for (int j = 0; j < n; ++j) {
    const int a = rng.integer(0, m - 1);
    std::vector<int> I;
    for (int i = 0; i < N; ++i)
      if (U(i, a) != 0 && std::isfinite(U(i, a))) I.push_back(i);
    std::vector<double> q = P[0];
    if (I.size() >= 2) {
      const double c1 = rng.uniform(1.05, 1.9);
      const int r = static_cast<int>(I.size()) - 1;
      const double c2 = r >= 2 ? rng.uniform(1.0, c1) : rng.uniform(0.3, 0.99);
      for (int k = 0; k <= r; ++k) {
        const double target = k == 0 ? -c1 : c2 / r;  // in units of 2^1024
        const double d = std::ldexp(target / U(I[k], a), 1024);
        q[I[k]] += std::isfinite(d) ? d : 0.0;
      }
    }
    P.push_back(q);
  }
  return P;
}

TEST(Differential, OverflowProneCharts) {
  Rng rng(0x5eed0005);
  const int systems = scaled(150);
  for (int s = 0; s < systems; ++s) {
    const System S = random_system(rng, true);
    const ImplicitSystem F = ImplicitSystem::parse(S.equations, S.N);
    std::vector<double> p(S.N);
    for (auto& v : p) v = rng.normal();
    std::optional<TangentSpace> T;
    try {
      T.emplace(F, p);
    } catch (const std::domain_error&) {
      ++tally().skipped_systems;
      continue;
    }
    SCOPED_TRACE(S.name);
    for (int c = 0; c < 3; ++c) tangent_round(S, *T, overflow_prone_points(S, *T, rng), kModes[6], rng, 40);
    tangent_round(S, *T, crafted_overflow_points(S, *T, rng), "crafted-overflow", rng, 40);
  }
}

TEST(Differential, OverflowFixtureSpec) {
  Rng rng(0x5eed0003);
  const System S = overflow_fixture_system();
  const SystemCase C{S, ImplicitSystem::parse(S.equations, S.N)};
  // The fixture's own points first (fixtures/soundness/overflow/points.txt), then random ones.
  const Points fixture = {{0.6, -0.8}, {-0.26, 0.41}, {-0.9, 0.4}, {-0.2047, 0.1232}};
  for (int p = 0; p < 4; ++p) {
    Points P = {fixture[p]};
    for (int q = 0; q < 4; ++q)
      if (q != p) P.push_back(fixture[q]);
    const TangentSpace T(C.F, P[0]);
    tangent_round(S, T, P, "fixture", rng);
  }
  const int rounds = scaled(40);
  for (int r = 0; r < rounds; ++r)
    for (int mode = 0; mode < kNumModes; ++mode) {
      SCOPED_TRACE(std::string("overflow spec mode ") + kModes[mode]);
      run_chart(C, mode, rng);
    }
}

TEST(Differential, CocircularDyadicPoints) {
  Rng rng(0x5eed0004);
  const System S = {"plane-in-R3", 3, 2, {"x3"}, false};
  const ImplicitSystem F = ImplicitSystem::parse(S.equations, S.N);
  const int rounds = scaled(150);
  for (int r = 0; r < rounds; ++r) {
    const Points P = cocircular_points(rng);
    const TangentSpace T(F, P[0]);
    tangent_round(S, T, P, "cocircular", rng);
    simplex_round(3, P, describe(S, P, "cocircular"), rng);
  }
}

}  // namespace
}  // namespace delcert::exact
