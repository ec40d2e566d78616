#include "certify/certificate.hpp"

#include <algorithm>

#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "io/points.hpp"

namespace delcert::certify {

using nlohmann::json;

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::certified: return "CERTIFIED";
    case Verdict::refuted: return "REFUTED";
    case Verdict::undecided: return "UNDECIDED";
    case Verdict::report: return "REPORT";
  }
  return "?";
}

const char* check_name(CheckId id) {
  static constexpr const char* names[] = {"input_sanity",     "sparsity",         "stars",    "consistency",
                                          "thickness",        "power_protection", "secure_simplices",
                                          "topology",         "theorem",          "star_radius",
                                          "covering",         "restricted_delaunay", "tangential_equals_restricted",
                                          "intrinsic_delaunay", "restricted_equals_intrinsic"};
  const int k = check_number(id);
  return k >= 1 && k <= 15 ? names[k - 1] : "?";
}

void CheckEntry::refute(std::string why) {
  if (verdict == Verdict::report) return;
  if (verdict != Verdict::refuted) details["reason"] = std::move(why);
  verdict = Verdict::refuted;
}

void CheckEntry::undecide(std::string why) {
  if (verdict == Verdict::report || verdict == Verdict::refuted) return;
  if (verdict != Verdict::undecided) details["reason"] = std::move(why);
  verdict = Verdict::undecided;
}

void CheckEntry::add_witness(json w, std::size_t cap) {
  long total = details.value("witnesses_total", 0L) + 1;
  details["witnesses_total"] = total;
  if (witnesses.size() < cap) witnesses.push_back(std::move(w));
}

void CheckEntry::require_at_least(std::string what, double certified_lower_bound, const mpq_class& bound) {
  requirements.push_back({std::move(what), certified_lower_bound, true, exact::enclose(bound).lo, bound.get_str()});
}

void CheckEntry::require_at_most(std::string what, double certified_upper_bound, const mpq_class& bound) {
  requirements.push_back({std::move(what), certified_upper_bound, false, exact::enclose(bound).hi, bound.get_str()});
}

void CheckEntry::bound_proven_whatever_the_verdict(std::string pointer, double value, std::string why) {
  proven_whatever_the_verdict.push_back({std::move(pointer), value, std::move(why)});
}

Verdict CheckEntry::decision() const {
  if (verdict != Verdict::report || !details.is_object() || !details.contains("decision")) return verdict;
  const json& d = details["decision"];
  for (Verdict v : {Verdict::certified, Verdict::refuted, Verdict::undecided})
    if (d.is_string() && d.get<std::string>() == to_string(v)) return v;
  return Verdict::report;
}

namespace {

// Every key named certified_upper_bound or certified_lower_bound in `j`, with its JSON pointer.
void certified_keys(const json& j, const std::string& at, std::vector<std::pair<std::string, const json*>>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      std::string key;  // JSON pointer escaping (RFC 6901)
      for (char ch : k) key += ch == '~' ? std::string("~0") : ch == '/' ? std::string("~1") : std::string(1, ch);
      if (k == "certified_upper_bound" || k == "certified_lower_bound") out.emplace_back(at + "/" + key, &v);
      certified_keys(v, at + "/" + key, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) certified_keys(j[i], at + "/" + std::to_string(i), out);
  }
}

}  // namespace

std::vector<std::string> Certificate::self_check_failures() const {
  std::vector<std::string> out;
  for (const auto& c : checks) {
    if (c.decision() == Verdict::undecided) {
      std::vector<std::pair<std::string, const json*>> keys;
      certified_keys(c.margin, "/margin", keys);
      certified_keys(c.details, "/details", keys);
      certified_keys(c.witnesses, "/witnesses", keys);
      for (const auto& [at, v] : keys) {
        const std::string text = v->is_string() ? v->get<std::string>() : v->dump();
        const auto& P = c.proven_whatever_the_verdict;
        const bool ok = std::any_of(P.begin(), P.end(), [&](const auto& b) { return b.pointer == at && num(b.value) == text; });
        if (!ok)
          out.push_back("check " + std::to_string(c.number()) + " (" + c.name() + ") is UNDECIDED but prints " + at + " = " +
                        text + ", a bound its verdict does not prove");
      }
    }
    // A check that is not a claim still prints its bounds as certified when it decided CERTIFIED (decision()):
    // they must not contradict it either. Any other decision implies nothing about them.
    const bool reported = c.verdict == Verdict::report;
    if (c.decision() != Verdict::certified) continue;
    for (const auto& r : c.requirements) {
      // Written so that NaN fails too.
      const bool ok = r.at_least ? r.value >= r.bound : r.value <= r.bound;
      if (!ok)
        out.push_back("check " + std::to_string(c.number()) + " (" + c.name() + ") is CERTIFIED" +
                      (reported ? " (reported, not claimed)" : "") + " but its certified " + r.what + " " +
                      num(r.value) + (r.at_least ? " is below " : " is above ") + r.bound_text);
    }
  }
  return out;
}

void enforce_self_consistency(const Certificate& certificate) {
  const std::vector<std::string> failures = certificate.self_check_failures();
  if (failures.empty()) return;
  std::string what = "the certificate contradicts itself, so nothing is certified (please report this input): ";
  for (std::size_t i = 0; i < failures.size(); ++i) what += (i ? "; " : "") + failures[i];
  throw SelfCheckFailure(what);
}

Verdict Certificate::overall() const {
  bool undecided = false;
  for (const auto& c : checks) {
    if (!c.claimed) continue;
    if (c.verdict == Verdict::refuted) return Verdict::refuted;
    undecided = undecided || c.verdict == Verdict::undecided;
  }
  return undecided ? Verdict::undecided : Verdict::certified;
}

std::string Certificate::decided_by() const {
  // One group per verdict, the overall verdict's first; a CERTIFIED verdict has only its own group.
  const Verdict overall_verdict = overall();
  std::string out;
  for (const Verdict v : {Verdict::refuted, Verdict::undecided, Verdict::certified}) {
    std::string group;
    for (const auto& c : checks) {
      if (!c.claimed || c.verdict != v) continue;
      group += std::string(group.empty() ? "" : ", ") + "check " + std::to_string(c.number()) + " " + c.name();
      // The claim about the given complex says what it is claimed to be.
      const bool about_kind = c.claim.is_object() && c.claim.contains("kind");
      if (about_kind && c.claim["kind"] == "restricted") group += " (the complex is Del_RM(P))";
      if (about_kind && c.claim["kind"] == "intrinsic") group += " (the complex is Del_M(P))";
    }
    if (group.empty()) continue;
    out += (out.empty() ? "" : "; ") + (overall_verdict == Verdict::certified ? "" : std::string(to_string(v)) + " ") + group;
  }
  return out.empty() ? "no claimed check" : out;
}

json Certificate::to_json(bool with_times) const {
  json j;
  j["format"] = "delcert-certificate v1";
  j["tool"] = {{"name", "delcert-certify"}, {"version", "0.1.0"}};
  j["inputs"] = inputs;
  j["conventions"] = conventions;
  j["parameters"] = parameters;
  json cs = json::array();
  for (const auto& c : checks) {
    json e;
    e["id"] = c.number();
    e["name"] = c.name();
    e["verdict"] = to_string(c.verdict);
    e["claimed"] = c.claimed;
    e["summary"] = c.summary;
    e["claim"] = c.claim;
    e["margin"] = c.margin;
    e["witnesses"] = c.witnesses;
    e["details"] = c.details;
    cs.push_back(std::move(e));
  }
  j["checks"] = cs;
  json f = json::object();
  for (int k = 0; k < exact::kNumPredicateKinds; ++k) {
    const auto& c = filter.counters[k];
    if (!c.calls) continue;
    f[std::string(exact::predicate_name(static_cast<exact::PredicateKind>(k)))] = {
        {"calls", c.calls}, {"exact_fallbacks", c.filter_failures}, {"exact_zeros", c.zero_results}};
  }
  std::uint64_t calls = filter.total_calls(), fails = filter.total_failures();
  j["filter"] = {{"predicates", f},
                 {"calls", calls},
                 {"decided_by_interval_filter", calls - fails},
                 {"exact_fallbacks", fails},
                 {"fraction_decided_by_filter", calls ? num(double(calls - fails) / double(calls)) : "1"}};
  if (with_times) {
    json t = json::object();
    for (const auto& [k, v] : times) t[k] = v;
    j["times_seconds"] = t;
  }
  j["verdict"] = to_string(overall());
  return j;
}

std::string Certificate::to_text(bool with_times) const {
  using ojson = nlohmann::ordered_json;
  json j = to_json(with_times);
  auto O = [](const json& v) { return ojson::parse(v.dump()); };
  ojson o;
  for (const char* k : {"format", "tool", "verdict", "inputs", "conventions", "parameters"}) o[k] = O(j[k]);
  ojson cs = ojson::array();
  for (const auto& c : j["checks"]) {
    ojson e;
    for (const char* k : {"id", "name", "verdict", "claimed", "summary", "claim", "margin", "witnesses", "details"}) e[k] = O(c[k]);
    cs.push_back(std::move(e));
  }
  o["checks"] = cs;
  o["filter"] = O(j["filter"]);
  if (with_times) o["times_seconds"] = O(j["times_seconds"]);
  return o.dump(2) + "\n";
}

std::string num(double x) { return io::format_double(x == 0 ? 0.0 : x); }  // no "-0"

json enclosure_json(const exact::Interval& iv) { return json::array({num(iv.lo), num(iv.hi)}); }

json lower_bound_json(const exact::Interval& iv) {
  return {{"certified_lower_bound", num(iv.lo)}, {"enclosure", enclosure_json(iv)}};
}

json over_determined_json(const exact::Interval& iv) {
  return {{"over_the_determined_only", enclosure_json(iv)},
          {"bound", "none: some members were not determined, and the extremum over all of them may lie beyond"}};
}

json rational_json(const mpq_class& q) {
  std::string s = exact::rational_to_string(q);
  if (s.size() <= 40) return s;
  return {{"enclosure", enclosure_json(exact::enclose(q))}};
}

json ints_json(const std::vector<int>& v) { return json(v); }

}  // namespace delcert::certify
