#pragma once
// The range of a sample with its k most extreme values at each end left out: object extents that
// a few stray points do not set.
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace objscan {

// [lo, hi] of `values` between the k-th smallest and the k-th largest (k = 0: the extremes; needs
// 2k < values.size()). Reorders `values`; {0, 0} when it is empty.
inline std::pair<float, float> TrimmedRange(std::vector<float>* values, std::size_t k) {
  auto& v = *values;
  if (v.empty()) return {0.f, 0.f};
  if (k == 0) {
    const auto mm = std::minmax_element(v.begin(), v.end());
    return {*mm.first, *mm.second};
  }
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  const float lo = v[k];
  const std::size_t top = v.size() - 1 - k;
  std::nth_element(v.begin() + static_cast<std::ptrdiff_t>(k), v.begin() + static_cast<std::ptrdiff_t>(top), v.end());
  return {lo, v[top]};
}

}  // namespace objscan
