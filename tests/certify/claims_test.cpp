// The verdict answers what was claimed (issue 43; docs/certificate.md, "What is claimed"): in every
// mode a check that is not claimed may fail without turning the verdict (it is reported, its decision
// in details.decision), and a claimed check that fails refutes it. One input shows all four modes:
// fixtures/certify/sphere-tm-inconsistent.off (fixtures/certify/README.md), 58 points within 1e-4
// of S^2 whose triangles are their Del_RM(P), while their Del_TM(P) is inconsistent and their Del_M(P)
// differs from Del_RM(P) in 4 triangles. Its points count as on M with --residual-tolerance 1/1000
// (so that Del_TM(P) is computed), as a mesher's vertices would with a raised tolerance.
#include <algorithm>
#include <functional>
#include <set>

#include "support.hpp"

namespace delcert::certify::test {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

const std::string& mesh() {
  static const std::string path = fixture("certify/sphere-tm-inconsistent.off");
  return path;
}

struct MeshRun {
  TempDir dir{"claims"};
  CertifyOptions o;
  MeshRun() {
    o.manifold = "builtin:sphere-2";
    o.points = mesh();
    o.threads = 2;
    o.residual_tolerance = "1/1000";
  }
  // The mesh's triangles, changed by `edit`, as the complex (written as an OFF: claimed restricted by default).
  Certificate with_complex(const std::function<void(io::Complex&)>& edit = {}) {
    io::ComplexFile f = io::read_complex(mesh());
    if (edit) edit(f.complex);
    o.points = o.complex = dir.file("mesh.off");
    io::write_off(o.complex, *f.embedded_points, f.complex);
    return run_certify(o);
  }
  Certificate with_claims(const std::string& claims_json) {
    o.claims = dir.file("claims.json");
    write_text(o.claims, claims_json);
    return with_complex();
  }
};

void expect_reported(const Certificate& c, CheckId id, const std::string& decision) {
  const CheckEntry& e = check(c, id);
  EXPECT_EQ(e.verdict, Verdict::report) << check_name(id) << ": " << e.summary;
  EXPECT_FALSE(e.claimed) << check_name(id);
  EXPECT_EQ(e.details.value("decision", ""), decision) << check_name(id) << ": " << e.summary;
}

void expect_claimed(const Certificate& c, CheckId id, Verdict v) {
  const CheckEntry& e = check(c, id);
  EXPECT_EQ(e.verdict, v) << check_name(id) << ": " << e.summary;
  EXPECT_TRUE(e.claimed) << check_name(id);
  EXPECT_FALSE(e.details.contains("decision")) << check_name(id);
}

TEST(ClaimedChecks, WhichChecksAreClaimsInEachMode) {
  io::Claims none, all;
  all.sparsity = all.gamma0 = all.power_protection = all.star_radius = all.covering = mpq_class(1, 10);
  all.secure = true;
  std::set<int> expect_all;
  for (int k = 1; k <= 15; ++k)
    if (k != 9) expect_all.insert(k);
  auto claimed = [](Mode mode, const io::Claims& claims) {
    std::set<int> out;
    for (int k = 1; k <= 15; ++k)
      if (is_claimed(static_cast<CheckId>(k), mode, claims)) out.insert(k);
    return out;
  };
  for (Mode mode : {Mode::audit, Mode::tangential}) {
    EXPECT_EQ(claimed(mode, all), expect_all);
    std::set<int> without_secure = expect_all;
    without_secure.erase(7);
    EXPECT_EQ(claimed(mode, none), without_secure);
  }
  EXPECT_EQ(claimed(Mode::restricted, none), (std::set<int>{1, 12}));
  EXPECT_EQ(claimed(Mode::intrinsic, none), (std::set<int>{1, 14}));
  EXPECT_EQ(claimed(Mode::restricted, all), (std::set<int>{1, 2, 5, 6, 7, 10, 11, 12}));
  EXPECT_EQ(claimed(Mode::intrinsic, all), (std::set<int>{1, 2, 5, 6, 7, 10, 11, 14}));
  io::Claims per_point;  // the per-point forms claim checks 10 and 11 as well
  per_point.star_radius_per_point_file = per_point.covering_per_point_file = "eps.txt";
  EXPECT_EQ(claimed(Mode::restricted, per_point), (std::set<int>{1, 10, 11, 12}));
}

// The issue's case: a mesh that is exactly Del_RM(P) gets CERTIFIED under --kind restricted whatever
// Del_TM(P) looks like, and the certificate still says what Del_TM(P) is.
TEST(ClaimedChecks, ARestrictedMeshIsCertifiedWhateverItsTangentialComplexIs) {
  MeshRun r;
  const Certificate c = r.with_complex();
  ASSERT_EQ(c.parameters["kind"], "restricted");
  EXPECT_EQ(check(c, CheckId::input_sanity).details["off_manifold_points"], 0);  // Del_TM is computed
  expect_claimed(c, CheckId::input_sanity, Verdict::certified);
  expect_claimed(c, CheckId::restricted_delaunay, Verdict::certified);
  EXPECT_EQ(check(c, CheckId::restricted_delaunay).details["missing_simplices"], 0);
  EXPECT_EQ(check(c, CheckId::restricted_delaunay).details["extra_simplices"], 0);
  // The tangential findings, reported with their witnesses.
  expect_reported(c, CheckId::consistency, "REFUTED");
  EXPECT_FALSE(check(c, CheckId::consistency).witnesses.empty());
  expect_reported(c, CheckId::tangential_equals_restricted, "REFUTED");
  expect_reported(c, CheckId::covering, "CERTIFIED");
  expect_reported(c, CheckId::intrinsic_delaunay, "CERTIFIED");
  for (CheckId id : {CheckId::stars, CheckId::power_protection, CheckId::topology, CheckId::restricted_equals_intrinsic})
    EXPECT_FALSE(check(c, id).claimed) << check_name(id);
  EXPECT_TRUE(check(c, CheckId::restricted_delaunay).details.contains("assumptions"));
  EXPECT_EQ(c.overall(), Verdict::certified) << c.to_text(false);
  const nlohmann::json j = c.to_json(false);
  EXPECT_EQ(j["verdict"], "CERTIFIED");
  EXPECT_EQ(j["checks"][3]["claimed"], false);
  EXPECT_EQ(j["checks"][11]["claimed"], true);
}

// --kind restricted: a claimed check that fails refutes, whether the complex or the claims file
// makes the claim; every mutant of the mesh is REFUTED by check 12.
TEST(ClaimedChecks, ARestrictedClaimThatFailsIsRefuted) {
  MeshRun r;
  const Certificate dropped = r.with_complex([](io::Complex& K) { K.simplices.erase(K.simplices.begin() + 5); });
  expect_claimed(dropped, CheckId::restricted_delaunay, Verdict::refuted);
  EXPECT_EQ(dropped.overall(), Verdict::refuted);
  const Certificate added = r.with_complex([](io::Complex& K) {
    const std::set<std::vector<int>> in(K.simplices.begin(), K.simplices.end());
    std::vector<int> t{0, 1, 2};
    while (in.count(t)) ++t[2];
    K.simplices.push_back(t);
  });
  expect_claimed(added, CheckId::restricted_delaunay, Verdict::refuted);
  EXPECT_EQ(added.overall(), Verdict::refuted);
  const Certificate replaced = r.with_complex([](io::Complex& K) { K.simplices[0][2] = (K.simplices[0][2] + 11) % 58; });
  EXPECT_EQ(replaced.overall(), Verdict::refuted);

  // The claims file's claims count in restricted mode: a false sparsity claim, a false covering claim.
  const Certificate sparse = r.with_claims(R"({"format": "delcert-claims v2", "sparsity": "1"})");
  expect_claimed(sparse, CheckId::sparsity, Verdict::refuted);
  expect_claimed(sparse, CheckId::restricted_delaunay, Verdict::certified);
  EXPECT_EQ(sparse.overall(), Verdict::refuted);
  const Certificate covering = r.with_claims(R"({"format": "delcert-claims v2", "covering": "1/100"})");
  expect_claimed(covering, CheckId::covering, Verdict::refuted);
  EXPECT_EQ(covering.overall(), Verdict::refuted);
  // A power_protection claim is about Del_TM's stars: claimed, and decided, in restricted mode too.
  const Certificate protection = r.with_claims(R"({"format": "delcert-claims v2", "power_protection": "0"})");
  EXPECT_TRUE(check(protection, CheckId::power_protection).claimed);
}

// --kind intrinsic: check 14 alone decides (checks 4, 12, 13 and 15 are reported). The mesh is not
// Del_M(P): REFUTED. Del_M(P), read off check 15's witnesses (4 triangles each way), is CERTIFIED
// although Del_TM(P) is inconsistent and Del_RM(P) differs from it.
TEST(ClaimedChecks, AnIntrinsicClaimIsDecidedByCheck14Alone) {
  MeshRun r;
  const Certificate restricted = r.with_complex();
  const CheckEntry& rm_m = check(restricted, CheckId::restricted_equals_intrinsic);
  ASSERT_EQ(rm_m.details["decision"], "REFUTED");
  std::set<std::vector<int>> only_rm, only_m;
  for (const auto& w : rm_m.witnesses) {
    std::vector<int> t = w["simplex"].get<std::vector<int>>();
    std::sort(t.begin(), t.end());
    (w["not_in"] == "Del_M(P)" ? only_rm : only_m).insert(t);
  }
  ASSERT_EQ(only_rm.size(), 4u);
  ASSERT_EQ(only_m.size(), 4u);

  r.o.kind = ComplexKind::intrinsic;
  const Certificate not_del_m = r.with_complex();
  expect_claimed(not_del_m, CheckId::intrinsic_delaunay, Verdict::refuted);
  expect_reported(not_del_m, CheckId::restricted_delaunay, "CERTIFIED");
  EXPECT_EQ(not_del_m.overall(), Verdict::refuted);

  auto to_del_m = [&](io::Complex& K) {
    std::erase_if(K.simplices, [&](std::vector<int> t) { return std::sort(t.begin(), t.end()), only_rm.count(t) > 0; });
    K.simplices.insert(K.simplices.end(), only_m.begin(), only_m.end());
  };
  const Certificate c = r.with_complex(to_del_m);
  expect_claimed(c, CheckId::intrinsic_delaunay, Verdict::certified);
  expect_reported(c, CheckId::restricted_delaunay, "CERTIFIED");
  expect_reported(c, CheckId::consistency, "REFUTED");
  expect_reported(c, CheckId::tangential_equals_restricted, "REFUTED");
  expect_reported(c, CheckId::restricted_equals_intrinsic, "REFUTED");
  EXPECT_EQ(c.overall(), Verdict::certified) << c.to_text(false);
  // The same complex claimed restricted: check 12 refutes it.
  r.o.kind = ComplexKind::restricted;
  EXPECT_EQ(r.with_complex(to_del_m).overall(), Verdict::refuted);
}

// --kind tangential and audit keep the refiner's promise: the same points, given as Del_TM (or
// audited), are REFUTED by the inconsistency. A check that is not claimed there (check 7 without
// "secure": true) is reported and does not turn a CERTIFIED verdict.
TEST(ClaimedChecks, TangentialAndAuditModesKeepTheRefinersPromise) {
  MeshRun r;
  r.o.kind = ComplexKind::tangential;
  const Certificate tangential = r.with_complex();
  ASSERT_EQ(tangential.parameters["kind"], "tangential");
  expect_claimed(tangential, CheckId::consistency, Verdict::refuted);
  expect_claimed(tangential, CheckId::restricted_delaunay, Verdict::certified);
  EXPECT_EQ(tangential.overall(), Verdict::refuted);

  CertifyOptions a;
  a.manifold = "builtin:sphere-2", a.points = mesh(), a.threads = 2, a.residual_tolerance = "1/1000";
  const Certificate audit_cert = run_certify(a);
  ASSERT_EQ(audit_cert.parameters["kind"], "audit");
  expect_claimed(audit_cert, CheckId::consistency, Verdict::refuted);
  expect_claimed(audit_cert, CheckId::tangential_equals_restricted, Verdict::refuted);
  EXPECT_EQ(audit_cert.overall(), Verdict::refuted);

  // A valid Del_TM (the Fibonacci sphere's), given as tangential and audited: check 7, not claimed,
  // decided REFUTED (secure_test.cpp), is reported; the verdict stands on the claims.
  const io::PointSet P = fibonacci_sphere(200);
  TempDir dir("claims-tangential");
  CertifyOptions t;
  t.manifold = "builtin:sphere-2", t.threads = 2;
  t.points = dir.file("points.txt"), t.complex = dir.file("complex.txt");
  io::write_points(t.points, P);
  io::write_complex(t.complex, audit("builtin:sphere-2", P).complex);
  for (const bool given : {true, false}) {
    CertifyOptions u = t;
    if (!given) u.complex.clear();
    const Certificate c = run_certify(u);
    expect_reported(c, CheckId::secure_simplices, "REFUTED");
    expect_claimed(c, CheckId::consistency, Verdict::certified);
    expect_claimed(c, CheckId::tangential_equals_restricted, Verdict::certified);
    EXPECT_EQ(c.overall(), Verdict::certified) << given;
  }
}

// The command line: exit 0 for the mesh, every check line says whether it is a claim, the line
// before the verdict names the claims that decided it; a dropped triangle exits 1 and names check 12.
TEST(ClaimedChecks, TheCommandLineNamesTheClaimsThatDecided) {
  TempDir dir("claims-cli");
  const std::string out = dir.file("cert.json");
  const std::string base = binary() + " --manifold builtin:sphere-2 --residual-tolerance 1/1000 --threads 2";
  RunResult r = run(base + " --points " + q(mesh()) + " --complex " + q(mesh()) + " --out " + q(out),
                    dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(last_line(r.out), "verdict: CERTIFIED");
  const std::string text = r.out;
  auto line_of = [&](const std::string& start) {
    const auto p = text.find(start);
    return p == std::string::npos ? std::string() : text.substr(p, text.find('\n', p) - p);
  };
  const std::string consistency = line_of("check 4 "), restricted = line_of("check 12 ");
  EXPECT_NE(consistency.find("REPORT"), std::string::npos) << consistency;
  EXPECT_NE(consistency.find("[not claimed]"), std::string::npos) << consistency;
  EXPECT_NE(consistency.find("(REFUTED)"), std::string::npos) << consistency;
  EXPECT_NE(restricted.find("CERTIFIED  [claimed]"), std::string::npos) << restricted;
  EXPECT_EQ(line_of("decided by the claims:"),
            "decided by the claims: check 1 input_sanity, check 12 restricted_delaunay (the complex is Del_RM(P))");
  const nlohmann::json j = nlohmann::json::parse(read_text(out));
  EXPECT_EQ(j["verdict"], "CERTIFIED");
  for (const auto& c : j["checks"])
    EXPECT_EQ(c["claimed"], c["id"] == 1 || c["id"] == 12) << c["name"];

  io::ComplexFile f = io::read_complex(mesh());
  f.complex.simplices.erase(f.complex.simplices.begin() + 3);
  const std::string dropped = dir.file("dropped.off");
  io::write_off(dropped, *f.embedded_points, f.complex);
  r = run(base + " --points " + q(dropped) + " --complex " + q(dropped), dir);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(last_line(r.out), "verdict: REFUTED");
  EXPECT_NE(r.out.find("decided by the claims: REFUTED check 12 restricted_delaunay (the complex is Del_RM(P)); "
                       "CERTIFIED check 1 input_sanity\n"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace delcert::certify::test
