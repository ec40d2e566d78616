// The grid's sufficiency guarantee: every point of the closed ball is a candidate.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cfenv>
#include <cfloat>
#include <map>

#include "exact/interval.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

TEST(PointGrid, CandidatesContainEveryPointOfTheBall) {
  Rng rng(7);
  for (int dim : {2, 3, 4, 9}) {
    io::PointSet P;
    P.dimension = dim;
    for (int i = 0; i < 400; ++i) {
      std::vector<double> x(dim);
      for (auto& v : x) v = rng.uniform() * 4 - 2;
      if (i % 50 == 0) x[0] = std::nextafter(x[0], 10.0);  // values one ulp apart
      P.push_back(x);
    }
    detail::PointGrid grid(P, std::min(dim, 3));
    for (int q = 0; q < 200; ++q) {
      std::vector<double> c(dim);
      for (auto& v : c) v = rng.uniform() * 5 - 2.5;
      double r = rng.uniform() * (q % 3 == 0 ? 3.0 : 0.5);
      auto cand = grid.candidates(c, r);
      EXPECT_TRUE(std::is_sorted(cand.begin(), cand.end()));
      for (std::size_t i = 0; i < P.size(); ++i) {
        double d = 0;
        for (int k = 0; k < dim; ++k) d += (P.point(i)[k] - c[k]) * (P.point(i)[k] - c[k]);
        if (std::sqrt(d) <= r) {
          EXPECT_TRUE(std::binary_search(cand.begin(), cand.end(), static_cast<int>(i)));
        }
      }
    }
    EXPECT_EQ(grid.candidates(P.point(0), grid.diameter()).size(), P.size());
  }
}


// The three cell tables (dense, lines along the last axis, hash map of occupied cells) return the
// same candidates: every point of the box, nothing else, for the same queries.
TEST(PointGrid, EveryCellTableGivesTheBoxExactly) {
  Rng rng(12);
  io::PointSet P;
  P.dimension = 3;
  for (int i = 0; i < 3000; ++i) P.push_back(std::vector<double>{rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 0.5});
  std::map<std::string, int> seen;
  for (double hint : {0.0, 0x1p-8, 0x1p-11}) {
    detail::PointGrid grid(P, 2, hint);
    ++seen[grid.table()];
    for (int q = 0; q < 300; ++q) {
      std::vector<double> c{rng.uniform() * 2.4 - 1.2, rng.uniform() * 2.4 - 1.2, rng.uniform() * 0.7 - 0.1};
      const double r = q % 10 == 0 ? 2.0 : rng.uniform() * 0.2;
      std::vector<int> box;
      for (std::size_t i = 0; i < P.size(); ++i) {
        bool in = true;
        for (int k = 0; k < 3; ++k) in = in && std::abs(P.point(i)[k] - c[k]) <= r;
        if (in) box.push_back(static_cast<int>(i));
      }
      const std::vector<int> cand = grid.candidates(c, r);
      // Candidates are whole cells: a superset of the box, and within one cell edge of it.
      EXPECT_TRUE(std::includes(cand.begin(), cand.end(), box.begin(), box.end())) << grid.table();
      const double h = std::ldexp(1.0, grid.cell_exponent());
      for (int i : cand)
        for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(P.point(i)[k] - c[k]), r + h) << grid.table();
    }
  }
  EXPECT_EQ(seen, (std::map<std::string, int>{{"cells", 1}, {"dense", 1}, {"lines", 1}}));
}

// visit_ball with half-widths per axis (check 7's box of W): every point of the ball that is in
// the box, nothing outside the ball, nothing beyond a cell edge of the box; on each cell table.
TEST(PointGrid, EveryCellTableGivesTheBallInABox) {
  Rng rng(13);
  io::PointSet P;
  P.dimension = 3;
  // The longest axes first in the grid (1, 2, 0): the half-widths must follow the coordinates.
  for (int i = 0; i < 3000; ++i) P.push_back(std::vector<double>{rng.uniform() * 0.5, rng.uniform() * 2 - 1, rng.uniform() * 1.6 - 0.8});
  for (double hint : {0.0, 0x1p-8, 0x1p-11}) {
    detail::PointGrid grid(P, 2, hint);
    const double h = std::ldexp(1.0, grid.cell_exponent());
    for (int q = 0; q < 300; ++q) {
      std::vector<double> c{rng.uniform() * 0.7 - 0.1, rng.uniform() * 2.4 - 1.2, rng.uniform() * 2 - 1};
      const double r = q % 10 == 0 ? 2.0 : rng.uniform() * 0.3;
      std::vector<double> half(3);
      for (double& w : half) w = q % 7 == 0 ? 0.0 : q % 5 == 0 ? 3 * r : rng.uniform() * r;
      std::vector<int> visited;
      grid.visit_ball(c, r, half, [&](int i, const double* x) {
        visited.push_back(i);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(x[k], P.point(i)[k]);
      });
      std::sort(visited.begin(), visited.end());
      EXPECT_TRUE(std::adjacent_find(visited.begin(), visited.end()) == visited.end()) << "a point visited twice";
      const std::vector<int> ball = grid.ball(c, r);
      EXPECT_TRUE(std::includes(ball.begin(), ball.end(), visited.begin(), visited.end())) << grid.table();
      for (std::size_t i = 0; i < P.size(); ++i) {
        mpq_class s = 0;
        bool in_box = true;
        for (int k = 0; k < 3; ++k) {
          const mpq_class d = mpq_class(P.point(i)[k]) - mpq_class(c[k]);
          s += d * d;
          in_box = in_box && abs(d) <= mpq_class(half[k]);
        }
        if (in_box && s <= mpq_class(r) * mpq_class(r)) {
          EXPECT_TRUE(std::binary_search(visited.begin(), visited.end(), static_cast<int>(i))) << grid.table() << " point " << i;
        }
      }
      for (int i : visited)
        for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(P.point(i)[k] - c[k]), half[k] + h) << grid.table();
    }
    // A negative half-width or radius is an empty box (not a loop without end).
    int seen = 0;
    grid.visit_ball(std::vector<double>{0.2, 0, 0}, 0.5, std::vector<double>{0.5, -0.1, 0.5}, [&](int, const double*) { ++seen; });
    EXPECT_EQ(seen, 0);
    EXPECT_TRUE(grid.candidates(std::vector<double>{0.2, 0, 0}, -1.0).empty());
  }
}

// Exact (rational) tests: |q_k - c_k| <= r for every k, and |q - c|^2 <= r^2.
mpq_class q_of(double x) { return mpq_class(x); }
bool in_box_exact(std::span<const double> q, std::span<const double> c, double r) {
  for (std::size_t k = 0; k < q.size(); ++k) {
    mpq_class d = q_of(q[k]) - q_of(c[k]);
    if (abs(d) > q_of(r)) return false;
  }
  return true;
}
bool in_ball_exact(std::span<const double> q, std::span<const double> c, double r) {
  mpq_class s = 0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    mpq_class d = q_of(q[k]) - q_of(c[k]);
    s += d * d;
  }
  return s <= q_of(r) * q_of(r);
}

// Every point of the exact box (resp. ball) is returned, whatever the rounding mode of the query.
void expect_superset(const io::PointSet& P, const detail::PointGrid& grid, std::span<const double> c, double r) {
  for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    std::vector<int> cand, ball, filtered;
    {
      const int saved = std::fegetround();
      std::fesetround(mode);
      cand = grid.candidates(c, r);
      ball = grid.ball(c, r);
      // ball() is exactly the box's candidates that pass its floating-point filter (grid.cpp: the
      // lines of cells cut to the ball lose none of them).
      const double r2 = r * r * (1 + 0x1p-40);
      for (int i : cand) {
        double d2 = 0;
        for (std::size_t k = 0; k < c.size(); ++k) d2 += (P.point(i)[k] - c[k]) * (P.point(i)[k] - c[k]);
        if (!(r2 > 1e-280) || !(r2 <= DBL_MAX) || d2 <= r2) filtered.push_back(i);
      }
      std::fesetround(saved);
    }
    ASSERT_TRUE(std::is_sorted(cand.begin(), cand.end()));
    EXPECT_EQ(ball, filtered) << "r = " << r << ", mode " << mode;
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (in_box_exact(P.point(i), c, r)) {
        EXPECT_TRUE(std::binary_search(cand.begin(), cand.end(), static_cast<int>(i)))
            << "point " << i << " (" << P.point(i)[0] << ", ...) missed, r = " << r << ", mode " << mode;
      }
      if (in_ball_exact(P.point(i), c, r)) {
        EXPECT_TRUE(std::binary_search(ball.begin(), ball.end(), static_cast<int>(i)))
            << "point " << i << " missed by ball, r = " << r << ", mode " << mode;
      }
    }
  }
}

// Queries centred at points, between points and far away, with radii equal to coordinate
// differences (the box boundary falls exactly on a point) and their neighbours.
void adversarial_queries(const io::PointSet& P, const detail::PointGrid& grid, Rng& rng, int count) {
  const int N = P.dimension;
  for (int q = 0; q < count; ++q) {
    std::size_t a = rng.next() % P.size(), b = rng.next() % P.size();
    std::vector<double> c(P.point(a).begin(), P.point(a).end());
    if (q % 4 == 1)
      for (int k = 0; k < N; ++k) c[k] = P.point(a)[k] / 2 + P.point(b)[k] / 2;
    int k = static_cast<int>(rng.next() % N);
    double r = std::abs(P.point(b)[k] - c[k]);  // rounded: sometimes just below the exact difference
    if (q % 3 == 1) r = std::nextafter(r, 0.0);
    if (q % 3 == 2) r = std::nextafter(r, INFINITY);
    if (q % 17 == 0) r = 0;
    if (std::isinf(r)) r = DBL_MAX;
    expect_superset(P, grid, c, r);
  }
}

io::PointSet scaled_cloud(Rng& rng, int n, int N, double scale) {
  io::PointSet P;
  P.dimension = N;
  for (int i = 0; i < n; ++i) {
    std::vector<double> x(N);
    for (auto& v : x) v = (rng.uniform() * 2 - 1) * scale;
    if (i % 7 == 0) x[0] = -x[0];
    P.push_back(x);
  }
  return P;
}

// An MPI rank's part (a slab of the whole grid, certify/detail/grid.hpp): wherever covers() says
// so, every query answers exactly as the whole grid does, on each cell table; where it does not,
// the slab gives only points it holds; cells_for(h) is wide enough for every ball of radius h
// centred in the slab's core. A mutant covers() that ignores the slab fails the "not covered"
// count; one that tests one cell too far fails the equality.
TEST(PointGrid, SlabAnswersLikeTheWholeGridWhereItCovers) {
  Rng rng(14);
  io::PointSet P;
  P.dimension = 3;
  for (int i = 0; i < 3000; ++i) P.push_back(std::vector<double>{rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 0.5});
  std::map<std::string, int> seen;
  long covered = 0, not_covered = 0;
  for (double hint : {0.0, 0x1p-8, 0x1p-11}) {
    const detail::PointGrid whole(P, 2, hint);
    const auto [lo, hi] = whole.first_axis_range(whole.order());
    EXPECT_TRUE(whole.covers(std::vector<double>{9, 9, 9}, 1e300));  // the whole grid covers everything
    for (int cut = 0; cut < 4; ++cut) {
      const std::int64_t n0 = hi - lo + 1, a = lo + n0 * cut / 5, b = lo + n0 * (cut + 2) / 5;
      const detail::PointGrid slab(whole, a, b);
      ++seen[slab.table()];
      // It holds exactly the points whose first-axis cell is in [a, b].
      std::vector<int> held(slab.order()), expect;
      std::sort(held.begin(), held.end());
      for (int i = 0; i < static_cast<int>(P.size()); ++i) {
        const int one[1] = {i};
        const std::int64_t c = whole.first_axis_range(one).first;
        if (c >= a && c <= b) expect.push_back(i);
      }
      EXPECT_EQ(held, expect) << slab.table();
      EXPECT_EQ(slab.spacing(), whole.spacing());
      EXPECT_EQ(slab.diameter(), whole.diameter());
      for (int q = 0; q < 200; ++q) {
        const int p = expect.empty() ? 0 : expect[rng.below(static_cast<int>(expect.size()))];
        std::vector<double> c(P.point(p).begin(), P.point(p).end());
        const double r = q % 10 == 0 ? 2.0 : rng.uniform() * 0.4;
        std::vector<double> half{r * rng.uniform(), r, r * rng.uniform()};
        std::vector<int> w1, w2;
        whole.visit_ball(c, r, half, [&](int i, const double*) { w1.push_back(i); });
        slab.visit_ball(c, r, half, [&](int i, const double*) { w2.push_back(i); });
        std::sort(w1.begin(), w1.end()), std::sort(w2.begin(), w2.end());
        if (slab.covers(c, r)) {
          ++covered;
          EXPECT_EQ(slab.candidates(c, r), whole.candidates(c, r)) << slab.table();
          EXPECT_EQ(slab.ball(c, r), whole.ball(c, r));
          EXPECT_EQ(w2, w1);
        } else {
          ++not_covered;
          const std::vector<int> part = slab.ball(c, r);
          EXPECT_TRUE(std::includes(held.begin(), held.end(), part.begin(), part.end()));
        }
      }
      // A halo of cells_for(h) cells around a core [a', b'] covers every ball of radius h centred in it.
      const double h = rng.uniform() * 0.3;
      const std::int64_t k = whole.cells_for(h);
      const detail::PointGrid halo(whole, a + k, b - k);  // core [a + 2k, b - 2k] ... its halo is [a + k, b - k]
      for (int p : expect) {
        const int one[1] = {p};
        const std::int64_t c = whole.first_axis_range(one).first;
        if (c >= a + 2 * k && c <= b - 2 * k) {
          EXPECT_TRUE(halo.covers(P.point(p), h)) << p;
        }
      }
    }
  }
  EXPECT_EQ(seen, (std::map<std::string, int>{{"cells", 4}, {"dense", 4}, {"lines", 4}}));
  EXPECT_GT(covered, 100);
  EXPECT_GT(not_covered, 100);
}

TEST(PointGrid, SupersetAtAdversarialMagnitudes) {
  Rng rng(2024);
  for (double scale : {1e-310, 4e-323, 1e-300, 1.0, 1e300, 1e308, DBL_MAX}) {
    for (int N : {2, 3, 5}) {
      io::PointSet P = scaled_cloud(rng, 60, N, scale);
      for (double hint : {0.0, scale * 1e-9, scale})
        for (int m : {1, 2}) {
          detail::PointGrid grid(P, m, hint);
          EXPECT_GT(grid.spacing(), 0);
          EXPECT_LE(grid.diameter(), DBL_MAX);
          adversarial_queries(P, grid, rng, 12);
          EXPECT_EQ(grid.candidates(P.point(0), INFINITY).size(), P.size());
        }
    }
  }
}

TEST(PointGrid, SupersetWithMixedMagnitudes) {
  Rng rng(99);
  for (int N : {2, 3, 4}) {
    io::PointSet P;
    P.dimension = N;
    const double scales[] = {5e-324, 1e-310, 1e-300, 1, 1e300, 1e308, -DBL_MAX, DBL_MAX};
    for (int i = 0; i < 80; ++i) {
      std::vector<double> x(N);
      for (auto& v : x) v = (rng.uniform() * 2 - 1) * scales[rng.next() % 8];
      P.push_back(x);
    }
    for (double hint : {0.0, 1e-320, 1e-300, 1.0}) {
      detail::PointGrid grid(P, 2, hint);
      adversarial_queries(P, grid, rng, 30);
    }
  }
}

// A small hint over a huge extent: the old int64 key ((i0 d1) + i1) d2 + i2 needed about 2^90
// cells and wrapped; cells per axis and their product are now bounded and every query is exact.
TEST(PointGrid, HugeExtentsDoNotOverflowCellKeys) {
  Rng rng(5);
  for (double far : {1.0, 1e10, 1e300, DBL_MAX}) {
    io::PointSet P;
    P.dimension = 3;
    for (int i = 0; i < 40; ++i) P.push_back(std::vector<double>{rng.uniform() * 1e-3, rng.uniform() * 1e-3, rng.uniform() * 1e-3});
    P.push_back(std::vector<double>{far, far, far});
    P.push_back(std::vector<double>{-far, -far, -far});
    P.push_back(std::vector<double>{far, -far, far});
    for (double hint : {1e-300, 1e-12, 1e-6})
      for (int m : {1, 3}) {
        detail::PointGrid grid(P, m, hint);
        adversarial_queries(P, grid, rng, 40);
        // Small radii around the cluster: the scan-every-occupied-cell path and the odometer.
        for (double r : {1e-4, 1e-3, 1e3}) expect_superset(P, grid, P.point(rng.next() % 40), r);
      }
  }
}

// The soundness fixture: four points with subnormal coordinates (the old cell size was 0).
TEST(PointGrid, SubnormalPoints) {
  io::PointSet P;
  P.dimension = 3;
  P.push_back(std::vector<double>{0, 0, 0});
  P.push_back(std::vector<double>{5e-324, 0, 0});
  P.push_back(std::vector<double>{0, 5e-324, 0});
  P.push_back(std::vector<double>{5e-324, 5e-324, 0});
  for (int m : {1, 2, 3}) {
    detail::PointGrid grid(P, m);
    EXPECT_GT(grid.spacing(), 0);
    EXPECT_GE(grid.diameter(), 5e-324);
    for (std::size_t i = 0; i < P.size(); ++i)
      for (double r : {0.0, 5e-324, 1e-323, 1.0}) expect_superset(P, grid, P.point(i), r);
    EXPECT_EQ(grid.candidates(P.point(0), 5e-324).size(), P.size());
  }
}

TEST(PointGrid, NanRadiusReturnsEveryPoint) {
  Rng rng(1);
  io::PointSet P = scaled_cloud(rng, 20, 2, 1);
  detail::PointGrid grid(P, 1);
  EXPECT_EQ(grid.candidates(P.point(0), NAN).size(), P.size());
}

}  // namespace
}  // namespace delcert::certify::test
