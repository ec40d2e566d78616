#include "certify/restricted/restricted_recheck.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>

#include "certify/certificate.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify {

namespace {

using IA = exact::IntervalNumber;

// The boxes tried, in order: the hint, then the hint widened about its centre (a root on or just
// outside an enclosure's face, a fixed axis that must cross the box).
std::vector<exact::Box> boxes_around(const exact::Box& hint) {
  std::vector<exact::Box> out{hint};
  for (double f : {4.0, 64.0}) {
    exact::Box b = hint;
    for (auto& i : b) {
      const double c = i.midpoint(), h = 0.5 * i.width() * f + std::abs(c) * 0x1p-40 + 0x1p-1000;
      i = {c - h, c + h};
    }
    out.push_back(std::move(b));
  }
  return out;
}

// s > 0 on B, in interval arithmetic.
bool selector_positive(const exact::Polynomial& s, const exact::Box& B) {
  exact::UpwardRounding up;
  std::vector<IA> x;
  for (const auto& i : B) x.push_back(exact::to_interval_number(i));
  const IA v = s.evaluate_with<IA>(std::span<const IA>(x), [&](std::size_t t) {
    return exact::to_interval_number(exact::enclose(s.terms()[t].coefficient));
  });
  return v.inf() > 0;
}

// Every point of P outside `simplex` strictly farther than its first point c_0 from every x in B.
bool others_farther(const io::PointSet& P, const std::vector<int>& simplex, const exact::Box& B) {
  exact::UpwardRounding up;
  const int N = P.dimension;
  const auto c0 = P.point(simplex[0]);
  for (std::size_t q = 0; q < P.size(); ++q) {
    if (std::binary_search(simplex.begin(), simplex.end(), static_cast<int>(q))) continue;
    IA s(0);  // |q - c0|^2 - 2 (x - c0).(q - c0) = |x - q|^2 - |x - c0|^2
    for (int v = 0; v < N; ++v) {
      const IA d = IA(P.point(q)[v]) - IA(c0[v]);
      s += exact::square(d) - IA(2) * (exact::to_interval_number(B[v]) - IA(c0[v])) * d;
    }
    if (!(s.inf() > 0)) return false;
  }
  return true;
}

}  // namespace

std::optional<exact::Box> recheck_nearest_set(const RecheckInput& in, const std::vector<int>& simplex,
                                              const exact::Box& hint) {
  const io::PointSet& P = *in.points;
  const int N = P.dimension, k = static_cast<int>(in.equations->size()), m = N - k;
  const int j = static_cast<int>(simplex.size()) - 1;
  if (j < 0 || j > m || static_cast<int>(hint.size()) != N || !std::is_sorted(simplex.begin(), simplex.end()) ||
      std::adjacent_find(simplex.begin(), simplex.end()) != simplex.end() || simplex.front() < 0 ||
      static_cast<std::size_t>(simplex.back()) >= P.size() ||
      std::any_of(hint.begin(), hint.end(), [](const exact::Interval& i) { return !i.is_finite() || i.lo > i.hi; }))
    return std::nullopt;
  // The rows that do not depend on the box: F, then the equidistance rows, exactly.
  std::vector<exact::Polynomial> rows(in.equations->begin(), in.equations->end());
  const std::vector<mpq_class> c0 = exact::to_rational(P.point(simplex[0]));
  mpq_class c0_2 = 0;
  for (const auto& v : c0) c0_2 += v * v;
  for (int i = 1; i <= j; ++i) {
    const std::vector<mpq_class> ci = exact::to_rational(P.point(simplex[i]));
    std::vector<mpq_class> linear(N);
    mpq_class ci_2 = 0;
    for (int v = 0; v < N; ++v) linear[v] = 2 * (ci[v] - c0[v]), ci_2 += ci[v] * ci[v];
    rows.push_back(exact::Polynomial::affine(c0_2 - ci_2, linear));
  }
  // The sets A of m - j fixed axes, as bit masks in increasing order.
  std::vector<unsigned> axes;
  for (unsigned A = 0; A < (1u << N); ++A)
    if (__builtin_popcount(A) == m - j) axes.push_back(A);
  for (const exact::Box& X0 : boxes_around(hint)) {
    for (unsigned A : axes) {
      std::vector<exact::Polynomial> system = rows;
      exact::Box X = X0;
      for (int a = 0; a < N; ++a) {
        if (!(A >> a & 1)) continue;
        const double t = X0[a].midpoint();
        std::vector<mpq_class> linear(N, mpq_class(0));
        linear[a] = 1;
        system.push_back(exact::Polynomial::affine(-mpq_class(t), linear));
        if (!(X[a].lo < t && t < X[a].hi)) {  // the box needs an interior on that axis
          const double h = std::abs(t) * 0x1p-40 + 0x1p-1000;
          X[a] = {t - h, t + h};
        }
      }
      const exact::KrawczykResult kr = exact::krawczyk(exact::SquareSystem(std::move(system)), X);
      const exact::Box* root = kr.status == exact::RootStatus::unique_root ? &kr.box
                               : kr.nearby_root                              ? &*kr.nearby_root
                                                                             : nullptr;
      if (!root) continue;
      if (in.selector && !selector_positive(*in.selector, *root)) continue;
      if (!others_farther(P, simplex, *root)) continue;
      return *root;
    }
  }
  return std::nullopt;
}

exact::Box require_nearest_set(const RecheckInput& in, const std::vector<int>& simplex, const exact::Box& hint,
                               const std::string& what) {
  if (auto B = recheck_nearest_set(in, simplex, hint)) return *B;
  std::string s;
  for (int v : simplex) s += (s.empty() ? "" : ", ") + std::to_string(v);
  throw WitnessRecheckFailure(what + ": the witness for the simplex [" + s +
                              "] fails its independent re-check (no point of M whose nearest sample points are "
                              "exactly these could be proven near its enclosure); no verdict rests on it");
}

void require_completeness(const RecheckInput& in, const RestrictedDelaunay& R, const std::string& what) {
  auto fail = [&](const std::string& why) {
    throw WitnessRecheckFailure(what + ": it rests on Del_RM(P) being known completely, but " + why +
                                "; no verdict rests on it");
  };
  if (R.cells.size() != in.points->size()) fail("not every point has a cell");
  double c = 0, r = INFINITY;
  for (std::size_t p = 0; p < R.cells.size(); ++p) {
    const RestrictedCellReport& cell = R.cells[p];
    if (!cell.complete || !cell.undecided.empty())
      fail("the cell of point " + std::to_string(p) + " is not complete");
    c = std::max(c, cell.covering_bound), r = std::min(r, cell.graph_radius);
  }
  if (!(c < r)) fail("the covering bound " + num(c) + " is not below every analysed radius (" + num(r) + ")");
  if (!R.cross_check_failures.empty()) fail("the cells contradict each other (cross-check failures)");
  // An anchor: a re-checked point of M within r of its nearest sample point (hence within c).
  std::vector<const RestrictedSimplex*> anchors;
  for (const auto& s : R.simplices) anchors.push_back(&s);
  for (const auto& s : R.lower_faces) anchors.push_back(&s);
  for (std::size_t i = 0; i < anchors.size() && i < 3; ++i) {
    const auto B = recheck_nearest_set(in, anchors[i]->simplex, anchors[i]->vertex.x);
    if (!B) continue;
    exact::UpwardRounding up;
    IA d(0);
    const auto c0 = in.points->point(anchors[i]->simplex[0]);
    for (std::size_t v = 0; v < B->size(); ++v) d += exact::square(exact::to_interval_number((*B)[v]) - IA(c0[v]));
    if (exact::sqrt(d).sup() < r) return;
  }
  fail(anchors.empty() ? "no restricted Voronoi vertex or face point anchors the covering argument"
                       : "no anchor of the covering argument passes its re-check");
}

}  // namespace delcert::certify
