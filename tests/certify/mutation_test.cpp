// Mutation suite (soundness): valid certified inputs are mutated in seeded, random ways - drop a
// simplex, add a simplex, replace a vertex, swap two points, move a point onto a Delaunay sphere
// to within one ulp - and every mutant must come back REFUTED or UNDECIDED, never CERTIFIED.
// Bases: every built-in with a sample generator (sphere-2, sphere-3, clifford-torus-2,
// clifford-torus-3, torus-of-revolution; so3 has none, see fixtures/manifolds), and huge- and
// tiny-magnitude variants (the input scaled by 2^k, the spec scaled accordingly), which must
// still certify. Variants that must keep the verdict: one-ulp moves of points of a valid input.
// At least 1,000 mutants per run; the tally per kind is printed. One more kind runs checks 11-12:
// a sample of two spheres with one component emptied (EmptiedComponentMutantsAreNeverCertified).
#include <array>
#include <map>
#include <set>

#include "exact/number_types.hpp"

#include "exact/tangent_predicates.hpp"
#include "support.hpp"
#include "tests/test_support.hpp"

namespace delcert::certify::test {
namespace {

using delcert::test::scaled;
using delcert::test::test_scale;

struct Base {
  std::string spec;
  std::string shape;  // "sphere", "circles" (a product of circles) or "torus-of-revolution"
  double scale;       // the manifold is the built-in scaled by this power of 2
  io::PointSet points;
  io::Complex complex;
  std::string claims;
  int per_kind;
  std::uint64_t seed;
};

// Claims slightly weaker than the measured values (as a producer would state them).
std::string claims_for(const Certificate& c) {
  auto D = [](const nlohmann::json& s) {
    const std::string t = s.is_string() ? s.get<std::string>() : s.dump();
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    EXPECT_TRUE(end != t.c_str() && std::isfinite(v)) << "not a finite number: " << t;
    return v;
  };
  double r2 = D(check(c, CheckId::star_radius).margin["max_radius_squared"]["certified_upper_bound"]);
  double d = D(check(c, CheckId::sparsity).margin["min_distance"]["certified_lower_bound"]);
  double prot = D(check(c, CheckId::power_protection).margin["min_power_margin"]["certified_lower_bound"]);
  char buf[512];
  std::snprintf(buf, sizeof buf, R"({"format": "delcert-claims v1", "eps": "%.17g", "sparsity": "%.17g", "power_protection": "%.17g"})",
                std::sqrt(r2) * 1.01, d * 0.99, prot * 0.5);
  return buf;
}

Certificate run_case(const TempDir& dir, const std::string& spec, const io::PointSet& P, const io::Complex& K,
                     const std::string& claims) {
  CertifyOptions o;
  o.skip_restricted = true;  // these tests are about Del_TM (checks 11-13: restricted_test.cpp)
  o.manifold = spec;
  o.points = dir.file("points.txt");
  o.complex = dir.file("complex.txt");
  o.claims = dir.file("claims.json");
  io::write_points(o.points, P);
  io::write_complex(o.complex, K);
  write_text(o.claims, claims);
  return run_certify(o);
}

std::set<Simplex> as_set(const io::Complex& K) {
  std::set<Simplex> s;
  for (auto t : K.simplices) {
    std::sort(t.begin(), t.end());
    s.insert(t);
  }
  return s;
}

// Nearest point to M along the closed-form projection of the built-in (sphere, flat torus, torus
// of revolution R = 2, r = 1 about x3), for M scaled by `scale`.
void project(const std::string& shape, double scale, std::vector<double>& x) {
  for (double& v : x) v /= scale;
  if (shape == "sphere") {
    double s = 0;
    for (double v : x) s += v * v;
    for (double& v : x) v /= std::sqrt(s);
  } else if (shape == "torus-of-revolution") {
    const double rho = std::hypot(x[0], x[1]), h = std::hypot(rho - 2, x[2]);
    const double rho2 = 2 + (rho - 2) / h;
    x[0] *= rho2 / rho, x[1] *= rho2 / rho, x[2] /= h;
  } else {  // product of unit circles in coordinate pairs
    for (std::size_t k = 0; k + 1 < x.size(); k += 2) {
      double s = std::hypot(x[k], x[k + 1]);
      x[k] /= s, x[k + 1] /= s;
    }
  }
  for (double& v : x) v *= scale;
}

// Moves point q of P onto the sphere of the cell s (centred on T_p) along M, to within rounding,
// then by `ulps` ulps in coordinate `coord`. False when no such position was found. `sign` is the
// exact sign of |c - q|^2 - R^2 after the move (computed here independently of the certifier).
bool move_onto_sphere(const Base& B, io::PointSet& P, int p, const Simplex& s, int q, int coord, int ulps, int& sign) {
  const std::string& spec_source = B.spec;
  io::ManifoldSpec spec = io::read_spec(spec_source);
  exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);
  exact::TangentSpace T(system, P.point(p));
  std::vector<const double*> ptrs;
  std::vector<int> local;
  for (int v : s)
    if (v != p) ptrs.push_back(P.point(v).data());
  exact::TangentChart chart(T, std::span<const double* const>(ptrs));
  std::vector<int> cell_vertices(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) cell_vertices[i] = static_cast<int>(i);
  exact::FilterContext ctx;
  exact::TangentCell cell = chart.cell(cell_vertices, ctx);
  if (cell.degenerate()) return false;
  std::vector<double> c;
  for (const auto& x : cell.centre_exact()) c.push_back(x.get_d());
  double R2 = cell.squared_radius_exact().get_d();
  const int N = P.dimension;
  std::vector<double> from(P.point(q).begin(), P.point(q).end()), to(N, 0);
  for (int v : s)
    for (int k = 0; k < N; ++k) to[k] += P.point(v)[k] / s.size();
  auto at = [&](double t) {
    std::vector<double> x(N);
    for (int k = 0; k < N; ++k) x[k] = (1 - t) * from[k] + t * to[k];
    project(B.shape, B.scale, x);
    return x;
  };
  auto f = [&](const std::vector<double>& x) {
    double d = 0;
    for (int k = 0; k < N; ++k) d += (x[k] - c[k]) * (x[k] - c[k]);
    return d - R2;
  };
  double lo = 0, hi = 1;
  if (!(f(at(lo)) > 0 && f(at(hi)) < 0)) return false;
  for (int it = 0; it < 200; ++it) {
    double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (f(at(mid)) > 0 ? lo : hi) = mid;
  }
  std::vector<double> x = at(hi);
  for (int u = 0; u < std::abs(ulps); ++u) x[coord] = std::nextafter(x[coord], ulps > 0 ? INFINITY : -INFINITY);
  std::copy(x.begin(), x.end(), P.coordinates.begin() + static_cast<long>(q) * N);
  ptrs.push_back(P.point(q).data());
  exact::TangentChart moved(T, std::span<const double* const>(ptrs));
  sign = moved.cell(cell_vertices, ctx).power_sign(static_cast<int>(ptrs.size()), ctx);
  return true;
}

struct Tally {
  std::map<std::string, std::array<int, 3>> by_kind;  // certified, refuted, undecided
  int variants = 0, variants_same = 0;                // one-ulp moves of a valid input
};

void run_mutants(const Base& B, Tally& tally) {
  TempDir dir("mut");
  Rng rng(B.seed);
  const auto K0 = as_set(B.complex);
  std::vector<Simplex> simplices(K0.begin(), K0.end());
  const int n = static_cast<int>(B.points.size());
  std::vector<std::vector<int>> incident(n);
  for (std::size_t i = 0; i < simplices.size(); ++i)
    for (int v : simplices[i]) incident[v].push_back(static_cast<int>(i));
  auto neighbour_of = [&](const Simplex& s) {  // a vertex of a simplex sharing a vertex with s, not in s
    for (int tries = 0; tries < 100; ++tries) {
      int v = s[rng.below(static_cast<int>(s.size()))];
      const Simplex& t = simplices[incident[v][rng.below(static_cast<int>(incident[v].size()))]];
      int w = t[rng.below(static_cast<int>(t.size()))];
      const Simplex& u = simplices[incident[w][rng.below(static_cast<int>(incident[w].size()))]];
      int z = u[rng.below(static_cast<int>(u.size()))];
      if (std::find(s.begin(), s.end(), z) == s.end()) return z;
    }
    return -1;
  };
  auto record = [&](const std::string& kind, const Certificate& c, const std::string& what) {
    Verdict v = c.overall();
    EXPECT_NE(v, Verdict::certified) << B.spec << " " << kind << " mutant CERTIFIED: " << what;
    tally.by_kind[kind][v == Verdict::certified ? 0 : v == Verdict::refuted ? 1 : 2]++;
  };
  auto complex_of = [&](const std::set<Simplex>& s) {
    io::Complex K;
    K.num_vertices = n;
    K.simplices.assign(s.begin(), s.end());
    return K;
  };
  for (int i = 0; i < B.per_kind; ++i) {
    {  // not a mutant: one to three coordinates moved by one ulp keep the verdict (CERTIFIED)
      io::PointSet P = B.points;
      for (int u = 0, moves = 1 + rng.below(3); u < moves; ++u) {
        double& v = P.coordinates[rng.below(static_cast<int>(P.coordinates.size()))];
        v = std::nextafter(v, rng.below(2) ? INFINITY : -INFINITY);
      }
      const Verdict v = run_case(dir, B.spec, P, B.complex, B.claims).overall();
      EXPECT_EQ(v, Verdict::certified) << B.spec << ": a one-ulp move of a valid input changed the verdict";
      ++tally.variants;
      tally.variants_same += v == Verdict::certified;
    }
    {  // drop a simplex
      auto K = K0;
      auto it = K.begin();
      std::advance(it, rng.below(static_cast<int>(K.size())));
      Simplex gone = *it;
      K.erase(it);
      record("drop", run_case(dir, B.spec, B.points, complex_of(K), B.claims), "dropped " + std::to_string(gone[0]));
    }
    {  // add a simplex: a face of an existing simplex joined to a nearby point
      Simplex s = simplices[rng.below(static_cast<int>(simplices.size()))];
      int w = neighbour_of(s);
      s.erase(s.begin() + rng.below(static_cast<int>(s.size())));
      s.push_back(w);
      std::sort(s.begin(), s.end());
      if (w >= 0 && !K0.count(s)) {
        auto K = K0;
        K.insert(s);
        record("add", run_case(dir, B.spec, B.points, complex_of(K), B.claims), "added simplex");
      }
    }
    {  // replace a vertex of a simplex by a nearby point
      Simplex s = simplices[rng.below(static_cast<int>(simplices.size()))];
      int w = neighbour_of(s);
      if (w >= 0) {
        auto K = K0;
        K.erase(s);
        s[rng.below(static_cast<int>(s.size()))] = w;
        std::sort(s.begin(), s.end());
        K.insert(s);
        record("replace", run_case(dir, B.spec, B.points, complex_of(K), B.claims), "replaced a vertex");
      }
    }
    {  // swap two points (nearby half of the time)
      int a = rng.below(n);
      int b = (i % 2) ? neighbour_of(Simplex{a}) : rng.below(n);
      if (b >= 0 && b != a) {
        std::set<Simplex> relabelled;  // skip equivalent mutants (the swap is an automorphism)
        for (Simplex s : K0) {
          for (int& v : s) v = v == a ? b : v == b ? a : v;
          std::sort(s.begin(), s.end());
          relabelled.insert(s);
        }
        if (relabelled != K0) {
          io::PointSet P = B.points;
          for (int k = 0; k < P.dimension; ++k) std::swap(P.coordinates[a * P.dimension + k], P.coordinates[b * P.dimension + k]);
          record("swap", run_case(dir, B.spec, P, B.complex, B.claims), "swapped points");
        }
      }
    }
    {  // move a point onto the sphere of a star simplex, to within one ulp
      for (int tries = 0; tries < 20; ++tries) {
        const Simplex& s = simplices[rng.below(static_cast<int>(simplices.size()))];
        int p = s[rng.below(static_cast<int>(s.size()))], q = neighbour_of(s);
        io::PointSet P = B.points;
        int sign = 2;
        if (q < 0 || !move_onto_sphere(B, P, p, s, q, rng.below(P.dimension), rng.below(3) - 1, sign)) continue;
        Certificate c = run_case(dir, B.spec, P, B.complex, B.claims);
        record("ulp-onto-sphere", c, "moved a point");
        // Cross-check with the independent exact sign: inside -> wrong star; on -> tie; outside ->
        // a margin far below the claim.
        if (sign < 0) {
          EXPECT_EQ(check(c, CheckId::stars).verdict, Verdict::refuted);
        } else if (sign == 0) {
          EXPECT_GT(check(c, CheckId::power_protection).details["exact_ties"].get<long>(), 0);
        } else {
          EXPECT_EQ(check(c, CheckId::power_protection).verdict, Verdict::refuted);
        }
        tally.by_kind[sign < 0 ? "  (inside)" : sign == 0 ? "  (exactly on)" : "  (outside)"][1]++;
        break;
      }
    }
  }
}

Base make_base(const std::string& spec, const std::string& shape, double scale, const io::PointSet& P, int per_kind,
               std::uint64_t seed) {
  Audit A = audit(spec, P);
  EXPECT_TRUE(A.consistent && A.all_proven) << spec;
  TempDir dir("base");
  Base B{spec, shape, scale, P, A.complex, "", per_kind, seed};
  CertifyOptions o;
  o.skip_restricted = true;  // these tests are about Del_TM (checks 11-13: restricted_test.cpp)
  o.manifold = spec;
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  B.claims = claims_for(run_certify(o));
  Certificate base = run_case(dir, spec, P, A.complex, B.claims);
  EXPECT_EQ(base.overall(), Verdict::certified) << base.to_text(false);  // the unmutated input certifies
  return B;
}

Tally& grand_total() {
  static Tally t;
  return t;
}

void report(const Tally& t) {
  int total = 0, killed = 0;
  for (const auto& [kind, c] : t.by_kind)
    for (int k = 0; k < 3; ++k) grand_total().by_kind[kind][k] += c[k];
  grand_total().variants += t.variants;
  grand_total().variants_same += t.variants_same;
  for (const auto& [kind, c] : t.by_kind) {
    if (kind[0] == ' ') {  // the exact position of moved points, not separate mutants
      std::printf("  %-16s %d\n", kind.c_str(), c[1]);
      continue;
    }
    std::printf("  %-16s mutants %3d   refuted %3d   undecided %3d   certified %d\n", kind.c_str(), c[0] + c[1] + c[2], c[1],
                c[2], c[0]);
    total += c[0] + c[1] + c[2];
    killed += c[1];
  }
  std::printf("  total            mutants %3d   refuted %3d   undecided %3d\n", total, killed, total - killed);
  std::printf("  one-ulp variants %d, verdict kept %d\n", t.variants, t.variants_same);
}

// The grand total over the bases run in this process, printed at the end (the minima above are
// what is asserted).
class PrintTotal : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("[mutation] all bases:\n");
    Tally t = grand_total();
    grand_total() = Tally{};
    report(t);
  }
};
[[maybe_unused]] ::testing::Environment* const kTotalEnv = ::testing::AddGlobalTestEnvironment(new PrintTotal);

int mutants(const Tally& t) {
  int total = 0;
  for (const auto& [k, c] : t.by_kind)
    if (k[0] != ' ') total += c[0] + c[1] + c[2];
  return total;
}

// A spec file for the built-in sphere or Clifford torus `name` scaled by 2^k (radius 2^k), with
// the built-in's expected topology, a residual tolerance and a bounding box scaled alike.
std::string scaled_spec(const TempDir& dir, const std::string& name, int k) {
  const mpq_class s2 = k >= 0 ? mpq_class(mpz_class(1) << (2 * k)) : mpq_class(1) / mpq_class(mpz_class(1) << (-2 * k));
  const std::string r2 = "(" + s2.get_str() + ")";
  nlohmann::json j = nlohmann::json::parse(io::builtin_spec_text(name));
  std::vector<std::string> eq;
  if (name.rfind("sphere", 0) == 0) {
    std::string e;
    for (int i = 1; i <= j["ambient_dimension"].get<int>(); ++i) e += "x" + std::to_string(i) + "^2 + ";
    eq.push_back(e + "(-1)*" + r2);
  } else {  // clifford tori: products of circles
    for (int i = 1; i < j["ambient_dimension"].get<int>(); i += 2)
      eq.push_back("x" + std::to_string(i) + "^2 + x" + std::to_string(i + 1) + "^2 + (-1)*" + r2);
  }
  j["equations"] = eq;
  j["name"] = name + "-scaled";
  j.erase("reach");
  j.erase("metric");
  j.erase("parametrization");
  const mpq_class b = mpq_class(5, 4) * (k >= 0 ? mpq_class(mpz_class(1) << k) : mpq_class(1) / mpq_class(mpz_class(1) << -k));
  nlohmann::json box = nlohmann::json::array();
  for (int i = 0; i < j["ambient_dimension"].get<int>(); ++i) box.push_back({mpq_class(-b).get_str(), b.get_str()});
  j["bounding_box"] = box;
  j["residual_tolerance"] = mpq_class(s2 / 1000000000).get_str();
  const std::string path = dir.file(name + "-scaled-" + std::to_string(k) + ".json");
  write_text(path, j.dump());
  return path;
}

io::PointSet scaled_points(io::PointSet P, int k) {
  for (double& v : P.coordinates) v = std::ldexp(v, k);
  return P;
}

// At least 1,000 mutants per run across the bases: each test below asserts its own minimum (ctest
// runs every test in a process of its own, so a total kept across tests could not be asserted),
// and the minima add up to 1,000. Below DELCERT_TEST_SCALE = 1 (the sanitizer run at 0.1) each
// kind still gets at least one mutant, which is not proportional to the minima, so only a
// non-empty run is required there.
constexpr long kMinSphere2 = 330, kMinTorus2 = 190, kMinSphere3 = 140, kMinTorusOfRevolution = 160, kMinTorus3 = 35,
               kMinScaled = 150;
static_assert(kMinSphere2 + kMinTorus2 + kMinSphere3 + kMinTorusOfRevolution + kMinTorus3 + kMinScaled >= 1000);
long minimum(long m) { return test_scale() >= 1 ? m : 1; }

TEST(Mutation, SphereMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:sphere-2", "sphere", 1, fibonacci_sphere(90), scaled(70), 101), t);
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinSphere2));
}

TEST(Mutation, FlatTorusMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:clifford-torus-2", "circles", 1, torus2_lattice(8, 10), scaled(40), 202), t);
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinTorus2));
}

TEST(Mutation, ThreeSphereMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:sphere-3", "sphere", 1, spread_sphere(4, 70, 0.5, 13), scaled(30), 303), t);
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinSphere3));
}

TEST(Mutation, TorusOfRevolutionMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:torus-of-revolution", "torus-of-revolution", 1, torus_of_revolution(18, 8), scaled(35), 404), t);
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinTorusOfRevolution));
}

TEST(Mutation, FlatThreeTorusMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:clifford-torus-3", "circles", 1, torus3_bcc(4), scaled(8), 505), t);
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinTorus3));
}

// Huge and tiny magnitudes: the same inputs scaled by 2^k (points exactly, spec and claims
// accordingly) still certify, and their mutants never do.
TEST(Mutation, ScaledInputMutantsAreNeverCertified) {
  TempDir dir("scaled-specs");
  Tally t;
  for (int k : {-600, 450}) {
    const std::string spec = scaled_spec(dir, "sphere-2", k);
    run_mutants(make_base(spec, "sphere", std::ldexp(1.0, k), scaled_points(fibonacci_sphere(90), k), scaled(12),
                          606 + static_cast<std::uint64_t>(k + 1000)), t);
  }
  {
    const int k = -300;
    const std::string spec = scaled_spec(dir, "clifford-torus-2", k);
    run_mutants(make_base(spec, "circles", std::ldexp(1.0, k), scaled_points(torus2_lattice(8, 10), k), scaled(12), 707), t);
  }
  report(t);
  EXPECT_GE(mutants(t), minimum(kMinScaled));
}

// Mutants of the certificate itself (issue 39): a certified bound under an UNDECIDED decision that
// the check did not prove whatever its verdict. Real certificates (an audit that is UNDECIDED, the
// tesseract's 16 vertices on S^3, and one that is CERTIFIED, 90 points on S^2) are mutated by
//  * "undecide": a check that prints certified bounds is made UNDECIDED (or REPORT with
//    details.decision UNDECIDED) with its bounds left in place;
//  * "perturb": a certified bound printed by an UNDECIDED check is moved by 1 to 2^20 ulps;
//  * "insert": a certified_upper_bound or certified_lower_bound key is added to an UNDECIDED entry;
// and the consistency guard must catch every one (Certificate::self_check_failures non-empty). The
// unmutated certificates must pass it.
using Pointer = std::vector<std::string>;  // the path of a certified key inside the entry's JSON

void certified_paths(const nlohmann::json& j, Pointer at, std::vector<Pointer>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      Pointer next = at;
      next.push_back(k);
      if (k == "certified_upper_bound" || k == "certified_lower_bound") out.push_back(next);
      certified_paths(v, next, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) certified_paths(j[i], [&] { Pointer n = at; n.push_back(std::to_string(i)); return n; }(), out);
  }
}

nlohmann::json& at_path(CheckEntry& e, const Pointer& p) {
  nlohmann::json* j = p[0] == "margin" ? &e.margin : p[0] == "details" ? &e.details : &e.witnesses;
  for (std::size_t i = 1; i < p.size(); ++i) j = j->is_array() ? &(*j)[std::stoul(p[i])] : &(*j)[p[i]];
  return *j;
}

std::vector<Pointer> certified_in(const CheckEntry& e) {
  std::vector<Pointer> out;
  certified_paths(e.margin, {"margin"}, out);
  certified_paths(e.details, {"details"}, out);
  certified_paths(e.witnesses, {"witnesses"}, out);
  return out;
}

bool registered(const CheckEntry& e, const Pointer& p) {
  std::string s;
  for (const auto& k : p) s += "/" + k;
  for (const auto& b : e.proven_whatever_the_verdict)
    if (b.pointer == s) return true;
  return false;
}

// A sample with one component emptied (issue 39.1): M is two unit spheres 5 apart
// (fixtures/soundness/components/two-spheres.json), the base samples both (a Fibonacci sample of each,
// randomly rotated) and certifies covering 1/4 (check 11 CERTIFIED, so the test can fail); the mutant
// keeps one sphere's points only, and checks 11 and 12 (whose completeness rests on 11) must not be
// CERTIFIED. The spec's expected b0 = 1 is wrong for M: it must play no part (check 8 only).
TEST(Mutation, EmptiedComponentMutantsAreNeverCertified) {
  TempDir dir("mut-components");
  const std::string claims = dir.file("claims.json");
  write_text(claims, R"({"format": "delcert-claims v2", "covering": "1/4"})");
  auto certify = [&](const io::PointSet& P) {
    CertifyOptions o;
    o.manifold = fixture("soundness/components/two-spheres.json");
    o.points = dir.file("points.txt");
    o.claims = claims;
    io::write_points(o.points, P);
    return run_certify(o);
  };
  int mutants = 0;
  const int seeds = test_scale() >= 1 ? 2 : 1;
  for (int seed = 0; seed < seeds; ++seed) {
    Rng rng(700 + static_cast<std::uint64_t>(seed));
    // A random rotation (a unit quaternion) per sphere.
    auto rotated = [&](double dz) {
      double a[4], n = 0;
      for (double& v : a) v = rng.uniform() - 0.5, n += v * v;
      for (double& v : a) v /= std::sqrt(n);
      const auto [w, x, y, z] = a;
      const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                              {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                              {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
      io::PointSet S = fibonacci_sphere(300), out;
      out.dimension = 3;
      for (std::size_t i = 0; i < S.size(); ++i) {
        std::vector<double> p(3);
        for (int r = 0; r < 3; ++r) p[r] = R[r][0] * S.point(i)[0] + R[r][1] * S.point(i)[1] + R[r][2] * S.point(i)[2];
        p[2] += dz;
        out.push_back(p);
      }
      return out;
    };
    const io::PointSet first = rotated(0), second = rotated(5);
    io::PointSet both = first;
    both.coordinates.insert(both.coordinates.end(), second.coordinates.begin(), second.coordinates.end());
    const Certificate base = certify(both);
    ASSERT_EQ(check(base, CheckId::covering).verdict, Verdict::certified) << check(base, CheckId::covering).summary;
    for (const io::PointSet* kept : {&first, &second}) {
      const Certificate c = certify(*kept);
      ++mutants;
      EXPECT_EQ(check(c, CheckId::covering).verdict, Verdict::refuted) << check(c, CheckId::covering).summary;
      EXPECT_NE(check(c, CheckId::restricted_delaunay).decision(), Verdict::certified);
      EXPECT_NE(c.overall(), Verdict::certified);
    }
  }
  std::printf("[ mutants  ] component emptied: %d, none certified\n", mutants);
  EXPECT_GE(mutants, 2);
}

TEST(Mutation, CertifiedBoundsUnderUndecidedAreCaughtByTheGuard) {
  std::vector<Certificate> bases;
  {
    CertifyOptions o;  // UNDECIDED: check 11 (exact ties at the centres of the tesseract's cells)
    o.manifold = "builtin:sphere-3";
    o.points = fixture("soundness/bounds/tesseract-s3.txt");
    bases.push_back(run_certify(o));
    TempDir dir("mut-guard");
    o.manifold = "builtin:sphere-2";  // CERTIFIED
    o.points = dir.file("points.txt");
    io::write_points(o.points, fibonacci_sphere(90));
    bases.push_back(run_certify(o));
  }
  ASSERT_EQ(check(bases[0], CheckId::covering).verdict, Verdict::undecided);
  ASSERT_EQ(bases[1].overall(), Verdict::certified);
  Rng rng(909);
  std::map<std::string, int> caught, total;
  auto record = [&](const std::string& kind, const Certificate& C, const std::string& what) {
    ++total[kind];
    const bool found = !C.self_check_failures().empty();
    caught[kind] += found;
    EXPECT_TRUE(found) << kind << " mutant not caught: " << what;
  };
  for (const Certificate& base : bases) {
    EXPECT_TRUE(base.self_check_failures().empty());
    for (int round = 0; round < scaled(60); ++round)
      for (std::size_t i = 0; i < base.checks.size(); ++i) {
        const CheckEntry& e = base.checks[i];
        const auto keys = certified_in(e);
        const bool undecided = e.decision() == Verdict::undecided;
        if (!undecided && !keys.empty() && !std::all_of(keys.begin(), keys.end(), [&](const Pointer& p) { return registered(e, p); })) {
          Certificate C = base;
          if (rng.below(2)) C.checks[i].verdict = Verdict::undecided;
          else C.checks[i].verdict = Verdict::report, C.checks[i].details["decision"] = "UNDECIDED";
          record("undecide", C, e.name());
        }
        if (undecided && !keys.empty()) {
          Certificate C = base;
          nlohmann::json& v = at_path(C.checks[i], keys[rng.below(static_cast<int>(keys.size()))]);
          double x = std::stod(v.get<std::string>());
          const int ulps = 1 + rng.below(1 << 20);
          const bool up = rng.below(2);
          for (int u = 0; u < ulps && std::isfinite(x); u = u < 64 ? u + 1 : u * 2) x = std::nextafter(x, up ? INFINITY : -INFINITY);
          v = num(x);
          record("perturb", C, e.name());
        }
        if (undecided) {
          Certificate C = base;
          nlohmann::json& m = C.checks[i].margin;
          if (!m.is_object()) m = nlohmann::json::object();
          const std::string key = rng.below(2) ? "certified_upper_bound" : "certified_lower_bound";
          const std::string value = num(std::ldexp(1.0 + rng.below(1000) / 1000.0, rng.below(8) - 4));
          std::string beside = "inserted";  // or beside the entry's own keys, in an object of its margin
          for (const auto& [k, v] : m.items())
            if (v.is_object() && !v.contains(key) && rng.below(2)) beside = k;
          m[beside][key] = value;
          record("insert", C, e.name() + std::string(" at /margin/") + beside);
        }
      }
  }
  for (const auto& [kind, n] : total) std::printf("  guard mutants %-9s %4d   caught %4d\n", kind.c_str(), n, caught[kind]);
  EXPECT_GE(total["undecide"], 1);
  EXPECT_GE(total["perturb"], 1);
  EXPECT_GE(total["insert"], 1);
}

// POINTS PUSHED OFF M (issue 39). A mesher's vertices lie only near M, and Del_RM(P) is defined for
// any P: a complex claimed restricted must never be CERTIFIED unless it is Del_RM of the points as
// they are, and never REFUTED when it is. The truth comes from an independent floating-point oracle
// for the unit sphere (below), and a mutant is used only where the oracle decides with a margin.
// Base: the Fibonacci sphere and its Del_RM (= Del_TM, from the stars). Kinds: one point or three
// pushed radially (along the normal) by a factor in [0.7, 1.3] (Del_RM usually changes: a mutant
// when it does, a variant that must not be REFUTED when it does not), and every point scaled by
// one factor in [0.7, 1.4] (the cells of a radial sample are cones from the centre: Del_RM stays,
// so never REFUTED: the reviewed false REFUTED was the mesh scaled by 1.3).
//
// The oracle: x on the unit sphere is nearest to exactly a, b, c in P when it lies on the line of
// points equidistant from them (through their circumcentre, along the normal of their plane) and
// every other point is farther. Every triple, both intersections, every other point: the set of
// triangles of Del_RM(P). `decided` is false when some margin is within 1e-9 of a tie.
struct SphereOracle {
  std::set<Simplex> triangles;
  bool decided = true;
};
SphereOracle sphere_del_rm(const io::PointSet& P) {
  SphereOracle o;
  const int n = static_cast<int>(P.size());
  auto pt = [&](int i) { return std::array<double, 3>{P.point(i)[0], P.point(i)[1], P.point(i)[2]}; };
  auto sub = [](auto a, auto b) { return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot = [](auto a, auto b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto cross = [](auto a, auto b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c) {
        const auto A = pt(a), u = sub(pt(b), A), v = sub(pt(c), A), w = cross(u, v);
        const double w2 = dot(w, w);
        if (w2 < 1e-20) continue;
        // circumcentre A + (|u|^2 (v x w) + |v|^2 (w x u)) / (2 |w|^2)
        const auto p1 = cross(v, w), p2 = cross(w, u);
        std::array<double, 3> C;
        for (int k = 0; k < 3; ++k) C[k] = A[k] + (dot(u, u) * p1[k] + dot(v, v) * p2[k]) / (2 * w2);
        // |C + t w|^2 = 1
        const double qa = w2, qb = 2 * dot(C, w), qc = dot(C, C) - 1, disc = qb * qb - 4 * qa * qc;
        if (disc < 0) continue;
        for (double sgn : {-1.0, 1.0}) {
          const double t = (-qb + sgn * std::sqrt(disc)) / (2 * qa);
          std::array<double, 3> x;
          for (int k = 0; k < 3; ++k) x[k] = C[k] + t * w[k];
          const double r2 = dot(sub(x, A), sub(x, A));
          double margin = INFINITY;
          for (int q = 0; q < n && margin > -1e-9; ++q)
            if (q != a && q != b && q != c) margin = std::min(margin, dot(sub(x, pt(q)), sub(x, pt(q))) - r2);
          if (std::abs(margin) <= 1e-9) o.decided = false;
          if (margin > 1e-9) o.triangles.insert({a, b, c});
        }
      }
  return o;
}

TEST(Mutation, PointsPushedOffMAreNeverCertifiedWrongly) {
  TempDir dir("mut-off-M");
  const io::PointSet P0 = fibonacci_sphere(90);
  const SphereOracle base = sphere_del_rm(P0);
  ASSERT_TRUE(base.decided);
  io::Complex K;
  K.num_vertices = static_cast<int>(P0.size());
  K.simplices.assign(base.triangles.begin(), base.triangles.end());
  ASSERT_EQ(as_set(K), as_set(audit("builtin:sphere-2", P0).complex));  // the oracle agrees with the stars
  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = dir.file("points.txt");
  o.complex = dir.file("complex.txt");
  o.kind = ComplexKind::restricted;
  io::write_complex(o.complex, K);
  Rng rng(909);
  Tally t;
  int kept = 0, kept_not_refuted = 0;
  auto factor = [&](double lo, double hi) { return lo + (hi - lo) * rng.below(1000001) / 1e6; };
  auto try_mutant = [&](const std::string& kind, const io::PointSet& P) {
    const SphereOracle truth = sphere_del_rm(P);
    if (!truth.decided) return;
    io::write_points(o.points, P);
    const Certificate c = run_certify(o);
    const CheckEntry& rd = check(c, CheckId::restricted_delaunay);
    if (truth.triangles != base.triangles) {  // a mutant: the complex is not Del_RM(P)
      EXPECT_NE(c.overall(), Verdict::certified) << kind << ": CERTIFIED, but the complex is not Del_RM of the moved points";
      t.by_kind[kind][c.overall() == Verdict::certified ? 0 : c.overall() == Verdict::refuted ? 1 : 2]++;
    } else {  // the complex is still Del_RM(P): a REFUTED of check 12 would be false (unless "not pure")
      ++kept;
      const bool refuted = rd.verdict == Verdict::refuted && rd.details["pure"] != false;
      EXPECT_FALSE(refuted) << kind << ": REFUTED, but the complex is Del_RM of the moved points: " << rd.summary;
      kept_not_refuted += !refuted;
    }
  };
  for (int i = 0, rounds = std::max(1, static_cast<int>(scaled(12))); i < rounds; ++i) {
    for (int moved : {1, 3}) {
      io::PointSet P = P0;
      for (int k = 0; k < moved; ++k) {
        const int p = rng.below(static_cast<int>(P.size()));
        double f = factor(0.7, 1.3);
        if (std::abs(f - 1) < 0.02) f = 1.1;
        for (int v = 0; v < 3; ++v) P.coordinates[p * 3 + v] *= f;
      }
      try_mutant(moved == 1 ? "off-M-one" : "off-M-three", P);
    }
    io::PointSet P = P0;
    const double f = factor(0.7, 1.4);
    for (double& v : P.coordinates) v *= f;
    try_mutant("off-M-all-scaled", P);
  }
  report(t);
  std::printf("  off-M variants still Del_RM %d, not refuted %d\n", kept, kept_not_refuted);
  EXPECT_GE(mutants(t), test_scale() >= 1 ? 10 : 1);
  EXPECT_GE(kept, test_scale() >= 1 ? 10 : 1);  // the all-scaled ones at least
}

}  // namespace
}  // namespace delcert::certify::test
