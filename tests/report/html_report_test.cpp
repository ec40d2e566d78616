// The HTML report writer (report/html_report.hpp) without a browser: what the page holds, that it
// holds no raw markup from the certificate, and that it is deterministic. The page in a real
// browser is tests/report/browser_test.py (label browser).
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "io/complex.hpp"
#include "io/points.hpp"
#include "report/html_report.hpp"
#include "tests/test_paths.hpp"

namespace delcert::report {
namespace {

std::string fixture(const std::string& rel) { return std::string(DELCERT_FIXTURES_DIR) + "/" + rel; }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A small certificate in the shape of delcert-certificate v1, with a hostile reason text.
nlohmann::json certificate() {
  return nlohmann::json::parse(R"({
    "format": "delcert-certificate v1", "verdict": "REFUTED",
    "inputs": {"manifold": {"name": "sphere-2", "intrinsic_dimension": 2, "ambient_dimension": 3}},
    "checks": [
      {"id": 1, "name": "input_sanity", "verdict": "CERTIFIED", "summary": "fine", "margin": null,
       "witnesses": [], "details": {}},
      {"id": 4, "name": "consistency", "verdict": "REFUTED", "summary": "2 of 8 <b>not</b>",
       "margin": null, "details": {"reason": "a simplex is not in the star of one of its vertices",
                                   "witnesses_total": 3},
       "witnesses": [{"kind": "point_in_ball", "simplex": [0, 2, 3], "at_vertex": 2,
                      "detail": "</script><script>alert(1)</script>"},
                     {"kind": "degenerate_in_tangent_space", "simplex": [0, 2, 4], "at_vertex": 0}]},
      {"id": 2, "name": "sparsity", "verdict": "REPORT", "summary": "min distance",
       "margin": {"pair": [0, 2]}, "witnesses": [{"kind": "pair", "pair": [1, 5]}], "details": {}},
      {"id": 11, "name": "covering", "verdict": "UNDECIDED", "summary": "open",
       "margin": null, "witnesses": [{"kind": "restricted_voronoi_vertex", "at": [0.5, 0.5]}], "details": {}}
    ]})");
}

class HtmlReport : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!viewer_available()) GTEST_SKIP() << viewer_missing_message();
    points = io::read_points(fixture("points/octahedron.off"));
    complex = io::read_complex(fixture("certify/octahedron.complex")).complex;
  }
  io::PointSet points;
  io::Complex complex;
};

TEST_F(HtmlReport, HoldsTheChecksTheWitnessesAndTheLibraries) {
  const std::string page = format_html_report(certificate(), points, &complex);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("verdict: <span class=\"verdict\">REFUTED</span>"), std::string::npos);
  EXPECT_EQ(count(page, "<tr class=\"verdict-"), 4u);  // one row per check
  // One list item per witness, in the certificate's order, with the vertices it is about.
  std::regex item(R"re(<li class="witness [^"]*" data-index="(\d+)" data-check="(\d+)" data-kind="([^"]*)" data-simplex="([^"]*)")re");
  std::vector<std::string> seen;
  for (std::sregex_iterator it(page.begin(), page.end(), item), end; it != end; ++it)
    seen.push_back((*it)[1].str() + " " + (*it)[2].str() + " " + (*it)[3].str() + " " + (*it)[4].str());
  EXPECT_EQ(seen, (std::vector<std::string>{"0 4 point_in_ball [0,2,3]", "1 4 degenerate_in_tangent_space [0,2,4]",
                                            "2 2 pair [1,5]", "3 11 restricted_voronoi_vertex []"}));
  EXPECT_NE(page.find("check 4: 1 more not listed"), std::string::npos);  // witnesses_total 3, 2 listed
  EXPECT_NE(page.find("(check: a simplex is not in the star of one of its vertices)"), std::string::npos);
  // Everything inline: three.js and OrbitControls as base64, no <script src>, no placeholder left.
  EXPECT_EQ(count(page, "<script src"), 0u);
  EXPECT_NE(page.find("<script type=\"text/plain\" id=\"three-module\">"), std::string::npos);
  EXPECT_NE(page.find("<script type=\"text/plain\" id=\"orbit-controls\">"), std::string::npos);
  EXPECT_FALSE(std::regex_search(page, std::regex("@[A-Z_]+@")));
  EXPECT_NE(page.find("MIT License"), std::string::npos);  // three.js's licence travels with it
}

// A check that is not a claim of the input (issue 43) says so in its row, with its own decision;
// a claimed check's row does not.
TEST_F(HtmlReport, ARowSaysWhenItsCheckIsNotClaimed) {
  nlohmann::json c = certificate();
  c["verdict"] = "CERTIFIED";
  c["checks"][1]["verdict"] = "REPORT";
  c["checks"][1]["claimed"] = false;
  c["checks"][1]["details"]["decision"] = "REFUTED";
  c["checks"][0]["claimed"] = true;
  const std::string page = format_html_report(c, points, &complex);
  EXPECT_EQ(count(page, "<small>not claimed"), 1u);
  EXPECT_NE(page.find("REPORT<br><small>not claimed: REFUTED</small>"), std::string::npos);
}

TEST_F(HtmlReport, CertificateTextCannotBreakOutOfThePage) {
  const std::string page = format_html_report(certificate(), points, &complex);
  // The template's four scripts close; the certificate's "</script>" is escaped in the list (HTML)
  // and in the data (\u003c inside a JSON string).
  EXPECT_EQ(count(page, "</script>"), 4u);
  EXPECT_EQ(count(page, "<script>alert"), 0u);
  EXPECT_NE(page.find("&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(page.find("\\u003c/script>\\u003cscript>alert(1)\\u003c/script>"), std::string::npos);
  EXPECT_NE(page.find("2 of 8 &lt;b&gt;not&lt;/b&gt;"), std::string::npos);
}

TEST_F(HtmlReport, SameInputsSameBytes) {
  EXPECT_EQ(format_html_report(certificate(), points, &complex), format_html_report(certificate(), points, &complex));
  // From the files: the same page as from the parsed inputs.
  EXPECT_EQ(format_html_report(certificate(), fixture("points/octahedron.off"), fixture("certify/octahedron.complex")),
            format_html_report(certificate(), points, &complex));
}

TEST_F(HtmlReport, AuditModeHasNoComplex) {
  const std::string page = format_html_report(certificate(), points, nullptr);
  EXPECT_NE(page.find("\"has_complex\":false"), std::string::npos);
  EXPECT_NE(page.find("\"simplices\":[]"), std::string::npos);
  EXPECT_NE(page.find("\"points\":[1.0,0.0,0.0,"), std::string::npos) << page.substr(page.find("\"points\""), 80);
}

TEST(HtmlReportWithoutViewer, RefusesInsteadOfWritingABrokenPage) {
  if (viewer_available()) GTEST_SKIP() << "this build holds three.js";
  EXPECT_THROW(format_html_report(certificate(), io::PointSet{}, nullptr), std::logic_error);
  EXPECT_NE(viewer_missing_message().find("scripts/setup.sh"), std::string::npos);
}

}  // namespace
}  // namespace delcert::report
