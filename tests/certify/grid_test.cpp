// The grid's sufficiency guarantee: every point of the closed ball is a candidate.
#include <gtest/gtest.h>

#include "support.hpp"

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
    PointGrid grid(P, std::min(dim, 3));
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

}  // namespace
}  // namespace delcert::certify::test
