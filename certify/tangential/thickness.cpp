#include "certify/tangential/thickness.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "certify/detail/parallel.hpp"
#include "certify/tangential/topology.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "exact/simplex_predicates.hpp"

namespace delcert::certify {

using nlohmann::json;

namespace {

// Floating-point Upsilon^2 of a j-simplex (a guess that only selects which face to certify).
// Fixed-size scratch (no allocation per face); j <= kMaxJ, larger j take the same code on vectors.
constexpr int kMaxJ = 7;

double approx_thickness2(const io::PointSet& P, const int* v, int j) {
  const int N = P.dimension, V = j + 1;
  // Larger faces are refused by exact::thickness_sign / thickness_squared_exact anyway.
  if (j > kMaxJ) return 0.0;
  std::array<double, (kMaxJ + 1) * (kMaxJ + 1)> d;
  std::fill(d.begin(), d.begin() + V * V, 0.0);
  double longest = 0;
  for (int a = 0; a < V; ++a)
    for (int b = a + 1; b < V; ++b) {
      double s = 0;
      for (int k = 0; k < N; ++k) s += (P.point(v[a])[k] - P.point(v[b])[k]) * (P.point(v[a])[k] - P.point(v[b])[k]);
      d[a * V + b] = d[b * V + a] = s;
      longest = std::max(longest, s);
    }
  auto gram = [&](const int* idx, int count) {
    const int n = count - 1;
    std::array<double, kMaxJ * kMaxJ> g;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) g[a * n + b] = 0.5 * (d[idx[0] * V + idx[a + 1]] + d[idx[0] * V + idx[b + 1]] - d[idx[a + 1] * V + idx[b + 1]]);
    // Gaussian elimination with partial pivoting.
    double det = 1;
    for (int c = 0; c < n; ++c) {
      int piv = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(g[r * n + c]) > std::abs(g[piv * n + c])) piv = r;
      if (g[piv * n + c] == 0) return 0.0;
      if (piv != c) {
        for (int k = 0; k < n; ++k) std::swap(g[c * n + k], g[piv * n + k]);
        det = -det;
      }
      det *= g[c * n + c];
      for (int r = c + 1; r < n; ++r) {
        double f = g[r * n + c] / g[c * n + c];
        for (int k = c; k < n; ++k) g[r * n + k] -= f * g[c * n + k];
      }
    }
    return det;
  };
  std::array<int, kMaxJ + 1> all{};
  for (int i = 0; i < V; ++i) all[i] = i;
  double gt = gram(all.data(), V), best = INFINITY;
  for (int l = 0; l < V; ++l) {
    std::array<int, kMaxJ + 1> f{};
    int nf = 0;
    for (int i = 0; i < V; ++i)
      if (i != l) f[nf++] = i;
    double gf = gram(f.data(), nf);
    best = std::min(best, gf > 0 ? gt / gf : 0.0);
  }
  return longest > 0 ? std::max(0.0, best) / (double(j) * j * longest) : 0.0;
}

// The coordinates of a j-face's vertices: in place for j <= kMaxJ (no allocation per face), in a
// vector above (faces the exact predicates refuse with their own message).
struct VertexPointers {
  std::array<const double*, kMaxJ + 1> p{};
  std::vector<const double*> big;
  int n = 0;
  operator std::span<const double* const>() const {
    return n <= kMaxJ + 1 ? std::span<const double* const>(p.data(), n) : std::span<const double* const>(big);
  }
};
VertexPointers vertex_pointers(const io::PointSet& P, const int* v, int j) {
  VertexPointers out;
  out.n = j + 1;
  for (int i = 0; i <= j; ++i) {
    if (j <= kMaxJ) out.p[i] = P.point(v[i]).data();
    else out.big.push_back(P.point(v[i]).data());
  }
  return out;
}

}  // namespace

ThicknessResult check_thickness(const io::PointSet& P, const FaceLattice& L, int m, const mpq_class* gamma0, int threads,
                                exact::FilterStats& stats, bool force_exact) {
  ThicknessResult R;
  CheckEntry& e = R.entry;
  const int N = P.dimension;
  std::vector<exact::FilterContext> ctx(std::max(1, threads));
  for (auto& c : ctx) c.force_exact = force_exact;
  json minima = json::object();
  std::vector<std::vector<char>> thin(std::max(0, L.dimension + 1));  // per face: Upsilon < Gamma0^j
  long thin_count = 0;
  for (int j = 2; j <= L.dimension; ++j) {
    const std::size_t n = L.count(j);
    const int* faces = L.flat[j].data();
    thin[j].assign(n, 0);
    if (gamma0) {
      mpq_class g2 = 1;
      for (int k = 0; k < 2 * j; ++k) g2 *= *gamma0;  // Gamma0^(2j): Upsilon >= Gamma0^j, squared
      exact::RationalConstant gc(g2);
      detail::parallel_for(n, threads, [&](std::size_t f, int t) {
        auto v = vertex_pointers(P, faces + f * (j + 1), j);
        thin[j][f] = exact::thickness_sign(v, N, gc, ctx[t]) < 0;
      });
      thin_count += std::count(thin[j].begin(), thin[j].end(), 1);
    }
    // Certified minimum: guess the thinnest face in floating point, take its exact Upsilon^2,
    // and prove every face thicker than slightly less than that (one predicate per face).
    std::vector<double> approx(n);
    detail::parallel_for(n, threads, [&](std::size_t f, int) { approx[f] = approx_thickness2(P, faces + f * (j + 1), j); });
    std::size_t arg = std::min_element(approx.begin(), approx.end()) - approx.begin();
    exact::Interval best{0, 0};
    for (int round = 0; round < 8 && n; ++round) {
      mpq_class exact2 = exact::thickness_squared_exact(vertex_pointers(P, faces + arg * (j + 1), j), N);
      exact::Interval enc = exact::enclose(exact2);
      double lo = enc.lo * (1 - 0x1p-20);  // a double: an exact rational threshold below Upsilon(arg)^2
      exact::RationalConstant thr{exact::to_rational(lo)};
      std::vector<char> below(n, 0);
      detail::parallel_for(n, threads, [&](std::size_t f, int t) {
        if (f != arg) below[f] = exact::thickness_sign(vertex_pointers(P, faces + f * (j + 1), j), N, thr, ctx[t]) <= 0;
      });
      auto it = std::find(below.begin(), below.end(), 1);
      best = {lo, enc.hi};
      if (it == below.end() || lo <= 0) break;
      arg = static_cast<std::size_t>(it - below.begin());  // a thinner face: certify from it
      if (round == 7) best.lo = 0;                          // give up tightening: 0 is a valid bound
    }
    // Upsilon = sqrt of Upsilon^2: bounds rounded outward.
    exact::Interval ups{best.lo > 0 ? std::nextafter(std::sqrt(best.lo), 0.0) : 0.0, std::nextafter(std::sqrt(best.hi), INFINITY)};
    if (gamma0 && n && !std::count(thin[j].begin(), thin[j].end(), 1)) {
      // Every j-face was proven to have Upsilon^2 >= gamma0^(2j) exactly, so gamma0^j (rounded
      // down) is a certified lower bound too; the tightening above stops 2^-20 short of it.
      mpq_class gj = 1;
      for (int k = 0; k < j; ++k) gj *= *gamma0;
      ups.lo = std::max(ups.lo, exact::enclose(gj).lo);
      // The consistency guard (certificate.hpp): the thinnest face's Upsilon, enclosed from its
      // exact value independently of the sign predicates, cannot be below gamma0^j.
      e.require_at_least("upper end of the thinnest " + std::to_string(j) + "-face's Upsilon", ups.hi, gj);
    }
    std::vector<int> face(faces + arg * (j + 1), faces + arg * (j + 1) + j + 1);
    if (n) minima[std::to_string(j)] = {{"min_thickness", lower_bound_json(ups)}, {"simplex", face}, {"faces", n}};
    if (j == m && n) R.min_top = ups;
  }
  e.margin = minima;
  e.details["edges_have_thickness_1"] = true;
  std::string mins = R.min_top.lo >= 0 ? "min Upsilon of m-simplices in [" + num(R.min_top.lo) + ", " + num(R.min_top.hi) + "]"
                                        : "no m-simplex";
  for (auto& c : ctx) stats.merge(c.stats);
  if (!gamma0) {
    e.verdict = Verdict::report;
    e.summary = mins + " (no gamma0 claim)";
    return R;
  }
  e.claim = {{"gamma0", exact::rational_to_string(*gamma0)},
             {"meaning", "every j-face t of every simplex has Upsilon(t) >= gamma0^j (gamma0-good)"}};
  // Flakes: thin faces whose proper faces (of dimension >= 2) are all thick enough.
  long flakes = 0;
  json flake_examples = json::array();
  for (int j = 2; j <= L.dimension; ++j)
    for (std::size_t f = 0; f < L.count(j); ++f) {
      if (!thin[j][f]) continue;
      const int* v = &L.flat[j][f * (j + 1)];
      bool proper_good = true;
      for (unsigned mask = 1; mask + 1 < (1u << (j + 1)) && proper_good; ++mask) {
        int k = __builtin_popcount(mask) - 1;
        if (k < 2) continue;
        std::vector<int> sub;
        for (int i = 0; i <= j; ++i)
          if (mask >> i & 1) sub.push_back(v[i]);
        proper_good = !thin[k][L.find(k, sub.data())];
      }
      std::vector<int> face(v, v + j + 1);
      if (proper_good) {
        ++flakes;
        if (flake_examples.size() < 10) flake_examples.push_back(face);
      }
      exact::Interval u2 = exact::enclose(exact::thickness_squared_exact(vertex_pointers(P, v, j), N));
      mpq_class g2 = 1;
      for (int k = 0; k < 2 * j; ++k) g2 *= *gamma0;
      e.add_witness({{"kind", "thin_face"},
                     {"simplex", face},
                     {"dimension", j},
                     {"thickness_squared", enclosure_json(u2)},
                     {"gamma0_power_2j", rational_json(g2)},
                     {"exact_sign", "Upsilon^2 - gamma0^(2j) < 0"}});
    }
  e.details["thin_faces"] = thin_count;
  e.details["flakes"] = flakes;
  e.details["flake_examples"] = flake_examples;
  if (thin_count) {
    e.refute("a face is thinner than gamma0^j");
    e.summary = std::to_string(thin_count) + " face(s) thinner than gamma0^j (" + std::to_string(flakes) + " flakes); " + mins;
  } else {
    e.summary = "every simplex is gamma0-good for gamma0 = " + exact::rational_to_string(*gamma0) + "; " + mins;
  }
  return R;
}

}  // namespace delcert::certify
