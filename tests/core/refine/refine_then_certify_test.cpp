// End to end: the refiner's output must be CERTIFIED by the independent certifier, with the
// refiner's own claims (docs/design.md §1, issue 6: "CI must run delcert refine then delcert-certify
// --claims on small fixtures and fail on anything but CERTIFIED"), Del_TM = Del_RM (check 13)
// included; only Del_RM = Del_M (check 15), which the refiner does not promise, may be decided
// either way, with witnesses that re-check (refined_certificate.hpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/points.hpp"
#include "tests/core/refine/refined_certificate.hpp"
#include "tests/test_support.hpp"

namespace delcert::refine {
namespace {

using test::binary;
using test::run;

struct Case {
  const char* manifold;
  const char* eps;
};

class RefineThenCertify : public ::testing::TestWithParam<Case> {};

TEST_P(RefineThenCertify, RefinedOutputIsCertifiedWithItsClaims) {
  const Case& c = GetParam();
  test::TempDir dir("refine-certify");
  std::string spec = std::string("builtin:") + c.manifold;
  std::string out = dir.file("out");
  auto refine = run(binary("delcert") + " refine --manifold " + spec + " --eps " + c.eps + " --seed 3 --out " + out);
  ASSERT_EQ(refine.status, 0) << refine.output;
  auto report = nlohmann::json::parse(test::slurp(out + "/report.json"));
  EXPECT_EQ(report.at("converged"), true);

  // SO(3) (m = 3 in R^9, codimension 6): the certified restricted Voronoi diagram takes minutes
  // per hundred points today (issue 11's closing note), so its checks are skipped here.
  const std::string skip = std::string(c.manifold) == "so3" ? " --skip-restricted" : "";
  const test::RefinedRun cert = test::certify_refined_output(spec, out, dir.file("certificate.json"), !skip.empty());
  const auto& certificate = cert.certificate;
  // Overall CERTIFIED when Del_RM = Del_M is decided as true too (check 15; 14-15 are "not
  // computed" for the torus of revolution, which has no closed-form metric).
  const auto& checks = certificate.at("checks");
  if (checks.at(14).at("verdict") == "CERTIFIED") {
    EXPECT_EQ(certificate.at("verdict"), "CERTIFIED");
    EXPECT_NE(cert.output.find("verdict: CERTIFIED"), std::string::npos) << cert.output;
  }
}

INSTANTIATE_TEST_SUITE_P(Builtins, RefineThenCertify,
                         ::testing::Values(Case{"clifford-torus-2", "0.3"}, Case{"sphere-2", "0.3"},
                                           Case{"torus-of-revolution", "0.4"}, Case{"sphere-3", "0.5"},
                                           Case{"so3", "0.8"}),
                         [](const auto& info) {
                           std::string n = info.param.manifold;
                           for (char& ch : n) ch = ch == '-' ? '_' : ch;
                           return n;
                         });

}  // namespace
}  // namespace delcert::refine
