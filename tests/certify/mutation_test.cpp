// Mutation suite (soundness): valid certified inputs are mutated in seeded, random ways - drop a
// simplex, add a simplex, replace a vertex, swap two points, move a point onto a Delaunay sphere
// to within one ulp - and every mutant must come back REFUTED or UNDECIDED, never CERTIFIED.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "exact/tangent_predicates.hpp"
#include "support.hpp"

namespace delcert::certify::test {
namespace {

struct Base {
  std::string spec;
  io::PointSet points;
  io::Complex complex;
  std::string claims;
  int per_kind;
  std::uint64_t seed;
};

// Claims slightly weaker than the measured values (as a producer would state them).
std::string claims_for(const Certificate& c) {
  auto D = [](const nlohmann::json& s) { return std::stod(s.get<std::string>()); };
  double r2 = D(check(c, 10).margin["max_radius_squared"]["certified_upper_bound"]);
  double d = D(check(c, 2).margin["min_distance"]["certified_lower_bound"]);
  double prot = D(check(c, 6).margin["min_power_margin"]["certified_lower_bound"]);
  char buf[512];
  std::snprintf(buf, sizeof buf, R"({"format": "delcert-claims v1", "eps": "%.17g", "sparsity": "%.17g", "power_protection": "%.17g"})",
                std::sqrt(r2) * 1.01, d * 0.99, prot * 0.5);
  return buf;
}

Certificate run_case(const TempDir& dir, const std::string& spec, const io::PointSet& P, const io::Complex& K,
                     const std::string& claims) {
  CertifyOptions o;
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

// Nearest point to M along the closed-form projection of the built-in (sphere, flat torus).
void project(const std::string& spec, std::vector<double>& x) {
  if (spec.find("sphere") != std::string::npos) {
    double s = 0;
    for (double v : x) s += v * v;
    for (double& v : x) v /= std::sqrt(s);
  } else {  // product of unit circles in coordinate pairs
    for (std::size_t k = 0; k + 1 < x.size(); k += 2) {
      double s = std::hypot(x[k], x[k + 1]);
      x[k] /= s, x[k + 1] /= s;
    }
  }
}

// Moves point q of P onto the sphere of the cell s (centred on T_p) along M, to within rounding,
// then by `ulps` ulps in coordinate `coord`. False when no such position was found. `sign` is the
// exact sign of |c - q|^2 - R^2 after the move (computed here independently of the certifier).
bool move_onto_sphere(const std::string& spec_source, io::PointSet& P, int p, const Simplex& s, int q, int coord, int ulps,
                      int& sign) {
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
    project(spec_source, x);
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
        if (q < 0 || !move_onto_sphere(B.spec, P, p, s, q, rng.below(P.dimension), rng.below(3) - 1, sign)) continue;
        Certificate c = run_case(dir, B.spec, P, B.complex, B.claims);
        record("ulp-onto-sphere", c, "moved a point");
        // Cross-check with the independent exact sign: inside -> wrong star; on -> tie; outside ->
        // a margin far below the claim.
        if (sign < 0) {
          EXPECT_EQ(check(c, 3).verdict, Verdict::refuted);
        } else if (sign == 0) {
          EXPECT_GT(check(c, 6).details["exact_ties"].get<long>(), 0);
        } else {
          EXPECT_EQ(check(c, 6).verdict, Verdict::refuted);
        }
        tally.by_kind[sign < 0 ? "  (inside)" : sign == 0 ? "  (exactly on)" : "  (outside)"][1]++;
        break;
      }
    }
  }
}

// The number of mutants per kind, scaled by DELCERT_TEST_SCALE (scripts/sanitize.sh runs the
// suite at 0.1: instrumented code is several times slower); at least one of each kind.
int scaled(int per_kind) {
  const char* s = std::getenv("DELCERT_TEST_SCALE");
  double f = s ? std::strtod(s, nullptr) : 1.0;
  if (!(f > 0 && f <= 1e3)) f = 1.0;
  return std::max(1, static_cast<int>(std::lround(per_kind * f)));
}

Base make_base(const std::string& spec, const io::PointSet& P, int per_kind, std::uint64_t seed) {
  per_kind = scaled(per_kind);
  Audit A = audit(spec, P);
  EXPECT_TRUE(A.consistent && A.all_proven) << spec;
  TempDir dir("base");
  Base B{spec, P, A.complex, "", per_kind, seed};
  CertifyOptions o;
  o.manifold = spec;
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  B.claims = claims_for(run_certify(o));
  Certificate base = run_case(dir, spec, P, A.complex, B.claims);
  EXPECT_EQ(base.overall(), Verdict::certified) << base.to_text(false);  // the unmutated input certifies
  return B;
}

void report(const Tally& t) {
  int total = 0, killed = 0;
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
  std::printf("  total            mutants %3d   refuted %3d\n", total, killed);
}

TEST(Mutation, SphereMutantsAreNeverCertified) {
  Tally t;
  Base B = make_base("builtin:sphere-2", fibonacci_sphere(90), 30, 101);
  run_mutants(B, t);
  report(t);
  int total = 0;
  for (const auto& [k, c] : t.by_kind) total += c[0] + c[1] + c[2];
  // At full size 120 of the up to 150 mutants apply; scaled down, at least every drop does.
  EXPECT_GE(total, B.per_kind < 30 ? B.per_kind : 120);
}

TEST(Mutation, FlatTorusMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:clifford-torus-2", torus2_lattice(8, 10), 20, 202), t);
  report(t);
}

TEST(Mutation, ThreeSphereMutantsAreNeverCertified) {
  Tally t;
  run_mutants(make_base("builtin:sphere-3", spread_sphere(4, 70, 0.5, 13), 10, 303), t);
  report(t);
}

}  // namespace
}  // namespace delcert::certify::test
