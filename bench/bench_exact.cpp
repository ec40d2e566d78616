// Benchmark of the filtered exact predicates (issue 3): ns per call, filtered vs exact-only vs
// a plain double evaluation of the same expression (exact/detail/kernels.hpp instantiated with
// double), on random and on exactly degenerate input, for the power test (predicate 2) and the
// thickness test (predicate 4) at (N, m) = (4, 2), (6, 3), (9, 3). Prints JSON on stdout.
//
// Power test variants:
//   query    TangentCell::power_sign(q): a prepared cell tested against one more point (the
//            gift-wrapping inner loop); double baseline: power_value<M, double>.
//   cell     TangentChart::cell(...) + one power_sign: cell preparation from cached chart rows;
//            double baseline: power_cell + power_value in double.
//   raw      tangent_power_sign(T, points, q): chart rows recomputed from raw points at every
//            call; double baseline: chart_row + power_cell + power_value in double.
// Each filtered variant is timed twice: with one UpwardRounding for the whole batch ("batched")
// and without (each call switches the rounding mode itself).
//
// Usage: bench_exact [--quick]
#include <gmpxx.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "exact/detail/kernels.hpp"
#include "exact/predicates.hpp"

using namespace delcert;
using namespace delcert::exact;

namespace {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : e_(seed) {}
  double uniform() { return static_cast<double>(e_() >> 11) * 0x1.0p-53; }
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  int integer(int lo, int hi) { return lo + static_cast<int>(e_() % static_cast<std::uint64_t>(hi - lo + 1)); }
  // A dyadic number in [-1, 1) with `bits` fractional bits.
  double dyadic(int bits) { return std::ldexp(static_cast<double>(integer(-(1 << bits), (1 << bits) - 1)), -bits); }

 private:
  std::mt19937_64 e_;
};

struct Config {
  std::string manifold;
  int N, m;
  std::vector<std::string> equations;
};

std::vector<Config> configs() {
  return {
      {"clifford-torus-2", 4, 2, {"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}},
      {"clifford-torus-3", 6, 3, {"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5^2 + x6^2 - 1"}},
      {"so3",
       9,
       3,
       {"x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 + x6^2 - 1", "x7^2 + x8^2 + x9^2 - 1", "x1*x4 + x2*x5 + x3*x6",
        "x1*x7 + x2*x8 + x3*x9", "x4*x7 + x5*x8 + x6*x9"}},
  };
}

// A point on M (rounded): products of circles or a rotation matrix.
std::vector<double> on_manifold(const Config& c, Rng& rng) {
  std::vector<double> x(c.N);
  if (c.manifold != "so3") {
    for (int i = 0; i < c.N / 2; ++i) {
      const double a = 6.283185307179586 * rng.uniform();
      x[2 * i] = std::cos(a);
      x[2 * i + 1] = std::sin(a);
    }
  } else {
    double q[4], n = 0;
    for (double& v : q) {
      v = rng.normal();
      n += v * v;
    }
    for (double& v : q) v /= std::sqrt(n);
    const double w = q[0], a = q[1], b = q[2], d = q[3];
    x = {1 - 2 * (b * b + d * d), 2 * (a * b - d * w), 2 * (a * d + b * w),
         2 * (a * b + d * w),     1 - 2 * (a * a + d * d), 2 * (b * d - a * w),
         2 * (a * d - b * w),     2 * (b * d + a * w), 1 - 2 * (a * a + b * b)};
  }
  return x;
}

bool is_exact_double(const mpq_class& q) {
  if (!is_dyadic(q)) return false;
  const double d = q.get_d();
  return std::isfinite(d) && to_rational(d) == q;
}

// CPU time of the calling thread (the machine is shared: wall time would count other
// processes' time slices).
double thread_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Median ns (thread CPU time) per call of `body(i)` over `n` cases; each repetition runs the
// cases `reps` times, with reps chosen so that a repetition takes at least ~20 ms (2 ms with
// --quick); 9 repetitions (3 with --quick).
double time_ns(std::size_t n, bool quick, const std::function<void(std::size_t)>& body) {
  std::size_t reps = 1;
  for (;;) {
    const double t0 = thread_seconds();
    for (std::size_t r = 0; r < reps; ++r)
      for (std::size_t i = 0; i < n; ++i) body(i);
    const double ms = 1e3 * (thread_seconds() - t0);
    if (ms >= (quick ? 2.0 : 20.0) || reps > (1u << 20)) break;
    reps *= 2;
  }
  std::vector<double> samples;
  for (int k = 0; k < (quick ? 3 : 9); ++k) {
    const double t0 = thread_seconds();
    for (std::size_t r = 0; r < reps; ++r)
      for (std::size_t i = 0; i < n; ++i) body(i);
    samples.push_back(1e9 * (thread_seconds() - t0) / double(reps * n));
  }
  std::sort(samples.begin(), samples.end());
  return samples[samples.size() / 2];
}

volatile long g_sink = 0;
inline void sink(long v) { g_sink = g_sink + v; }

// Input for the power benchmarks at one point p: neighbours, cells and queries.
struct PowerInput {
  std::vector<double> p;
  std::vector<std::vector<double>> points;  // chart points (local index i + 1)
  std::vector<std::vector<int>> cells;      // m + 1 local indices, containing 0
  std::vector<std::pair<int, int>> cases;   // (cell index, query local index)
};

PowerInput random_power_input(const Config& c, Rng& rng) {
  PowerInput in;
  in.p = on_manifold(c, rng);
  // Neighbours: points of M near p (nearby angles / perturbed then re-sampled is overkill:
  // small perturbations of p suffice for predicate costs).
  for (int i = 0; i < 48; ++i) {
    auto q = in.p;
    for (auto& v : q) v += 0.15 * rng.normal();
    in.points.push_back(q);
  }
  const int K = static_cast<int>(in.points.size());
  for (int t = 0; t < 64; ++t) {
    std::vector<int> cell{0};
    while (static_cast<int>(cell.size()) <= c.m) {
      const int v = rng.integer(1, K);
      if (std::find(cell.begin(), cell.end(), v) == cell.end()) cell.push_back(v);
    }
    in.cells.push_back(cell);
  }
  for (int t = 0; t < 4096; ++t) {
    const int ci = rng.integer(0, static_cast<int>(in.cells.size()) - 1);
    int q;
    do q = rng.integer(1, K);
    while (std::find(in.cells[ci].begin(), in.cells[ci].end(), q) != in.cells[ci].end());
    in.cases.push_back({ci, q});
  }
  return in;
}

// Exactly cospherical input: c = p + U z in T_p, and every point at distance |U z| from c,
// obtained by signed permutations of a = U z. Coordinates carry ~20-40 significant bits so that
// interval arithmetic is inexact and the filter has to fall back to exact arithmetic.
PowerInput degenerate_power_input(const Config& c, const ImplicitSystem& F, Rng& rng) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    PowerInput in;
    in.p.resize(c.N);
    for (auto& v : in.p) v = rng.dyadic(10);
    TangentSpace T(F, in.p);
    std::vector<int> z(c.m);
    for (auto& v : z) v = rng.integer(-3, 3);
    std::vector<mpq_class> a(c.N);
    bool ok = true, nonzero = false;
    for (int i = 0; i < c.N; ++i) {
      for (int k = 0; k < c.m; ++k) a[i] += T.basis(i, k) * z[k];
      nonzero = nonzero || a[i] != 0;
    }
    if (!nonzero) continue;
    std::vector<mpq_class> centre(c.N);
    for (int i = 0; i < c.N; ++i) centre[i] = to_rational(in.p[i]) + a[i];
    for (int t = 0; t < 48 && ok; ++t) {
      std::vector<int> perm(c.N);
      std::iota(perm.begin(), perm.end(), 0);
      for (int i = c.N - 1; i > 0; --i) std::swap(perm[i], perm[rng.integer(0, i)]);
      std::vector<double> x(c.N);
      for (int i = 0; i < c.N; ++i) {
        const mpq_class xi = centre[i] + (rng.integer(0, 1) ? 1 : -1) * a[perm[i]];
        if (!is_exact_double(xi)) ok = false;
        x[i] = xi.get_d();
      }
      in.points.push_back(x);
    }
    if (!ok) continue;
    const int K = static_cast<int>(in.points.size());
    for (int t = 0; t < 64; ++t) {
      std::vector<int> cell{0};
      while (static_cast<int>(cell.size()) <= c.m) {
        const int v = rng.integer(1, K);
        if (std::find(cell.begin(), cell.end(), v) == cell.end()) cell.push_back(v);
      }
      in.cells.push_back(cell);
    }
    for (int t = 0; t < 4096; ++t) {
      const int ci = rng.integer(0, static_cast<int>(in.cells.size()) - 1);
      int q;
      do q = rng.integer(1, K);
      while (std::find(in.cells[ci].begin(), in.cells[ci].end(), q) != in.cells[ci].end());
      in.cases.push_back({ci, q});
    }
    return in;
  }
  throw std::runtime_error("could not build a degenerate configuration");
}

std::vector<const double*> pointers(const std::vector<std::vector<double>>& pts) {
  std::vector<const double*> out;
  for (const auto& p : pts) out.push_back(p.data());
  return out;
}

template <int M>
nlohmann::json bench_power(const Config& c, const ImplicitSystem& F, const PowerInput& in, bool quick) {
  TangentSpace T(F, in.p);
  TangentChart chart(T, pointers(in.points));
  const int N = c.N, L = M + 1;
  // Double data: U rounded, chart rows in double.
  const Eigen::MatrixXd Ud = T.basis_approx();
  std::vector<double> U(N * M);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < M; ++a) U[i * M + a] = Ud(i, a);
  const int count = chart.size();
  std::vector<double> rows(count * L, 0.0);
  auto row_of = [&](const double* x, double* row) {
    detail::chart_row<M>(U.data(), [&](int i) { return x[i] - in.p[i]; }, N, row);
  };
  for (int i = 1; i < count; ++i) row_of(in.points[i - 1].data(), rows.data() + i * L);
  // Prepared double cells.
  std::vector<double> dcoef(in.cells.size() * L), dk0(in.cells.size());
  for (std::size_t ci = 0; ci < in.cells.size(); ++ci) {
    const double* r[M + 1];
    for (int i = 0; i <= M; ++i) r[i] = rows.data() + in.cells[ci][i] * L;
    detail::power_cell<M>(r, true, dcoef.data() + ci * L, dk0[ci]);
  }
  FilterContext ctx;
  std::vector<TangentCell> cells;
  for (const auto& cell : in.cells) cells.push_back(chart.cell(cell, ctx));
  FilterContext exact_ctx;
  exact_ctx.force_exact = true;
  std::vector<TangentCell> exact_cells;
  for (const auto& cell : in.cells) exact_cells.push_back(chart.cell(cell, exact_ctx));

  nlohmann::json out;
  const std::size_t n = in.cases.size();
  const std::size_t n_exact = quick ? 64 : 512;
  // -- query on a prepared cell --
  {
    FilterContext q_ctx;
    double batched, unbatched, exact, dbl;
    {
      UpwardRounding batch;
      batched = time_ns(n, quick, [&](std::size_t i) {
        sink(cells[in.cases[i].first].power_sign(in.cases[i].second, q_ctx));
      });
    }
    unbatched = time_ns(n, quick, [&](std::size_t i) {
      sink(cells[in.cases[i].first].power_sign(in.cases[i].second, q_ctx));
    });
    exact = time_ns(n_exact, quick, [&](std::size_t i) {
      sink(exact_cells[in.cases[i].first].power_sign(in.cases[i].second, exact_ctx));
    });
    dbl = time_ns(n, quick, [&](std::size_t i) {
      const auto [ci, q] = in.cases[i];
      const double v = detail::power_value<M>(dcoef.data() + ci * L, dk0[ci], rows.data() + q * L, true);
      sink((v > 0) - (v < 0));
    });
    const auto& st = q_ctx.stats[PredicateKind::power];
    out["query"] = {{"filtered_batched_ns", batched},
                    {"filtered_unbatched_ns", unbatched},
                    {"exact_ns", exact},
                    {"double_ns", dbl},
                    {"filtered_over_double", batched / dbl},
                    {"target_2x_double_plus_50ns", 2 * dbl + 50},
                    {"meets_target", batched <= 2 * dbl + 50},
                    {"filter_failure_rate", double(st.filter_failures) / double(std::max<std::uint64_t>(1, st.calls))}};
  }
  // -- cell preparation + one query --
  {
    FilterContext q_ctx;
    double batched, exact, dbl;
    {
      UpwardRounding batch;
      batched = time_ns(n, quick, [&](std::size_t i) {
        const auto [ci, q] = in.cases[i];
        sink(chart.cell(in.cells[ci], q_ctx).power_sign(q, q_ctx));
      });
    }
    exact = time_ns(n_exact, quick, [&](std::size_t i) {
      const auto [ci, q] = in.cases[i];
      sink(chart.cell(in.cells[ci], exact_ctx).power_sign(q, exact_ctx));
    });
    dbl = time_ns(n, quick, [&](std::size_t i) {
      const auto [ci, q] = in.cases[i];
      const double* r[M + 1];
      for (int k = 0; k <= M; ++k) r[k] = rows.data() + in.cells[ci][k] * L;
      double coef[M + 1], k0;
      detail::power_cell<M>(r, true, coef, k0);
      const double v = detail::power_value<M>(coef, k0, rows.data() + q * L, true);
      sink(((coef[M] > 0) - (coef[M] < 0)) * ((v > 0) - (v < 0)));
    });
    const auto& st = q_ctx.stats[PredicateKind::power];
    out["cell"] = {{"filtered_batched_ns", batched},
                   {"exact_ns", exact},
                   {"double_ns", dbl},
                   {"filtered_over_double", batched / dbl},
                   {"target_2x_double_plus_50ns", 2 * dbl + 50},
                   {"meets_target", batched <= 2 * dbl + 50},
                   {"filter_failure_rate", double(st.filter_failures) / double(std::max<std::uint64_t>(1, st.calls))}};
  }
  // -- raw points --
  {
    FilterContext q_ctx;
    std::vector<std::vector<const double*>> cell_pts;
    for (const auto& cell : in.cells) {
      std::vector<const double*> v;
      for (int k : cell) v.push_back(k == 0 ? in.p.data() : in.points[k - 1].data());
      cell_pts.push_back(v);
    }
    double batched, exact, dbl;
    {
      UpwardRounding batch;
      batched = time_ns(n, quick, [&](std::size_t i) {
        const auto [ci, q] = in.cases[i];
        sink(tangent_power_sign(T, cell_pts[ci], in.points[q - 1].data(), q_ctx));
      });
    }
    exact = time_ns(n_exact, quick, [&](std::size_t i) {
      const auto [ci, q] = in.cases[i];
      sink(tangent_power_sign(T, cell_pts[ci], in.points[q - 1].data(), exact_ctx));
    });
    dbl = time_ns(n, quick, [&](std::size_t i) {
      const auto [ci, q] = in.cases[i];
      double buf[(M + 2) * (M + 1)];
      const double* r[M + 1];
      for (int k = 0; k <= M; ++k) {
        row_of(cell_pts[ci][k], buf + k * L);
        r[k] = buf + k * L;
      }
      row_of(in.points[q - 1].data(), buf + (M + 1) * L);
      double coef[M + 1], k0;
      detail::power_cell<M>(r, false, coef, k0);
      const double v = detail::power_value<M>(coef, k0, buf + (M + 1) * L, false);
      sink(((coef[M] > 0) - (coef[M] < 0)) * ((v > 0) - (v < 0)));
    });
    const auto& st = q_ctx.stats[PredicateKind::power];
    out["raw"] = {{"filtered_batched_ns", batched},
                  {"exact_ns", exact},
                  {"double_ns", dbl},
                  {"filtered_over_double", batched / dbl},
                  {"target_2x_double_plus_50ns", 2 * dbl + 50},
                  {"meets_target", batched <= 2 * dbl + 50},
                  {"filter_failure_rate", double(st.filter_failures) / double(std::max<std::uint64_t>(1, st.calls))}};
  }
  return out;
}

// Thickness input: (j + 1)-vertex simplices in R^N, j = m.
std::vector<std::vector<std::vector<double>>> thickness_input(int N, int j, bool degenerate, Rng& rng) {
  std::vector<std::vector<std::vector<double>>> out;
  for (int t = 0; t < 1024; ++t) {
    std::vector<std::vector<double>> s(j + 1, std::vector<double>(N));
    if (!degenerate) {
      for (auto& v : s)
        for (auto& x : v) x = rng.normal();
    } else {
      // Affinely dependent: the last vertex is an exact affine combination of the others
      // (v_j = v_0 + (v_1 - v_0) + (v_2 - v_0) with ~20-bit coordinates: exact in double).
      for (int k = 0; k < j; ++k)
        for (auto& x : s[k]) x = rng.dyadic(20);
      for (int i = 0; i < N; ++i) s[j][i] = s[1][i] + s[2 % j == 0 ? 1 : 2][i] - s[0][i];
    }
    out.push_back(s);
  }
  return out;
}

template <int J>
nlohmann::json bench_thickness(int N, bool degenerate, bool quick, Rng& rng) {
  auto input = thickness_input(N, J, degenerate, rng);
  std::vector<std::vector<const double*>> ptrs;
  for (const auto& s : input) ptrs.push_back(pointers(s));
  const RationalConstant gamma2(mpq_class(1, 400));
  const double g2 = 1.0 / 400;
  FilterContext ctx, exact_ctx;
  exact_ctx.force_exact = true;
  double batched, exact, dbl;
  {
    UpwardRounding batch;
    batched = time_ns(input.size(), quick, [&](std::size_t i) { sink(thickness_sign(ptrs[i], N, gamma2, ctx)); });
  }
  exact = time_ns(quick ? 64 : 512, quick, [&](std::size_t i) { sink(thickness_sign(ptrs[i], N, gamma2, exact_ctx)); });
  dbl = time_ns(input.size(), quick, [&](std::size_t i) {
    const auto& v = ptrs[i];
    double d[(J + 1) * (J + 1)] = {};
    double delta2 = 0;
    for (int a = 0; a <= J; ++a)
      for (int b = a + 1; b <= J; ++b) {
        double s = 0;
        for (int k = 0; k < N; ++k) s += (v[a][k] - v[b][k]) * (v[a][k] - v[b][k]);
        d[a * (J + 1) + b] = d[b * (J + 1) + a] = s;
        delta2 = std::max(delta2, s);
      }
    double gt, gf[J + 1];
    detail::thickness_terms<J>(d, gt, gf);
    int r = 1;
    for (int l = 0; l <= J; ++l) r = std::min(r, (gt - 2.0 * J * J * g2 * delta2 * gf[l] > 0) ? 1 : -1);
    sink(r);
  });
  const auto& st = ctx.stats[PredicateKind::thickness];
  return {{"filtered_batched_ns", batched},
          {"exact_ns", exact},
          {"double_ns", dbl},
          {"filtered_over_double", batched / dbl},
          {"target_2x_double_plus_50ns", 2 * dbl + 50},
          {"meets_target", batched <= 2 * dbl + 50},
          {"filter_failure_rate", double(st.filter_failures) / double(std::max<std::uint64_t>(1, st.calls))}};
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  Rng rng(20240607);
  nlohmann::json report;
  report["benchmark"] = "bench_exact";
  report["unit"] = "ns per call (thread CPU time), median of 9 repetitions";
  report["note"] =
      "filtered = interval filter + exact fallback (CGAL Interval_nt_advanced, Mpzf); exact = fallback only; double = "
      "the same kernel expression in double (not certified)";
  for (const auto& c : configs()) {
    ImplicitSystem F = ImplicitSystem::parse(c.equations, c.N);
    nlohmann::json entry;
    entry["manifold"] = c.manifold;
    entry["N"] = c.N;
    entry["m"] = c.m;
    auto run = [&](auto Mc) {
      constexpr int M = decltype(Mc)::value;
      PowerInput random = random_power_input(c, rng);
      PowerInput degenerate = degenerate_power_input(c, F, rng);
      entry["power"]["random"] = bench_power<M>(c, F, random, quick);
      entry["power"]["degenerate"] = bench_power<M>(c, F, degenerate, quick);
      entry["thickness"]["random"] = bench_thickness<M>(c.N, false, quick, rng);
      entry["thickness"]["degenerate"] = bench_thickness<M>(c.N, true, quick, rng);
    };
    if (c.m == 2) run(std::integral_constant<int, 2>{});
    else run(std::integral_constant<int, 3>{});
    report["results"].push_back(entry);
  }
  report["sink"] = static_cast<long>(g_sink);
  std::cout << report.dump(2) << std::endl;
  return 0;
}
