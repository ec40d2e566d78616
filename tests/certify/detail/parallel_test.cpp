// certify/detail/parallel.hpp: every index exactly once, the smallest failing index's exception,
// and per-index results independent of the thread count under uneven work.
#include "certify/detail/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace delcert::certify::detail {
namespace {

TEST(ParallelFor, EveryIndexOnceWithWorkersInRange) {
  for (int threads : {1, 2, 3, 8}) {
    for (std::size_t n : {0u, 1u, 2u, 7u, 1000u}) {
      std::vector<std::atomic<int>> seen(n);
      for (auto& s : seen) s = 0;
      std::atomic<bool> bad_worker{false};
      parallel_for(n, threads, [&](std::size_t i, int w) {
        seen[i].fetch_add(1);
        if (w < 0 || w >= threads) bad_worker = true;
      });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i].load(), 1) << "n " << n << " threads " << threads << " i " << i;
      EXPECT_FALSE(bad_worker.load());
    }
  }
}

TEST(ParallelFor, UnevenWorkGivesTheSameSlots) {
  // Index i costs about i^2 steps modulo a cycle: the schedule differs between thread counts.
  const std::size_t n = 300;
  auto run = [&](int threads) {
    std::vector<unsigned long> out(n);
    parallel_for(n, threads, [&](std::size_t i, int) {
      unsigned long h = i;
      for (std::size_t s = 0; s < (i * i) % 5000; ++s) h = h * 6364136223846793005ul + 1442695040888963407ul;
      out[i] = h;
    });
    return out;
  };
  const auto one = run(1);
  EXPECT_EQ(run(2), one);
  EXPECT_EQ(run(5), one);
}

TEST(ParallelFor, TheSmallestFailingIndexIsRethrown) {
  for (int threads : {1, 2, 4}) {
    for (int trial = 0; trial < 20; ++trial) {
      try {
        parallel_for(500, threads, [&](std::size_t i, int) {
          if (i == 451 || i == 137 || i == 138 || i == 499) throw std::runtime_error(std::to_string(i));
        });
        ADD_FAILURE() << "no exception with " << threads << " threads";
      } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "137") << threads << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace delcert::certify::detail
