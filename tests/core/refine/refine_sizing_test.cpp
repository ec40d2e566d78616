// Issue 15, item 2: `delcert refine --sizing curvature` on an ellipsoid with axis ratio 4
// (fixtures/specs/uneven/ellipsoid-4-2-1.json). The run converges, writes claims.json version 3
// with ε(p) per point in eps.txt, and delcert-certify CERTIFIES its output with those claims
// (checks 10 and 11 against ε(p), every other check as refined_certificate.hpp asks). One point's
// ε shrunk below its star radius and its cell's distance is REFUTED by both checks, that point the
// witness. Same seed, same bytes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "exact/polynomial.hpp"
#include "io/claims.hpp"
#include "tests/core/refine/refined_certificate.hpp"
#include "tests/test_support.hpp"

namespace delcert::refine {
namespace {

using test::binary;
using test::fixture;
using test::run;

const nlohmann::json& check(const nlohmann::json& certificate, const std::string& name) {
  for (const auto& c : certificate.at("checks"))
    if (c.at("name") == name) return c;
  throw std::runtime_error("no check " + name);
}

// eps 0.5 (the cap), c = 1/2 and the default floor 0.05: the field runs from c / 4 = 0.125 at the
// sharp ends (κ_max = a/c^2 = 4) to the cap where M is flatter than κ_max = 1 (~470 points; the
// uniform ε = 0.125 needs ~2700).
std::string refine_command(const std::string& spec, const std::string& out, int threads) {
  return binary("delcert") + " refine --manifold " + spec + " --eps 0.5 --sizing curvature --seed 1 --threads " +
         std::to_string(threads) + " --out " + out;
}

TEST(RefineSizing, CurvatureFieldConvergesAndIsCertifiedPerPoint) {
  test::TempDir dir("refine-sizing");
  const std::string spec = fixture("specs/uneven/ellipsoid-4-2-1.json");
  const std::string out = dir.file("out");
  auto refine = run(refine_command(spec, out, 1));
  ASSERT_EQ(refine.status, 0) << refine.output;
  auto report = nlohmann::json::parse(test::slurp(out + "/report.json"));
  EXPECT_EQ(report.at("converged"), true);
  EXPECT_EQ(report.at("sizing").at("kind"), "curvature");
  EXPECT_LT(report.at("sizing").at("min_local_eps").get<double>(), 0.13);  // the sharp ends: 1/2 / 4
  EXPECT_EQ(report.at("sizing").at("max_local_eps").get<double>(), 0.5);   // the flat parts: the cap
  auto claims = nlohmann::json::parse(test::slurp(out + "/claims.json"));
  EXPECT_EQ(claims.at("format"), "delcert-claims v3");
  EXPECT_EQ(claims.at("star_radius_per_point"), "eps.txt");
  EXPECT_EQ(claims.at("covering_per_point"), "eps.txt");
  EXPECT_FALSE(claims.contains("star_radius"));
  const auto eps = io::parse_per_point(test::slurp(out + "/eps.txt"), "eps.txt");
  const io::PointSet P = io::read_points(out + "/points.txt");
  ASSERT_EQ(eps.size(), P.size());

  const test::RefinedRun cert = test::certify_refined_output(spec, out, dir.file("certificate.json"), false);
  EXPECT_EQ(check(cert.certificate, "star_radius").at("verdict"), "CERTIFIED") << cert.output;
  EXPECT_EQ(check(cert.certificate, "covering").at("verdict"), "CERTIFIED") << cert.output;
  EXPECT_EQ(check(cert.certificate, "star_radius").at("claim").at("star_radius_per_point"), "eps.txt");

  // One point's ε shrunk far below its star radius and its cell: both checks REFUTED, naming it.
  const std::size_t p = P.size() / 2;
  auto mutated = eps;
  mutated[p] = mpq_class(1, 1000000);
  std::ofstream(out + "/eps.txt", std::ios::binary) << io::format_per_point(mutated);
  auto bad = run(binary("delcert-certify") + " --manifold " + spec + " --points " + out + "/points.txt --complex " + out +
                 "/complex.txt --claims " + out + "/claims.json --out " + dir.file("refuted.json"));
  EXPECT_EQ(bad.status, 1) << bad.output;
  const auto refuted = nlohmann::json::parse(test::slurp(dir.file("refuted.json")));
  const auto& radius = check(refuted, "star_radius");
  EXPECT_EQ(radius.at("verdict"), "REFUTED");
  ASSERT_FALSE(radius.at("witnesses").empty());
  for (const auto& w : radius.at("witnesses")) {
    EXPECT_EQ(w.at("at_vertex"), p);
    EXPECT_EQ(exact::parse_rational(w.at("eps_at_vertex").get<std::string>()), mpq_class(1, 1000000));
  }
  const auto& covering = check(refuted, "covering");
  EXPECT_EQ(covering.at("verdict"), "REFUTED");
  ASSERT_FALSE(covering.at("witnesses").empty());
  for (const auto& w : covering.at("witnesses")) EXPECT_EQ(w.at("point"), p);

  // A file with one value too few: bad input (exit 2), nothing written.
  mutated.pop_back();
  std::ofstream(out + "/eps.txt", std::ios::binary) << io::format_per_point(mutated);
  auto short_file = run(binary("delcert-certify") + " --manifold " + spec + " --points " + out + "/points.txt --claims " +
                        out + "/claims.json --skip-restricted --out " + dir.file("short.json"));
  EXPECT_EQ(short_file.status, 2) << short_file.output;
  EXPECT_NE(short_file.output.find("one eps(p) per point"), std::string::npos) << short_file.output;
  EXPECT_FALSE(std::ifstream(dir.file("short.json")).good());
}

// Same inputs and seed, same bytes, whatever the thread count (the field is a function of the point).
TEST(RefineSizing, CurvatureFieldIsDeterministic) {
  test::TempDir dir("refine-sizing-det");
  const std::string spec = fixture("specs/uneven/ellipsoid-4-2-1.json");
  for (int threads : {1, 2}) {
    auto r = run(refine_command(spec, dir.file("t" + std::to_string(threads)), threads));
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const char* f : {"points.txt", "complex.txt", "claims.json", "eps.txt"})
    EXPECT_EQ(test::slurp(dir.file("t1/") + f), test::slurp(dir.file("t2/") + f)) << f;
}

TEST(RefineSizing, RefusesBadSizingOptions) {
  test::TempDir dir("refine-sizing-bad");
  const std::string spec = fixture("specs/uneven/ellipsoid-4-2-1.json");
  const std::string base = binary("delcert") + " refine --manifold " + spec + " --eps 0.5 --out " + dir.file("o");
  auto above = run(base + " --sizing curvature --eps-floor 0.6");
  EXPECT_EQ(above.status, 2) << above.output;
  EXPECT_NE(above.output.find("--eps-floor"), std::string::npos) << above.output;
  auto zero_c = run(base + " --sizing curvature --sizing-c 0");
  EXPECT_EQ(zero_c.status, 2) << zero_c.output;
  EXPECT_NE(zero_c.output.find("--sizing-c"), std::string::npos) << zero_c.output;
  auto uniform_floor = run(base + " --eps-floor 0.1");
  EXPECT_EQ(uniform_floor.status, 2) << uniform_floor.output;
  auto uniform_c = run(base + " --sizing-c 0.5");  // even the default value: it means nothing without the field
  EXPECT_EQ(uniform_c.status, 2) << uniform_c.output;
  auto paper = run(base + " --sizing curvature --mode paper");
  EXPECT_EQ(paper.status, 2) << paper.output;
  EXPECT_FALSE(std::ifstream(dir.file("o/points.txt")).good());
}

}  // namespace
}  // namespace delcert::refine
