#pragma once
// A stopwatch owned by whoever measures; no global timers.
#include <chrono>

namespace objscan {

class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void Restart() { start_ = Clock::now(); }
  double ElapsedSeconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double ElapsedMs() const { return 1e3 * ElapsedSeconds(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace objscan
