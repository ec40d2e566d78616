// A deterministic parallel loop: indices [0, n) are handed out in increasing order, one at a time,
// to `threads` workers (the caller and threads - 1 std::threads): uneven work keeps all busy.
// Results go to per-index slots, per-worker state only counts (order-independent), so the output
// depends on neither the thread count nor the schedule. The first exception by index is rethrown:
// every index below a failing one was taken before it and runs to its end.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace delcert::certify::detail {

// f(i, worker) for every i in [0, n); worker in [0, threads) identifies per-thread state.
template <class F>
void parallel_for(std::size_t n, int threads, F&& f) {
  threads = std::max(1, std::min<int>(threads, static_cast<int>(std::max<std::size_t>(n, 1))));
  std::atomic<std::size_t> next{0}, failed_at{n};  // failed_at: the smallest failing index (n: none)
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](int t) {
    for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < n;) {
      if (i > failed_at.load(std::memory_order_relaxed)) return;
      try {
        f(i, t);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (i < failed_at.load(std::memory_order_relaxed)) error = std::current_exception(), failed_at = i;
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace delcert::certify::detail
