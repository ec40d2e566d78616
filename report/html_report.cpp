// The HTML report (report/html_report.hpp). The page template is report/page.html; this file fills
// in the parts that need no JavaScript (the verdict table and the witness list, so that they read
// the same in any browser) and the data the page's script draws: the points, the simplices, the
// witnesses and the certified margins. three.js and OrbitControls are inlined as base64 text that
// the page turns into module blobs, so the file opens without any network.
#include "report/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>

#include "io/points.hpp"

namespace delcert::report {

namespace embedded {
std::string_view page();
std::string_view three_module();
std::string_view orbit_controls();
std::string_view three_license();
}  // namespace embedded

namespace {

std::string escape_html(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(std::string_view in) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) |
                 static_cast<unsigned char>(in[i + 2]);
    for (int k = 3; k >= 0; --k) out += digits[(v >> (6 * k)) & 63];
  }
  if (i < in.size()) {
    unsigned v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < in.size() ? digits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// JSON text safe inside <script>: '<' appears only inside JSON strings, where \u003c means the same.
std::string script_json(const nlohmann::json& j) {
  std::string s = j.dump();
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

bool is_index_list(const nlohmann::json& j) {
  if (!j.is_array() || j.empty()) return false;
  for (const auto& x : j)
    if (!x.is_number_integer() || x.get<long long>() < 0) return false;
  return true;
}

// ---- margins as a person reads them -------------------------------------------------------------

// A certified bound shown with 3 significant digits, rounded in its safe direction (a lower bound
// down, an upper bound up), so that the shown number is still a bound: "0.187", "1.55e-10".
std::string shown_number(double x, int direction) {
  if (!std::isfinite(x)) return x > 0 ? "inf" : x < 0 ? "-inf" : "nan";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  double y = std::strtod(buf, nullptr);
  if ((direction < 0 && y > x) || (direction > 0 && y < x)) {
    // One unit of the third significant digit towards safety.
    int e = x == 0 ? 0 : static_cast<int>(std::floor(std::log10(std::fabs(x)))) - 2;
    y += direction * std::pow(10.0, e);
    std::snprintf(buf, sizeof buf, "%.3g", y);
    if ((direction < 0 && std::strtod(buf, nullptr) > x) || (direction > 0 && std::strtod(buf, nullptr) < x))
      std::snprintf(buf, sizeof buf, "%.17g", x);  // (never reached; the exact text then)
  }
  std::string out = buf;
  // "1.55e-10" as printed; "1.2e-04" -> "1.2e-4".
  if (auto at = out.find("e"); at != std::string::npos) {
    std::string mantissa = out.substr(0, at), exponent = out.substr(at + 1);
    const char sign = exponent[0] == '-' ? '-' : '+';
    exponent = exponent.substr(exponent[0] == '-' || exponent[0] == '+' ? 1 : 0);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    out = mantissa + "e" + (sign == '-' ? "-" : "") + exponent;
  }
  return out;
}

std::optional<double> number_of(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (!j.is_string()) return std::nullopt;
  const std::string t = j.get<std::string>();
  char* end = nullptr;
  const double x = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size()) return std::nullopt;
  return x;
}

std::string words(std::string key) {
  std::replace(key.begin(), key.end(), '_', ' ');
  return key;
}

std::string index_list(const nlohmann::json& j) {
  std::string out = "[";
  for (std::size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + std::to_string(j[i].get<long long>());
  return out + "]";
}

// One value of a margin, in words: a bound, an enclosure, a place, a list of coordinates.
std::string margin_value(const nlohmann::json& v) {
  if (v.is_object()) {
    const auto lower = v.contains("certified_lower_bound") ? number_of(v["certified_lower_bound"]) : std::nullopt;
    const auto upper = v.contains("certified_upper_bound") ? number_of(v["certified_upper_bound"]) : std::nullopt;
    if (lower && upper) return "in [" + shown_number(*lower, -1) + ", " + shown_number(*upper, +1) + "] (certified)";
    if (lower) return "&ge; " + shown_number(*lower, -1) + " (certified)";
    if (upper) return "&le; " + shown_number(*upper, +1) + " (certified)";
    if (v.contains("enclosure") && v["enclosure"].is_array() && v["enclosure"].size() == 2) {
      const auto a = number_of(v["enclosure"][0]), b = number_of(v["enclosure"][1]);
      if (a && b) return "in [" + shown_number(*a, -1) + ", " + shown_number(*b, +1) + "]";
    }
    std::string out;
    for (const auto& [key, value] : v.items()) {
      if (key == "enclosure" && (v.contains("certified_lower_bound") || v.contains("certified_upper_bound"))) continue;
      out += (out.empty() ? "" : ", ") + escape_html(words(key)) + " " + margin_value(value);
    }
    return out;
  }
  if (is_index_list(v)) return index_list(v);
  if (v.is_array()) {
    std::string out = "(";
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto x = number_of(v[i]);
      out += (i ? ", " : "") + (x ? shown_number(*x, 0) : margin_value(v[i]));
    }
    return out + ")";
  }
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (const auto x = number_of(v)) return shown_number(*x, 0);
  if (v.is_string()) return escape_html(v.get<std::string>());
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  return "&mdash;";
}

// A check's margin as lines of "what: value" (the certificate's JSON holds the exact bounds).
std::string margin_html(const nlohmann::json& margin) {
  if (margin.is_null() || (margin.is_object() && margin.empty())) return "&mdash;";
  if (!margin.is_object()) return margin_value(margin);
  std::string out;
  for (const auto& [key, value] : margin.items()) {
    const bool dimension = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
    out += "<div>" + (dimension ? "dimension " + escape_html(key) : escape_html(words(key))) + ": " + margin_value(value) + "</div>";
  }
  return out;
}

// Table order: what needs a look first (REFUTED, then UNDECIDED), then CERTIFIED, then the rest
// (REPORT); by id within each.
int verdict_rank(const std::string& verdict) {
  return verdict == "REFUTED" ? 0 : verdict == "UNDECIDED" ? 1 : verdict == "CERTIFIED" ? 2 : 3;
}

// The vertices a witness is about: its simplex (or face, ridge, pair), else its point; empty when
// it names none (e.g. a restricted Voronoi vertex that only gives coordinates).
nlohmann::json witness_simplex(const nlohmann::json& w) {
  if (!w.is_object()) return nlohmann::json::array();
  for (const char* key : {"simplex", "face", "ridge", "pair", "edge", "vertices"})
    if (w.contains(key) && is_index_list(w[key])) return w[key];
  for (const char* key : {"point", "vertex", "at_point", "at_vertex"})
    if (w.contains(key) && w[key].is_number_integer() && w[key].get<long long>() >= 0)
      return nlohmann::json::array({w[key]});
  return nlohmann::json::array();
}

// Why the witness refutes (or leaves open) its check, in words.
std::string witness_reason(const nlohmann::json& w) {
  if (!w.is_object()) return w.dump();
  for (const char* key : {"detail", "failed", "reason"})
    if (w.contains(key) && w[key].is_string()) return w[key].get<std::string>();
  if (w.contains("kind") && w["kind"].is_string()) return w["kind"].get<std::string>();
  return w.dump();
}

// Where a witness was found, when it says: "at vertex 2, point 31".
std::string witness_place(const nlohmann::json& w) {
  std::string out;
  for (const auto& [key, label] : {std::pair{"at_vertex", "at vertex "}, std::pair{"point", "point "}})
    if (w.is_object() && w.contains(key) && w[key].is_number_integer())
      out += (out.empty() ? "" : ", ") + std::string(label) + std::to_string(w[key].get<long long>());
  return out;
}

std::string text_of(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
}

// The template with every @NAME@ of `values` replaced, in one pass (a value is never searched for
// placeholders); every name must occur.
std::string fill(std::string_view page, const std::map<std::string, std::string>& values) {
  std::string out;
  std::set<std::string> used;
  std::size_t i = 0;
  while (i < page.size()) {
    const std::size_t at = page.find('@', i);
    if (at == std::string_view::npos) break;
    const std::size_t end = page.find('@', at + 1);
    const auto it = end == std::string_view::npos ? values.end()
                                                  : values.find(std::string(page.substr(at + 1, end - at - 1)));
    if (it == values.end()) {
      out.append(page.substr(i, at + 1 - i));
      i = at + 1;
      continue;
    }
    out.append(page.substr(i, at - i));
    out += it->second;
    used.insert(it->first);
    i = end + 1;
  }
  out.append(page.substr(std::min(i, page.size())));
  for (const auto& [name, value] : values)
    if (!used.count(name)) throw std::logic_error("report/page.html has no @" + name + "@");
  return out;
}

}  // namespace

bool viewer_available() { return !embedded::three_module().empty() && !embedded::orbit_controls().empty(); }

std::string viewer_missing_message() {
  return "--report needs three.js " DELCERT_THREEJS_VERSION
         ", which this build does not hold: run scripts/setup.sh (it fetches the pinned release from the npm "
         "registry into third_party/), then rebuild (scripts/build.sh; or point the CMake cache variable "
         "DELCERT_THREEJS_DIR at a folder holding three.module.min.js, LICENSE and "
         "examples/jsm/controls/OrbitControls.js)";
}

std::string format_html_report(const nlohmann::json& certificate, const io::PointSet& points,
                               const io::Complex* complex) {
  if (!viewer_available()) throw std::logic_error(viewer_missing_message());
  const nlohmann::json& checks = certificate.contains("checks") ? certificate["checks"] : nlohmann::json::array();

  // The verdict table and the witness list, as plain HTML.
  std::string items;
  std::vector<std::pair<std::pair<int, int>, std::string>> rows;  // ((rank, id), row)
  std::string refuted_links;
  nlohmann::json witnesses = nlohmann::json::array();
  nlohmann::json margins = nlohmann::json::object();
  for (const auto& c : checks) {
    const std::string verdict = text_of(c, "verdict"), name = text_of(c, "name");
    const int id = c.value("id", 0);
    const nlohmann::json margin = c.contains("margin") ? c["margin"] : nlohmann::json();
    margins[name] = margin;
    const nlohmann::json& details = c.contains("details") ? c["details"] : nlohmann::json::object();
    // A check that is not a claim of the input: reported, with its own decision (never the verdict's).
    const std::string decision = text_of(details, "decision");
    const std::string not_claimed = c.value("claimed", true) ? std::string()
                                    : "<br><small>not claimed" + (decision.empty() ? "" : ": " + escape_html(decision)) + "</small>";
    rows.push_back({{verdict_rank(verdict), id},
                    "<tr id=\"check-" + std::to_string(id) + "\" class=\"verdict-" + escape_html(verdict) + "\"><td>" +
                        std::to_string(id) + "</td><td>" + escape_html(name) + "</td><td class=\"verdict\">" +
                        escape_html(verdict) + not_claimed + "</td><td>" + escape_html(text_of(c, "summary")) +
                        "</td><td class=\"margin\">" + margin_html(margin) + "</td></tr>\n"});
    if (verdict == "REFUTED" || verdict == "UNDECIDED")
      refuted_links += std::string(refuted_links.empty() ? "" : ", ") + "<a href=\"#check-" + std::to_string(id) +
                       "\" class=\"verdict-" + escape_html(verdict) + "\">" + escape_html(verdict) + " check " +
                       std::to_string(id) + " " + escape_html(name) + "</a>";
    const std::string check_reason = text_of(details, "reason");
    if (!c.contains("witnesses") || !c["witnesses"].is_array()) continue;
    int k = 0;
    for (const auto& w : c["witnesses"]) {
      nlohmann::json entry = {{"index", witnesses.size()},
                              {"check", id},
                              {"check_name", name},
                              {"verdict", verdict},
                              {"kind", text_of(w, "kind")},
                              {"simplex", witness_simplex(w)},
                              {"reason", witness_reason(w)},
                              {"witness", w}};
      items += "<li class=\"witness verdict-" + escape_html(verdict) + "\" data-index=\"" +
               std::to_string(witnesses.size()) + "\" data-check=\"" + std::to_string(id) + "\" data-kind=\"" +
               escape_html(entry["kind"].get<std::string>()) + "\" data-simplex=\"" +
               escape_html(entry["simplex"].dump()) + "\"><span class=\"wcheck\">check " + std::to_string(id) + " " +
               escape_html(name) + " (" + escape_html(verdict) + ")</span> <span class=\"wkind\">" +
               escape_html(entry["kind"].get<std::string>()) + "</span> <span class=\"wsimplex\">" +
               escape_html(entry["simplex"].dump()) + "</span> <span class=\"wplace\">" +
               escape_html(witness_place(w)) + "</span><div class=\"wreason\">" +
               escape_html(entry["reason"].get<std::string>()) +
               (k == 0 && !check_reason.empty() ? " <em>(check: " + escape_html(check_reason) + ")</em>" : "") +
               "</div></li>\n";
      witnesses.push_back(std::move(entry));
      ++k;
    }
    if (details.contains("witnesses_total") && details["witnesses_total"].is_number_integer() &&
        details["witnesses_total"].get<long long>() > k)
      items += "<li class=\"witness-more\">check " + std::to_string(id) + ": " +
               std::to_string(details["witnesses_total"].get<long long>() - k) +
               " more not listed in the certificate (it keeps the first " + std::to_string(k) + ")</li>\n";
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string row_text;
  for (const auto& r : rows) row_text += r.second;
  if (items.empty()) items = "<li class=\"witness-none\">no witnesses: nothing was refuted</li>\n";

  const nlohmann::json& inputs = certificate.contains("inputs") ? certificate["inputs"] : nlohmann::json::object();
  const nlohmann::json manifold = inputs.contains("manifold") ? inputs["manifold"] : nlohmann::json::object();
  nlohmann::json data = {{"verdict", text_of(certificate, "verdict")},
                         {"manifold", manifold},
                         {"ambient_dimension", points.dimension},
                         {"intrinsic_dimension", manifold.value("intrinsic_dimension", 2)},
                         {"points", points.coordinates},
                         {"simplices", complex ? nlohmann::json(complex->simplices) : nlohmann::json::array()},
                         {"has_complex", complex != nullptr},
                         {"witnesses", witnesses},
                         {"margins", margins}};

  const std::string verdict = text_of(certificate, "verdict");
  const std::string title = "delcert certificate: " + verdict + " (" + text_of(manifold, "name") + ", " +
                            std::to_string(points.size()) + " points)";
  return fill(embedded::page(), {{"TITLE", escape_html(title)},
                                 {"VERDICT", escape_html(verdict)},
                                 {"INPUTS", escape_html(inputs.dump(2))},
                                 {"CHECK_ROWS", row_text},
                                 {"NEEDS_A_LOOK", refuted_links.empty() ? std::string("no check refuted or undecided")
                                                                        : "needs a look: " + refuted_links},
                                 {"WITNESS_COUNT", std::to_string(witnesses.size())},
                                 {"WITNESS_ITEMS", items},
                                 {"THREE_VERSION", DELCERT_THREEJS_VERSION},
                                 {"THREE_LICENSE", escape_html(embedded::three_license())},
                                 {"DATA", script_json(data)},
                                 {"ORBIT_CONTROLS_BASE64", base64(embedded::orbit_controls())},
                                 {"THREE_BASE64", base64(embedded::three_module())}});
}

std::string format_html_report(const nlohmann::json& certificate, const std::string& points_path,
                               const std::string& complex_path) {
  io::PointSet points = io::read_points(points_path, {.expected_dimension = 0, .reject_duplicates = false});
  if (complex_path.empty()) return format_html_report(certificate, points, nullptr);
  io::ComplexFile complex = io::read_complex(complex_path);
  return format_html_report(certificate, points, &complex.complex);
}

}  // namespace delcert::report
