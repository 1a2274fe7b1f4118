#pragma once
// Runs fn(block) for block in [0, num_blocks) on up to `threads` threads. Blocks are handed out
// dynamically, so callers must make each block's result depend on the block index only (never on
// which thread ran it): that is what keeps results independent of the thread count.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace objscan {

// 0 means "as many as the hardware has".
inline int ResolveThreadCount(int threads) {
  if (threads > 0) return threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// The first exception thrown by any block is rethrown on the calling thread after all threads joined.
template <class Fn>
void ParallelForBlocks(int num_blocks, int threads, const Fn& fn) {
  const int workers = std::min(ResolveThreadCount(threads), num_blocks);
  if (workers <= 1) {
    for (int b = 0; b < num_blocks; ++b) fn(b);
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    try {
      for (int b = next.fetch_add(1); b < num_blocks; b = next.fetch_add(1)) fn(b);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(num_blocks);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace objscan
