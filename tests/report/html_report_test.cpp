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
  EXPECT_EQ(count(page, "<tr id=\"check-"), 4u);  // one row per check
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

// What needs a look comes first: REFUTED, then UNDECIDED, then CERTIFIED, then REPORT (issue 41).
TEST_F(HtmlReport, RefutedRowsComeFirst) {
  const std::string page = format_html_report(certificate(), points, &complex);
  std::vector<std::string> order;
  const std::regex row("<tr id=\"check-([0-9]+)\" class=\"verdict-([A-Z]+)\">");
  for (std::sregex_iterator it(page.begin(), page.end(), row), end; it != end; ++it) order.push_back((*it)[2].str() + " " + (*it)[1].str());
  EXPECT_EQ(order, (std::vector<std::string>{"REFUTED 4", "UNDECIDED 11", "CERTIFIED 1", "REPORT 2"}));
  EXPECT_NE(page.find("needs a look: <a href=\"#check-4\" class=\"verdict-REFUTED\">REFUTED check 4 consistency</a>, "
                      "<a href=\"#check-11\" class=\"verdict-UNDECIDED\">UNDECIDED check 11 covering</a>"),
            std::string::npos);
}

// Margins read as words and short numbers, each bound rounded in its safe direction (a lower bound
// down, an upper bound up), never as the certificate's JSON.
TEST_F(HtmlReport, MarginsAreNumbersAPersonReads) {
  nlohmann::json c = certificate();
  c["checks"][0]["margin"] = nlohmann::json::parse(R"({"at_point": 6,
      "max_residual": {"certified_upper_bound": "1.216524007297204e-16", "enclosure": ["1.2e-16", "1.216524007297204e-16"]}})");
  c["checks"][2]["margin"] = nlohmann::json::parse(R"({"2": {"faces": 190, "min_thickness":
      {"certified_lower_bound": "0.18666176406945584", "enclosure": ["0.18666176406945584", "0.1866618530767847"]},
      "simplex": [11, 34, 89]}, "factor": {"certified_lower_bound": "1.5453796367381597e-10"},
      "covering_radius": {"certified_lower_bound": "0.5557597393439546", "certified_upper_bound": "0.5616461195020096"},
      "attained_near": ["0.5291591255209892", "-0.848518073646868"], "max_radius_squared": {"certified_upper_bound": "0.37481315091323053"},
      "min_power_margin": {"certified_lower_bound": "0.00012345"}})");
  const std::string page = format_html_report(c, points, &complex);
  auto margin_of = [&](int id) {
    const std::size_t row = page.find("<tr id=\"check-" + std::to_string(id) + "\"");
    const std::size_t at = page.find("<td class=\"margin\">", row);
    return page.substr(at, page.find("</td>", at) - at);
  };
  EXPECT_EQ(margin_of(1), "<td class=\"margin\"><div>at point: 6</div><div>max residual: &le; 1.22e-16 (certified)</div>");
  const std::string m = margin_of(2);
  EXPECT_NE(m.find("<div>dimension 2: faces 190, min thickness &ge; 0.186 (certified), simplex [11, 34, 89]</div>"),
            std::string::npos) << m;
  EXPECT_NE(m.find("factor: &ge; 1.54e-10 (certified)"), std::string::npos) << m;
  EXPECT_NE(m.find("covering radius: in [0.555, 0.562] (certified)"), std::string::npos) << m;
  EXPECT_NE(m.find("attained near: (0.529, -0.849)"), std::string::npos) << m;
  EXPECT_NE(m.find("max radius squared: &le; 0.375 (certified)"), std::string::npos) << m;
  EXPECT_NE(m.find("min power margin: &ge; 0.000123 (certified)"), std::string::npos) << m;
  EXPECT_EQ(margin_of(4), "<td class=\"margin\">&mdash;");
  for (int id : {1, 2, 4, 11}) {
    const std::string text = margin_of(id).substr(std::string("<td class=\"margin\">").size());
    EXPECT_EQ(text.find_first_of("{}\""), std::string::npos) << text;  // no JSON
    EXPECT_FALSE(std::regex_search(text, std::regex("\\.[0-9]*[1-9][0-9]{4}"))) << text;  // no 17-digit numbers
  }
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
