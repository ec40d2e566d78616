// A small deterministic parallel loop: items [0, count) are handed out in chunks to `threads`
// workers; each worker owns its scratch state, and results are written by index, so the output
// never depends on the thread count or on scheduling.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace delcert::support {

// threads <= 0: one per hardware thread.
inline int resolve_threads(int threads) {
  if (threads > 0) return threads;
  unsigned h = std::thread::hardware_concurrency();
  return h ? static_cast<int>(h) : 1;
}

// Calls make_worker(thread_index) once per thread to get a callable `worker(begin, end)` that
// processes items [begin, end). The first exception thrown by a worker is rethrown here after
// all threads stopped.
template <class MakeWorker>
void parallel_chunks(std::size_t count, int threads, std::size_t chunk, MakeWorker&& make_worker) {
  threads = std::max(1, std::min<int>(resolve_threads(threads), static_cast<int>((count + chunk - 1) / std::max<std::size_t>(chunk, 1))));
  chunk = std::max<std::size_t>(chunk, 1);
  if (threads <= 1) {
    auto worker = make_worker(0);
    for (std::size_t b = 0; b < count; b += chunk) worker(b, std::min(count, b + chunk));
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      try {
        auto worker = make_worker(t);
        for (;;) {
          if (failed.load(std::memory_order_relaxed)) return;
          std::size_t b = next.fetch_add(chunk, std::memory_order_relaxed);
          if (b >= count) return;
          worker(b, std::min(count, b + chunk));
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    });
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace delcert::support
