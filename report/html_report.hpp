// The HTML report of delcert-certify --report (docs/formats.md, "The HTML report"): one
// self-contained page (no network when opened) with the verdict table, the margins, histograms,
// an interactive three.js view of the complex with every witness simplex highlighted, and the
// list of witnesses with their reasons.
//
// Presentation only (docs/design.md §5): it reads a finished certificate and never decides
// anything; it is outside certify/ and the trust boundary. three.js is compiled in from the
// pinned npm release (report/CMakeLists.txt); without it viewer_available() is false.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "io/complex.hpp"
#include "io/points.hpp"

namespace delcert::report {

// True when this build holds three.js; else viewer_missing_message() says what to do.
bool viewer_available();
std::string viewer_missing_message();

// The page for `certificate` (the JSON of the certificate, as written by --out), its points and
// its complex (null in audit mode: the page then shows the points and the witness simplices).
// The same arguments give the same bytes. Throws std::logic_error when !viewer_available().
std::string format_html_report(const nlohmann::json& certificate, const io::PointSet& points,
                               const io::Complex* complex);

// Reads the points and (when `complex_path` is not empty) the complex the certificate was made
// from, and formats the page. Throws io::InputError when a file cannot be read.
std::string format_html_report(const nlohmann::json& certificate, const std::string& points_path,
                               const std::string& complex_path);

}  // namespace delcert::report
