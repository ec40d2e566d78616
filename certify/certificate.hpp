// The certificate (docs/design.md §9, docs/certificate.md): input hashes, conventions, one entry per check, filter
// statistics, times and the overall verdict, written as JSON ("delcert-certificate v1").
// docs/certificate.md describes every field.
#pragma once

#include <gmpxx.h>

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"

namespace delcert::certify {

// CERTIFIED: proven. REFUTED: proven false, with a witness. UNDECIDED: neither, with the reason.
// REPORT: informational (measured values, theorem hypotheses); never changes the overall verdict.
enum class Verdict { certified, refuted, undecided, report };
const char* to_string(Verdict v);

// The checks, by their number in the certificate (certify/certify.hpp lists what each decides).
enum class CheckId {
  input_sanity = 1, sparsity = 2, stars = 3, consistency = 4, thickness = 5,
  power_protection = 6, secure_simplices = 7, topology = 8, theorem = 9, star_radius = 10,
  covering = 11, restricted_delaunay = 12, tangential_equals_restricted = 13, intrinsic_delaunay = 14,
  restricted_equals_intrinsic = 15,
};
// The number and the name written in the certificate ("id", "name").
constexpr int check_number(CheckId id) { return static_cast<int>(id); }
const char* check_name(CheckId id);

struct CheckEntry {
  explicit CheckEntry(CheckId check) : id(check) {}

  CheckId id;
  Verdict verdict = Verdict::certified;
  std::string summary;                                 // one human-readable line
  nlohmann::json claim;                                // the claim decided, or null
  nlohmann::json margin;                               // certified bounds, or null
  nlohmann::json witnesses = nlohmann::json::array();  // small, re-checkable by hand
  nlohmann::json details = nlohmann::json::object();
  // A claim of this input: its verdict counts in the overall verdict. A check that is not a claim of the mode
  // (claimed_checks in certify.hpp) is computed and reported: verdict REPORT, its own decision in
  // details.decision. Written in the certificate as "claimed".
  bool claimed = true;

  // Lowers the verdict: refuted beats undecided beats certified (report stays report).
  void refute(std::string why);
  void undecide(std::string why);
  // Appends a witness while keeping the list short; the total is counted in details.
  void add_witness(nlohmann::json w, std::size_t cap = 20);

  // The internal consistency guard. A check records here what its CERTIFIED verdict implies about a certified bound
  // it prints: "this lower bound is at least that", "this upper bound is at most that". The bounds and the verdicts
  // are computed by different code (enclosures versus exact signs), so a violated requirement means the program
  // itself is wrong: delcert-certify then stops with an internal error (exit 3) and certifies nothing. `bound` is
  // exact; the comparison uses its enclosure's end on the permissive side, so a correct run never trips it.
  struct Requirement {
    std::string what;   // the printed quantity, e.g. "min_power_margin"
    double value = 0;   // the certified bound printed in the certificate
    bool at_least = true;
    double bound = 0;   // the enclosure end of the exact requirement (lo for at_least, hi for at_most)
    std::string bound_text;
  };
  std::vector<Requirement> requirements;
  void require_at_least(std::string what, double certified_lower_bound, const mpq_class& bound);
  void require_at_most(std::string what, double certified_upper_bound, const mpq_class& bound);

  // The second half of the guard: the bounds an UNDECIDED check may print. A key named `certified_upper_bound` or
  // `certified_lower_bound` is a proven bound, or it is not printed; but what an UNDECIDED check computed is often
  // proven only under the argument it could not complete (check 11's upper bound over the decided boxes). So an
  // entry whose decision is UNDECIDED (decision() below) may print such a key only where it registered the printed
  // value here as proven whatever its verdict, with the reason (e.g. the distance to P of a certified restricted
  // Voronoi vertex). `pointer` is the key's JSON pointer in the entry ("/margin/covering_radius/certified_lower_bound");
  // the guard walks the whole entry (margin, details, witnesses) and fails a key that is not registered or whose
  // printed text is not num(value).
  struct ProvenBound {
    std::string pointer;
    double value = 0;
    std::string why;
  };
  std::vector<ProvenBound> proven_whatever_the_verdict;
  void bound_proven_whatever_the_verdict(std::string pointer, double value, std::string why);
  // The verdict, or for a REPORT entry that records one (details.decision, a check that is not claimed) that one.
  Verdict decision() const;

  int number() const { return check_number(id); }
  const char* name() const { return check_name(id); }
};

struct Certificate {
  nlohmann::json inputs = nlohmann::json::object();
  nlohmann::json conventions = nlohmann::json::object();
  nlohmann::json parameters = nlohmann::json::object();
  std::vector<CheckEntry> checks;
  exact::FilterStats filter;
  std::vector<std::pair<std::string, double>> times;  // seconds, wall clock
  std::vector<std::vector<int>> restricted_complex;  // Del_RM(P) when check 12 proves it complete and pure; not written

  // Over the claimed checks: REFUTED if any is refuted, else UNDECIDED if any is undecided, else
  // CERTIFIED. REPORT entries and checks that are not claims never change it.
  Verdict overall() const;
  // The claims that decided overall(), for the line before the verdict: the refuted ones first,
  // then the undecided, then the certified ("check 12 restricted_delaunay (the complex is
  // Del_RM(P))", ...).
  std::string decided_by() const;
  // One line per violated requirement of a check decided CERTIFIED (decision(): claimed, or only reported, since a
  // reported bound is printed as certified too; see CheckEntry::requirements) and per certified bound a check decided
  // UNDECIDED prints without having registered it as proven whatever the verdict
  // (CheckEntry::proven_whatever_the_verdict); empty when the certificate is consistent with itself.
  std::vector<std::string> self_check_failures() const;
  // `with_times = false` leaves the only non-deterministic field out (byte-identical reruns).
  nlohmann::json to_json(bool with_times = true) const;
  // The JSON text written by delcert-certify: fields in a fixed reading order, 2-space indent.
  std::string to_text(bool with_times = true) const;
};

// Thrown by enforce_self_consistency: the program contradicted itself, so nothing is certified
// (delcert-certify reports an internal error and exits with status 3).
class SelfCheckFailure : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};
// Throws SelfCheckFailure listing Certificate::self_check_failures() when there are any.
void enforce_self_consistency(const Certificate& certificate);

// JSON helpers shared by the checks. Doubles are printed with the shortest text that reads back
// to the same double, so a printed bound is exactly the bound that was certified.
std::string num(double x);
nlohmann::json enclosure_json(const exact::Interval& iv);
// {"certified_lower_bound": lo, "enclosure": [lo, hi]} for a certified quantity.
nlohmann::json lower_bound_json(const exact::Interval& iv);
// An extremum taken over the determined members of a set only (a check UNDECIDED because some were not determined):
// {"over_the_determined_only": [lo, hi], "bound": "none ..."}, with no certified_* key, since it bounds nothing.
nlohmann::json over_determined_json(const exact::Interval& iv);
// An exact rational: its text when short, else its enclosure.
nlohmann::json rational_json(const mpq_class& q);
nlohmann::json ints_json(const std::vector<int>& v);

}  // namespace delcert::certify
