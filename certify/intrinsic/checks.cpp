#include "certify/intrinsic/checks.hpp"

#include <algorithm>
#include <set>

#include "certify/restricted/checks.hpp"

namespace delcert::certify::detail {

using nlohmann::json;
using exact::Tri;

// Check 14: Del_M(P) computed (certify/intrinsic.hpp) and, with --kind intrinsic, compared with
// the given complex.
CheckEntry check_intrinsic(const IntrinsicDelaunay& D, const std::optional<io::Complex>& given, bool intrinsic_kind, int m) {
  CheckEntry im(CheckId::intrinsic_delaunay);
  im.details = {{"metric", D.metric.empty() ? json(nullptr) : json(D.metric)}};
  if (!D.computed) {
    im.undecide(D.reason);
    im.summary = "not computed: " + D.reason;
  } else {
    im.details["convention"] = D.convention;
    im.details["completeness"] = D.completeness;
    im.details["m_simplices"] = D.simplices.size();
    im.details["candidates_rejected"] = D.rejected.size();
    json und = json::array();
    for (const auto& u : D.undecided)
      if (und.size() < 10) und.push_back({{"simplex", u.simplex}, {"reason", u.reason}});
    im.details["candidates_undecided"] = D.undecided.size();
    im.details["undecided_examples"] = und;
    if (!D.complete) im.undecide("Del_M(P) not known completely: " + D.reason);
    long missing = 0, extra = 0;
    if (intrinsic_kind && given) {
      const std::set<Simplex> tops = top_simplices(*given, m);
      std::set<Simplex> certified;
      for (const auto& s : D.simplices) {
        certified.insert(s.simplex);
        if (tops.count(s.simplex)) continue;
        ++missing;
        im.refute("a simplex of Del_M(P) is missing from the complex");
        im.add_witness(s.witness);
      }
      for (const auto& r : D.rejected)
        if (tops.count(r.simplex)) {
          ++extra;
          im.refute("a simplex of the complex is not in Del_M(P)");
          im.add_witness(r.witness);
        }
      for (Simplex s : given->simplices) {
        std::sort(s.begin(), s.end());
        const bool top = static_cast<int>(s.size()) == m + 1;
        bool face = top;
        for (const auto& t : tops)
          if (!face && std::includes(t.begin(), t.end(), s.begin(), s.end())) face = static_cast<int>(s.size()) < m + 1;
        if (top ? certified.count(s) || !D.complete : face) continue;
        if (top && std::any_of(D.rejected.begin(), D.rejected.end(), [&](const auto& r) { return r.simplex == s; }))
          continue;  // already a witness
        ++extra;
        if (!D.complete) continue;
        im.refute("a simplex of the complex is not in Del_M(P)");
        im.add_witness({{"kind", top ? "not_intrinsic" : "not_a_face_of_an_m_simplex"},
                        {"simplex", s},
                        {"detail", "Del_M(P) is known completely (check 14) and does not contain it"}});
      }
      im.claim = {{"kind", "intrinsic"}, {"meaning", "the complex is the intrinsic Delaunay complex Del_M(P)"}};
      im.details["missing_simplices"] = missing, im.details["extra_simplices"] = extra;
    }
    im.summary = "Del_M of the points: " + std::to_string(D.simplices.size()) + " m-simplices certified" +
                 (D.complete ? " (all of them)" : " (maybe not all)") +
                 (intrinsic_kind && given ? "; the given complex is not it: " + std::to_string(missing) + " simplices of Del_M missing from it, " +
                                                std::to_string(extra) + " of its simplices not in Del_M"
                                          : "");
  }
  return im;
}

// Check 15: Del_RM(P) = Del_M(P) on m-simplices, decided either way with witnesses.
CheckEntry check_restricted_equals_intrinsic(const RestrictedDelaunay* R, const IntrinsicDelaunay& D) {
  CheckEntry eq(CheckId::restricted_equals_intrinsic);
  long only_rm = 0, only_m = 0;
  std::set<Simplex> rm, im, rejected;
  if (R)
    for (const auto& s : R->simplices) rm.insert(s.simplex);
  for (const auto& s : D.simplices) im.insert(s.simplex);
  for (const auto& r : D.rejected) rejected.insert(r.simplex);
  if (R && D.computed) {
    for (const auto& s : R->simplices) {
      const bool proven_out = rejected.count(s.simplex) || (D.complete && !im.count(s.simplex));
      if (!proven_out) continue;
      ++only_rm;
      eq.refute("a simplex of Del_RM(P) is not in Del_M(P)");
      json w = vertex_witness(s);
      w["not_in"] = "Del_M(P)";
      for (const auto& r : D.rejected)
        if (r.simplex == s.simplex) w["intrinsic_witness"] = r.witness;
      eq.add_witness(w);
    }
    for (const auto& s : D.simplices) {
      if (rm.count(s.simplex) || !R->covering_certified) continue;
      ++only_m;
      eq.refute("a simplex of Del_M(P) is not in Del_RM(P)");
      json w = s.witness;
      w["not_in"] = "Del_RM(P)";
      eq.add_witness(w);
    }
  }
  if (eq.verdict == Verdict::certified) {
    if (!R) eq.undecide("Del_RM(P) not computed");
    else if (!D.computed) eq.undecide("Del_M(P) not computed: " + D.reason);
    else if (!R->covering_certified) eq.undecide("Del_RM(P) not known completely: " + R->reason);
    else if (!D.complete) eq.undecide("Del_M(P) not known completely: " + D.reason);
  }
  eq.details = {{"restricted_m_simplices", rm.size()}, {"intrinsic_m_simplices", im.size()},
                {"only_in_restricted", only_rm}, {"only_in_intrinsic", only_m}};
  eq.summary = equality(eq.verdict, "Del_RM(P)", "Del_M(P)") + " (" + std::to_string(rm.size()) + " and " + std::to_string(im.size()) + " m-simplices; " +
               std::to_string(only_rm) + " only restricted, " + std::to_string(only_m) + " only intrinsic)";
  if (!D.computed) eq.summary = "not decided: Del_M(P) not computed: " + D.reason;
  return eq;
}

}  // namespace delcert::certify::detail
