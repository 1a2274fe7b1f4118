#pragma once
// Library code never prints: long work reports progress through this callback and the app decides
// whether to draw a bar (only when stderr is a terminal).
#include <functional>
#include <string>

namespace objscan {

// fraction in [0, 1]; `what` is a short label of the current work item.
using ProgressCallback = std::function<void(double fraction, const std::string& what)>;

inline void ReportProgress(const ProgressCallback& progress, double fraction, const std::string& what) {
  if (progress) progress(fraction, what);
}

}  // namespace objscan
