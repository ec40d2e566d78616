// Rule not_intrinsic (core/refine/intrinsic_repair.hpp, the Del_M check in refiner.cpp) and the
// final certification of `delcert refine`. The case: 1000 uniform points of the flat Clifford
// torus T^2 (seed 2). The refiner's other rules end there with Del_TM = Del_RM, but Del_RM != Del_M
// (a 2-2 flip: certifier check 15 REFUTED); the rule inserts one point and the output certifies.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "certify/certificate.hpp"
#include "core/manifold/manifold.hpp"
#include "core/refine/intrinsic_repair.hpp"
#include "core/refine/refiner.hpp"
#include "core/sampling/random.hpp"
#include "core/sampling/sampling.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/test_support.hpp"

namespace delcert::refine {
namespace {

using test::binary;
using test::run;

const char* kSpec = "builtin:clifford-torus-2";

io::PointSet flip_case() {
  manifold::Manifold M(io::read_spec(kSpec));
  sampling::Random rng(2);
  io::PointSet ps;
  sampling::sample_manifold(M, 1000, rng, ps);
  return ps;
}

std::vector<std::vector<int>> top_simplices(const io::Complex& K, int m) {
  std::set<std::vector<int>> out;
  for (auto s : K.simplices)
    if (static_cast<int>(s.size()) == m + 1) {
      std::sort(s.begin(), s.end());
      out.insert(s);
    }
  return {out.begin(), out.end()};
}

RefineParameters parameters(bool intrinsic_check) {
  RefineParameters p;
  p.intrinsic_check = intrinsic_check;
  p.threads = 1;
  return p;
}

TEST(RefineDelM, WithoutTheRuleDelRMAndDelMDifferWithItTheyAreEqual) {
  manifold::Manifold M(io::read_spec(kSpec));
  const io::PointSet input = flip_case();

  const RefineResult off = refine(M, input, parameters(false));
  ASSERT_TRUE(off.converged);
  EXPECT_FALSE(off.del_m.checked);
  EXPECT_EQ(off.rules[Rule::not_intrinsic].inserted, 0u);
  const DelMComparison before = compare_with_del_m(M.spec(), off.points, top_simplices(off.complex, 2), 1);
  EXPECT_TRUE(before.restricted_computed);
  ASSERT_TRUE(before.intrinsic_computed);
  ASSERT_FALSE(before.equal());  // the flip the rule is for
  bool only_intrinsic = false;
  for (const DelMBreak& b : before.breaks) {
    EXPECT_EQ(b.simplex.size(), 3u);
    ASSERT_EQ(b.location.size(), 4u) << b.what;  // a Voronoi vertex: restricted or intrinsic
    // On (near) the torus: both coordinate pairs on the unit circles.
    EXPECT_NEAR(std::hypot(b.location[0], b.location[1]), 1.0, 1e-6);
    EXPECT_NEAR(std::hypot(b.location[2], b.location[3]), 1.0, 1e-6);
    only_intrinsic = only_intrinsic || b.what.find("in Del_M, not in Del_TM, Del_RM") != std::string::npos;
  }
  EXPECT_TRUE(only_intrinsic);

  const RefineResult on = refine(M, input, parameters(true));
  ASSERT_TRUE(on.converged) << (on.stall ? describe_stall(*on.stall) : "");
  EXPECT_TRUE(on.del_m.checked);
  EXPECT_GE(on.repair_rounds, 1u);
  EXPECT_GE(on.rules[Rule::not_intrinsic].inserted, 1u);
  EXPECT_EQ(on.del_m.breaks, 0u);
  const DelMComparison after = compare_with_del_m(M.spec(), on.points, top_simplices(on.complex, 2), 1);
  EXPECT_TRUE(after.equal()) << after.breaks.front().what;
  EXPECT_EQ(after.tangential, after.intrinsic);
}

// Through the binaries: without the rule the certifier refutes check 15; with it (the default)
// `delcert refine` certifies its own output in-process and exits 0, and so does delcert-certify.
TEST(RefineDelM, TheDefaultOutputCertifiesWholeWithItsClaims) {
  test::TempDir dir("refine-del-m");
  io::write_points(dir.file("in.txt"), flip_case());
  const std::string base = binary("delcert") + " refine --manifold " + kSpec + " --points " + dir.file("in.txt") + " --threads 1";
  auto certify = [&](const std::string& out) {
    return run(binary("delcert-certify") + " --manifold " + kSpec + " --points " + out + "/points.txt --complex " + out +
               "/complex.txt --claims " + out + "/claims.json --threads 1 --out " + out + "/certificate.json");
  };

  auto off = run(base + " --no-intrinsic-check --out " + dir.file("off"));
  ASSERT_EQ(off.status, 0) << off.output;
  EXPECT_EQ(off.output.find("certified "), std::string::npos) << off.output;  // no final certification
  auto off_cert = certify(dir.file("off"));
  EXPECT_NE(off_cert.status, 0);
  const auto c_off = nlohmann::json::parse(test::slurp(dir.file("off/certificate.json")));
  EXPECT_EQ(c_off.at("checks").at(14).at("name"), "restricted_equals_intrinsic");
  EXPECT_EQ(c_off.at("checks").at(14).at("verdict"), "REFUTED");

  auto on = run(base + " --out " + dir.file("on"));
  ASSERT_EQ(on.status, 0) << on.output;
  EXPECT_NE(on.output.find("certified          yes"), std::string::npos) << on.output;
  EXPECT_NE(on.output.find("not_intrinsic"), std::string::npos) << on.output;
  const auto report = nlohmann::json::parse(test::slurp(dir.file("on/report.json")));
  EXPECT_EQ(report.at("parameters").at("intrinsic_check"), true);
  EXPECT_GE(report.at("rules").at("not_intrinsic").at("inserted").get<int>(), 1);
  EXPECT_GE(report.at("del_m_check").at("repair_rounds").get<int>(), 1);
  EXPECT_EQ(report.at("del_m_check").at("last_check").at("breaks"), 0);
  auto on_cert = certify(dir.file("on"));
  EXPECT_EQ(on_cert.status, 0) << on_cert.output;
  const auto c_on = nlohmann::json::parse(test::slurp(dir.file("on/certificate.json")));
  EXPECT_EQ(c_on.at("verdict"), "CERTIFIED");
  for (const auto& check : c_on.at("checks")) {
    if (check.at("verdict") == "REPORT") continue;
    EXPECT_EQ(check.at("verdict"), "CERTIFIED") << check.at("name");
  }
}

TEST(RefineDelM, StallNamesTheRuleAndTheSimplexWhenTheRepairCapIsZero) {
  manifold::Manifold M(io::read_spec(kSpec));
  RefineParameters p = parameters(true);
  p.max_repair_rounds = 0;
  const RefineResult r = refine(M, flip_case(), p);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason, StopReason::max_repair_rounds);
  EXPECT_EQ(r.repair_rounds, 0u);
  EXPECT_EQ(r.rules[Rule::not_intrinsic].inserted, 0u);
  ASSERT_TRUE(r.stall.has_value());
  EXPECT_EQ(r.stall->rule, Rule::not_intrinsic);
  ASSERT_EQ(r.stall->simplex.size(), 3u);
  EXPECT_EQ(r.stall->location.size(), 4u);
  const std::string message = describe_stall(*r.stall);
  std::string simplex = "simplex [" + std::to_string(r.stall->simplex[0]) + ", " + std::to_string(r.stall->simplex[1]) +
                        ", " + std::to_string(r.stall->simplex[2]) + "]";
  EXPECT_NE(message.find("rule not_intrinsic stalled"), std::string::npos) << message;
  EXPECT_NE(message.find(simplex), std::string::npos) << message;
  EXPECT_NE(message.find("location ("), std::string::npos) << message;

  // The command: exit 4, the stall on the summary and in report.json.
  test::TempDir dir("refine-del-m-cap");
  io::write_points(dir.file("in.txt"), flip_case());
  auto cmd = run(binary("delcert") + " refine --manifold " + kSpec + " --points " + dir.file("in.txt") +
                 " --threads 1 --max-repair-rounds 0 --out " + dir.file("out"));
  EXPECT_EQ(cmd.status, 4) << cmd.output;
  EXPECT_NE(cmd.output.find("stalled            " + message), std::string::npos) << cmd.output;
  EXPECT_NE(cmd.output.find("max_repair_rounds"), std::string::npos) << cmd.output;
  const auto report = nlohmann::json::parse(test::slurp(dir.file("out/report.json")));
  EXPECT_EQ(report.at("stop_reason"), "max_repair_rounds");
  EXPECT_EQ(report.at("stall").at("rule"), "not_intrinsic");
  EXPECT_EQ(report.at("stall").at("simplex"), r.stall->simplex);
}

// Paper mode has the rule only when asked (--intrinsic-check); its points then come from the paper's
// picking regions, and the same start ends with Del_TM = Del_RM = Del_M.
TEST(RefineDelM, PaperModeAppliesTheRuleOnlyWhenAsked) {
  manifold::Manifold M(io::read_spec(kSpec));
  RefineParameters p;
  p.mode = RefineMode::paper;
  p.threads = 1;
  const RefineResult plain = refine(M, flip_case(), p);
  EXPECT_EQ(plain.parameters.intrinsic_check, std::optional<bool>(false));
  EXPECT_FALSE(plain.del_m.checked);
  p.intrinsic_check = true;
  const RefineResult r = refine(M, flip_case(), p);
  ASSERT_TRUE(r.converged) << (r.stall ? describe_stall(*r.stall) : "");
  EXPECT_GE(r.rules[Rule::not_intrinsic].inserted, 1u);
  EXPECT_EQ(r.del_m.breaks, 0u);
  EXPECT_TRUE(compare_with_del_m(M.spec(), r.points, top_simplices(r.complex, 2), 1).equal());
}

// A simplex left out of the complex is a break at its restricted Voronoi vertex.
TEST(CompareWithDelM, AMissingSimplexIsABreakAtItsVoronoiVertex) {
  manifold::Manifold M(io::read_spec(kSpec));
  const RefineResult r = refine(M, flip_case(), parameters(true));
  ASSERT_TRUE(r.converged);
  auto tops = top_simplices(r.complex, 2);
  const std::vector<int> gone = tops[tops.size() / 2];
  tops.erase(tops.begin() + static_cast<long>(tops.size() / 2));
  const DelMComparison c = compare_with_del_m(M.spec(), r.points, tops, 1);
  ASSERT_EQ(c.breaks.size(), 1u);
  EXPECT_EQ(c.breaks[0].simplex, gone);
  EXPECT_EQ(c.breaks[0].what, "in Del_RM, Del_M, not in Del_TM");
  ASSERT_EQ(c.breaks[0].location.size(), 4u);
  // Equidistant from the simplex's three points.
  auto d = [&](int i) {
    double s = 0;
    for (int k = 0; k < 4; ++k) s += std::pow(c.breaks[0].location[k] - r.points.point(gone[i])[k], 2);
    return std::sqrt(s);
  };
  EXPECT_NEAR(d(0), d(1), 1e-9);
  EXPECT_NEAR(d(0), d(2), 1e-9);
}

// certifies_whole forgives exactly what the manifold leaves undecidable.
TEST(CertifiesWhole, ForgivesOnlyWhatTheEnginesCannotComputeOnTheManifold) {
  using certify::CheckId;
  // An entry decided UNDECIDED or REFUTED, with the summary the certifier prints.
  auto entry = [](CheckId id, bool refuted, const std::string& summary) {
    certify::CheckEntry e(id);
    if (refuted)
      e.refute(summary);
    else
      e.undecide(summary);
    e.summary = summary;
    return e;
  };
  certify::Certificate C;
  C.checks.emplace_back(CheckId::input_sanity);
  C.checks.push_back(entry(CheckId::intrinsic_delaunay, false,
                           "not computed: no closed-form geodesic distance: the spec declares no metric"));
  C.checks.push_back(entry(CheckId::restricted_equals_intrinsic, false,
                           "not decided: Del_M(P) not computed: no closed-form geodesic distance"));
  WholeVerdict v = certifies_whole(C);
  EXPECT_TRUE(v.certified);
  EXPECT_EQ(v.not_decidable.size(), 2u);

  C.checks.push_back(entry(CheckId::tangential_equals_restricted, true, "Del_TM(P) != Del_RM(P)"));
  C.checks.push_back(entry(CheckId::covering, false, "not decided: a cell is incomplete"));
  v = certifies_whole(C);
  EXPECT_FALSE(v.certified);
  ASSERT_EQ(v.failing.size(), 2u);
  EXPECT_NE(v.failing[0].find("check 13 tangential_equals_restricted REFUTED"), std::string::npos) << v.failing[0];
  EXPECT_NE(v.failing[1].find("check 11 covering UNDECIDED"), std::string::npos) << v.failing[1];
}

}  // namespace
}  // namespace delcert::refine
