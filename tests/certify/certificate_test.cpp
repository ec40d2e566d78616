// The internal consistency guard (certify/certificate.hpp): a CERTIFIED check whose printed
// certified bound contradicts what the verdict requires makes the whole run an internal error;
// and on real inputs with claims as tight as rationals allow, the guard never trips.
#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::certify::test {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

TEST(ConsistencyGuard, CertifiedCheckWithContradictingMarginFails) {
  Certificate C;
  CheckEntry e(CheckId::power_protection);
  e.require_at_least("min_power_margin", -4.32, 0);  // the false CERTIFIED of the overflow case
  C.checks.push_back(e);
  const auto failures = C.self_check_failures();
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_NE(failures[0].find("min_power_margin -4.32 is below 0"), std::string::npos) << failures[0];
  EXPECT_THROW(enforce_self_consistency(C), SelfCheckFailure);
}

TEST(ConsistencyGuard, ComparesWithTheEnclosureOfTheExactRequirement) {
  CheckEntry e(CheckId::power_protection);
  e.verdict = Verdict::certified;
  // 1/3 is not a double: a certified lower bound equal to the double just below 1/3 meets
  // "at least 1/3" as far as doubles can show, one ulp lower does not.
  const double below = exact::enclose(mpq_class(1, 3)).lo;
  e.require_at_least("x", below, mpq_class(1, 3));
  e.require_at_least("y", std::nextafter(below, 0.0), mpq_class(1, 3));
  e.require_at_most("z", exact::enclose(mpq_class(1, 3)).hi, mpq_class(1, 3));
  e.require_at_most("w", 1.0, mpq_class(1, 3));
  e.require_at_least("nan", std::nan(""), mpq_class(0));
  Certificate C;
  C.checks.push_back(e);
  const auto failures = C.self_check_failures();
  ASSERT_EQ(failures.size(), 3u);
  EXPECT_NE(failures[0].find("certified y"), std::string::npos);
  EXPECT_NE(failures[1].find("certified w"), std::string::npos);
  EXPECT_NE(failures[2].find("certified nan"), std::string::npos);
}

TEST(ConsistencyGuard, OnlyCertifiedChecksAreHeldToTheirRequirements) {
  for (Verdict v : {Verdict::refuted, Verdict::undecided, Verdict::report}) {
    CheckEntry e(CheckId::power_protection);
    e.verdict = v;
    e.require_at_least("min_power_margin", -4.32, 0);
    Certificate C;
    C.checks.push_back(e);
    EXPECT_TRUE(C.self_check_failures().empty());
    EXPECT_NO_THROW(enforce_self_consistency(C));
  }
}

// The second half of the guard: an UNDECIDED check prints a certified bound only where it registered
// that very value as proven whatever its verdict (the tesseract's covering bound 0.99253 < 1 was
// printed as certified under UNDECIDED).
TEST(ConsistencyGuard, UndecidedCheckPrintsOnlyTheBoundsItRegistered) {
  auto entry = [](Verdict v) {
    CheckEntry e(CheckId::covering);
    e.verdict = v;
    e.margin = {{"covering_radius", {{"certified_upper_bound", num(0.99253)}, {"certified_lower_bound", num(0.5)}}}};
    e.bound_proven_whatever_the_verdict("/margin/covering_radius/certified_lower_bound", 0.5, "a certified vertex");
    return e;
  };
  auto failures = [](const CheckEntry& e) {
    Certificate C;
    C.checks.push_back(e);
    return C.self_check_failures();
  };
  // UNDECIDED: the unregistered upper bound fails, the registered lower bound does not.
  auto f = failures(entry(Verdict::undecided));
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NE(f[0].find("/margin/covering_radius/certified_upper_bound = 0.99253"), std::string::npos) << f[0];
  // REPORT with details.decision UNDECIDED (a check that is not claimed) likewise; REPORT without one,
  // CERTIFIED and REFUTED are not held to it.
  CheckEntry r = entry(Verdict::report);
  r.details["decision"] = "UNDECIDED";
  EXPECT_EQ(failures(r).size(), 1u);
  r.details["decision"] = "CERTIFIED";
  EXPECT_TRUE(failures(r).empty());
  for (Verdict v : {Verdict::certified, Verdict::refuted, Verdict::report}) EXPECT_TRUE(failures(entry(v)).empty());
  // Registered, but printed with another value (perturbed by one ulp): fails.
  CheckEntry p = entry(Verdict::undecided);
  p.margin["covering_radius"].erase("certified_upper_bound");
  EXPECT_TRUE(failures(p).empty());
  p.margin["covering_radius"]["certified_lower_bound"] = num(std::nextafter(0.5, 1.0));
  EXPECT_EQ(failures(p).size(), 1u);
  // Anywhere in the entry: details and witnesses too, at their own pointer.
  CheckEntry d = entry(Verdict::undecided);
  d.margin["covering_radius"].erase("certified_upper_bound");
  d.details["per_point"] = {{"tightest_cell", {{"certified_upper_bound", "0.7"}}}};
  d.witnesses.push_back({{"distance", {{"certified_lower_bound", "0.5"}}}});
  f = failures(d);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NE(f[0].find("/details/per_point/tightest_cell/certified_upper_bound"), std::string::npos) << f[0];
  EXPECT_NE(f[1].find("/witnesses/0/distance/certified_lower_bound"), std::string::npos) << f[1];
  Certificate C;
  C.checks.push_back(d);
  EXPECT_THROW(enforce_self_consistency(C), SelfCheckFailure);
}

// A check that is not a claim of the input (reported, its decision in details.decision) still
// prints its bounds as certified when it decided CERTIFIED: the guard holds it to them (a
// contradiction is an internal error, not a certificate), and to nothing when it decided otherwise.
TEST(ConsistencyGuard, AReportedCertifiedDecisionIsHeldToItsRequirements) {
  for (const char* decision : {"CERTIFIED", "REFUTED", "UNDECIDED"}) {
    CheckEntry e(CheckId::power_protection);
    e.verdict = Verdict::report;
    e.claimed = false;
    e.details["decision"] = decision;
    e.require_at_least("min_power_margin", -4.32, 0);
    Certificate C;
    C.checks.push_back(e);
    const auto failures = C.self_check_failures();
    if (std::string(decision) == "CERTIFIED") {
      ASSERT_EQ(failures.size(), 1u);
      EXPECT_NE(failures[0].find("CERTIFIED (reported, not claimed) but its certified min_power_margin -4.32 is below 0"),
                std::string::npos) << failures[0];
      EXPECT_THROW(enforce_self_consistency(C), SelfCheckFailure);
    } else {
      EXPECT_TRUE(failures.empty()) << decision;
    }
  }
}

// The overall verdict and the line before it are about the claimed checks only, the decisive
// ones first.
TEST(ClaimedChecks, OverallVerdictAndDecidedByReadOnlyTheClaims) {
  Certificate C;
  CheckEntry sanity(CheckId::input_sanity), consistency(CheckId::consistency), restricted(CheckId::restricted_delaunay);
  consistency.verdict = Verdict::report, consistency.claimed = false, consistency.details["decision"] = "REFUTED";
  restricted.claim = {{"kind", "restricted"}};
  C.checks = {sanity, consistency, restricted};
  EXPECT_EQ(C.overall(), Verdict::certified);
  EXPECT_EQ(C.decided_by(), "check 1 input_sanity, check 12 restricted_delaunay (the complex is Del_RM(P))");
  C.checks[2].refute("a simplex of Del_RM(P) is missing from the complex");
  EXPECT_EQ(C.overall(), Verdict::refuted);
  EXPECT_EQ(C.decided_by(), "REFUTED check 12 restricted_delaunay (the complex is Del_RM(P)); CERTIFIED check 1 input_sanity");
  C.checks[2].verdict = Verdict::undecided;
  EXPECT_EQ(C.overall(), Verdict::undecided);
  EXPECT_EQ(C.decided_by(), "UNDECIDED check 12 restricted_delaunay (the complex is Del_RM(P)); CERTIFIED check 1 input_sanity");
  // A check that is not claimed never turns the verdict, whatever its verdict field says.
  C.checks[2].verdict = Verdict::certified;
  C.checks[1].verdict = Verdict::refuted;
  EXPECT_EQ(C.overall(), Verdict::certified);
  EXPECT_EQ(C.to_json(false)["checks"][1]["claimed"], false);
  EXPECT_EQ(C.to_json(false)["checks"][2]["claimed"], true);
}

// Claims as close to the true values as a short rational gets: the octahedron's minimum power
// margin is exactly 4 and its minimum distance exactly sqrt(2). Claims just below them are
// CERTIFIED, and the printed bounds must not fall below the claims (the guard would turn the run
// into an internal error if they did).
TEST(ConsistencyGuard, TightClaimsCertifyWithoutTrippingTheGuard) {
  TempDir dir("guard");
  const std::string claims = dir.file("claims.json");
  {
    std::ofstream out(claims);
    out << R"({"format": "delcert-claims v1", "sparsity": "1.4142135623730950488016887242096",)"
        << R"( "power_protection": "3.9999999999999999999999999999", "gamma0": "0.5", "eps": "1.5"})";
  }
  const std::string cert = dir.file("cert.json");
  RunResult r = run(binary() + " --manifold builtin:sphere-2 --points " + q(fixture("points/octahedron.off")) +
                        " --complex " + q(fixture("certify/octahedron.complex")) + " --claims " + q(claims) +
                        " --no-times --out " + q(cert),
                    dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  auto j = nlohmann::json::parse(read_text(cert));
  for (const auto& c : j["checks"]) {
    if (c["name"] == "power_protection") {
      const double lo = std::stod(c["margin"]["min_power_margin"]["certified_lower_bound"].get<std::string>());
      EXPECT_GE(lo, exact::enclose(mpq_class("39999999999999999999999999999/10000000000000000000000000000")).lo);
    }
    if (c["name"] == "sparsity") {
      const double lo = std::stod(c["margin"]["min_distance"]["certified_lower_bound"].get<std::string>());
      // The tightest double lower bound of sqrt(2): lo^2 <= 2 < next(lo)^2, exactly.
      const mpq_class a(lo), b(std::nextafter(lo, 2.0));
      EXPECT_LE(a * a, 2);
      EXPECT_GT(b * b, 2);
    }
  }
}

}  // namespace
}  // namespace delcert::certify::test
