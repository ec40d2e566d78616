#include "core/refine/intrinsic_repair.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>

// The certifier's engines (certify/ is being split into subfolders: these paths follow it at merge).
#include "certify/certificate.hpp"
#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::refine {

namespace {

using Simplex = std::vector<int>;

std::vector<double> midpoint(const exact::Box& box) {
  std::vector<double> x;
  for (const auto& iv : box) x.push_back(0.5 * (iv.lo + iv.hi));
  return x;
}

// The intrinsic Voronoi vertex a Del_M witness gives, in ambient coordinates (empty when the
// witness has none): "vertex" (an ambient box, products of spheres) or "centre_angles" (angles
// of a flat torus; x_{2i-1} = r_i cos θ_i, x_{2i} = r_i sin θ_i). Sphere and SO(3) witnesses name
// a cap, not a point: there Del_M = Del_RM, and the restricted vertex serves.
std::vector<double> intrinsic_vertex(const nlohmann::json& w, const certify::VerifiedShape& shape) {
  std::vector<double> x;
  auto mid = [](const nlohmann::json& pair) {
    auto num = [](const nlohmann::json& v) { return v.is_string() ? std::stod(v.get<std::string>()) : v.get<double>(); };
    return 0.5 * (num(pair.at(0)) + num(pair.at(1)));
  };
  try {
    if (w.contains("vertex")) {
      for (const auto& c : w.at("vertex")) x.push_back(mid(c));
    } else if (w.contains("centre_angles") && shape.shape && shape.shape->kind == io::ShapeSpec::Kind::product_of_circles) {
      const auto& angles = w.at("centre_angles");
      if (angles.size() != shape.shape->radii.size()) return {};
      for (std::size_t i = 0; i < angles.size(); ++i) {
        const double r = shape.shape->radii[i].get_d(), t = mid(angles[i]);
        x.push_back(r * std::cos(t));
        x.push_back(r * std::sin(t));
      }
    }
  } catch (const std::exception&) {
    return {};  // a witness of another form: no location
  }
  return x;
}

}  // namespace

DelMComparison compare_with_del_m(const io::ManifoldSpec& spec, const io::PointSet& points,
                                  const std::vector<std::vector<int>>& tangential_simplices, int threads) {
  const auto started = std::chrono::steady_clock::now();
  DelMComparison out;
  const int m = spec.intrinsic_dimension, N = spec.ambient_dimension;
  std::set<Simplex> T;
  for (Simplex s : tangential_simplices)
    if (static_cast<int>(s.size()) == m + 1) {
      std::sort(s.begin(), s.end());
      T.insert(std::move(s));
    }
  out.tangential = T.size();
  const std::vector<Simplex> expected(T.begin(), T.end());
  const certify::detail::PointGrid grid(points, m);
  const certify::VerifiedShape shape = certify::verify_declared_shape(spec);

  // Del_RM(P): check 12's engine with check 12's options (certify/certify.cpp).
  std::map<Simplex, std::vector<double>> R;  // m-simplex -> its restricted Voronoi vertex
  std::optional<certify::RestrictedDelaunay> rd;
  if (m <= 3) {
    const exact::ImplicitSystem system(spec.equations, N);
    certify::RestrictedDelaunayOptions ro;
    ro.threads = threads;
    ro.expected = &expected;
    if (spec.reach && N - m >= 4) ro.cell.reach = std::nextafter(std::sqrt(spec.reach->squared.get_d()), 0.0) * (1 - 1e-12);
    ro.cell.selector = spec.selector ? &*spec.selector : nullptr;
    if (shape.shape && (shape.shape->kind == io::ShapeSpec::Kind::so3 || shape.shape->kind == io::ShapeSpec::Kind::product_of_circles))
      ro.cell.shape = &*shape.shape;
    rd = certify::compute_restricted_delaunay(system, points, grid, ro);
    out.restricted_computed = true;
    for (const auto& s : rd->simplices) R.emplace(s.simplex, midpoint(s.vertex.x));
    out.restricted = R.size();
  }

  // Del_M(P): checks 14-15's engine, candidates Del_TM and Del_RM.
  std::vector<Simplex> candidates = expected;
  for (const auto& [s, x] : R) candidates.push_back(s);
  const certify::IntrinsicDelaunay D = certify::compute_intrinsic_delaunay(spec, points, grid, candidates, threads);
  out.intrinsic_computed = D.computed;
  if (!D.computed) out.intrinsic_reason = D.reason;
  std::map<Simplex, const nlohmann::json*> Min;
  std::map<Simplex, std::string> Mout;  // rejected or undecided, with why
  if (D.computed) {
    for (const auto& s : D.simplices) Min.emplace(s.simplex, &s.witness);
    for (const auto& r : D.rejected) Mout.emplace(r.simplex, "rejected by Del_M: " + r.witness.dump());
    for (const auto& u : D.undecided) Mout.emplace(u.simplex, "undecided in Del_M: " + u.reason);
    out.intrinsic = Min.size();
  }

  std::set<Simplex> all = T;
  for (const auto& [s, x] : R) all.insert(s);
  for (const auto& [s, w] : Min) all.insert(s);
  for (const Simplex& s : all) {
    const bool t = T.count(s) > 0;
    const bool r = out.restricted_computed ? R.count(s) > 0 : t;
    const bool i = out.intrinsic_computed ? Min.count(s) > 0 : t;
    const auto why = Mout.find(s);
    if (t && r && i && why == Mout.end()) continue;
    DelMBreak b;
    b.simplex = s;
    std::string in;
    for (const auto& [yes, name] : {std::pair{t, "Del_TM"}, std::pair{r, "Del_RM"}, std::pair{i, "Del_M"}})
      if (yes) in += (in.empty() ? "" : ", ") + std::string(name);
    b.what = "in " + (in.empty() ? std::string("none") : in);
    if (!(t && r && i)) {
      std::string not_in;
      for (const auto& [yes, name] : {std::pair{t, "Del_TM"}, std::pair{r, "Del_RM"}, std::pair{i, "Del_M"}})
        if (!yes) not_in += (not_in.empty() ? "" : ", ") + std::string(name);
      b.what += ", not in " + not_in;
    }
    if (why != Mout.end()) b.what += " (" + why->second + ")";
    if (auto it = R.find(s); it != R.end())
      b.location = it->second;
    else if (auto jt = Min.find(s); jt != Min.end())
      b.location = intrinsic_vertex(*jt->second, shape);
    out.breaks.push_back(std::move(b));
  }

  if (rd) {
    for (const auto& f : rd->lower_faces)
      out.breaks.push_back({f.simplex, "a face of no m-simplex in Del_RM (Del_RM not pure)", midpoint(f.vertex.x)});
    for (const auto& c : rd->cross_check_failures) {
      DelMBreak b{c.simplex, "restricted engine cross-check: found at " + std::to_string(c.found_at) + ", missed at " +
                                 std::to_string(c.missed_at), {}};
      if (auto it = R.find(c.simplex); it != R.end()) b.location = it->second;
      out.breaks.push_back(std::move(b));
    }
    for (int p : rd->incomplete_points) {
      const certify::RestrictedCellReport& cell = rd->cells[p];
      std::size_t before = out.breaks.size();
      for (const auto* boxes : {&cell.undecided, &cell.unresolved_faces})
        for (const auto& u : *boxes)
          out.breaks.push_back({u.candidates, "undecided in the restricted cell of point " + std::to_string(p) + ": " + u.reason,
                                u.location});
      if (out.breaks.size() == before)
        out.breaks.push_back({{p}, "restricted cell of point " + std::to_string(p) + " incomplete: " + cell.reason,
                              cell.covering_location});
    }
    if (out.breaks.empty() && !rd->covering_certified) {
      std::vector<double> at;
      Simplex s;
      if (rd->covering_point >= 0) at = rd->cells[rd->covering_point].covering_location, s = {rd->covering_point};
      out.breaks.push_back({s, "Del_RM not known completely: " + rd->reason, at});
    }
  }
  if (out.breaks.empty() && D.computed && !D.complete) out.breaks.push_back({{}, "Del_M not known completely: " + D.reason, {}});
  std::stable_sort(out.breaks.begin(), out.breaks.end(), [](const DelMBreak& a, const DelMBreak& b) {
    if (a.simplex.empty() != b.simplex.empty()) return b.simplex.empty();
    return a.simplex < b.simplex;
  });
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

WholeVerdict certifies_whole(const certify::Certificate& certificate) {
  using certify::CheckId;
  using certify::Verdict;
  WholeVerdict v;
  // Check 12 not computed for m > 3: then check 15 (Del_RM = Del_M) cannot be decided either.
  bool rm_not_built = false;
  for (const certify::CheckEntry& e : certificate.checks)
    if (e.id == CheckId::restricted_delaunay && e.summary.find("built for m <= 3") != std::string::npos) rm_not_built = true;
  for (const certify::CheckEntry& e : certificate.checks) {
    if (!e.claimed || e.verdict == Verdict::certified) continue;
    const std::string line = "check " + std::to_string(e.number()) + " " + e.name() + " " + certify::to_string(e.verdict) +
                             ": " + e.summary;
    // Not decidable on this manifold, whatever the output: Del_M without a closed-form metric (the
    // intrinsic engine did not compute it), Del_RM for m > 3 (the restricted engine is built for m <= 3).
    const bool no_del_m = (e.id == CheckId::intrinsic_delaunay && e.summary.rfind("not computed: ", 0) == 0) ||
                          (e.id == CheckId::restricted_equals_intrinsic &&
                           e.summary.find("Del_M(P) not computed") != std::string::npos);
    const bool no_del_rm = (e.id == CheckId::covering || e.id == CheckId::restricted_delaunay ||
                            e.id == CheckId::tangential_equals_restricted || e.id == CheckId::restricted_equals_intrinsic) &&
                           (e.summary.find("built for m <= 3") != std::string::npos ||
                            (rm_not_built && e.id == CheckId::restricted_equals_intrinsic));
    if (e.verdict == Verdict::undecided && (no_del_m || no_del_rm))
      v.not_decidable.push_back(line);
    else
      v.failing.push_back(line);
  }
  v.certified = v.failing.empty();
  return v;
}

}  // namespace delcert::refine
