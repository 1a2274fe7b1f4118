#include "objscan/segmentation/segmentation_quality.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace objscan::segmentation {

namespace {
std::uint64_t PairKey(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
std::int64_t Choose2(std::int64_t k) { return k * (k - 1) / 2; }
}  // namespace

double RandIndex(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("RandIndex: labelings differ in size");
  const std::int64_t n = static_cast<std::int64_t>(a.size());
  if (n < 2) return 1.0;
  std::unordered_map<std::uint64_t, std::int64_t> cells;
  std::unordered_map<std::int32_t, std::int64_t> rows, cols;
  for (std::int64_t i = 0; i < n; ++i) {
    ++cells[PairKey(a[i], b[i])];
    ++rows[a[i]];
    ++cols[b[i]];
  }
  std::int64_t same_both = 0, same_a = 0, same_b = 0;
  for (const auto& kv : cells) same_both += Choose2(kv.second);
  for (const auto& kv : rows) same_a += Choose2(kv.second);
  for (const auto& kv : cols) same_b += Choose2(kv.second);
  const std::int64_t pairs = Choose2(n);
  // Agreements = pairs together in both + pairs apart in both.
  const std::int64_t agree = pairs + 2 * same_both - same_a - same_b;
  return static_cast<double>(agree) / static_cast<double>(pairs);
}

double Purity(const std::vector<std::int32_t>& predicted, const std::vector<std::int32_t>& truth) {
  if (predicted.size() != truth.size()) throw std::invalid_argument("Purity: labelings differ in size");
  if (predicted.empty()) return 1.0;
  std::unordered_map<std::uint64_t, std::int64_t> cells;
  for (std::size_t i = 0; i < predicted.size(); ++i) ++cells[PairKey(predicted[i], truth[i])];
  std::unordered_map<std::int32_t, std::int64_t> best;
  for (const auto& kv : cells) {
    const std::int32_t p = static_cast<std::int32_t>(kv.first >> 32);
    std::int64_t& b = best[p];
    b = std::max(b, kv.second);
  }
  std::int64_t sum = 0;
  for (const auto& kv : best) sum += kv.second;
  return static_cast<double>(sum) / static_cast<double>(predicted.size());
}

PresegQuality EvaluatePresegmentation(const mapping::SurfaceMap& map, const std::vector<std::int32_t>& element_instance,
                                      const std::vector<std::int32_t>& structural_instances) {
  const std::unordered_set<std::int32_t> structural(structural_instances.begin(), structural_instances.end());
  std::vector<std::int32_t> predicted, truth;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (map.label(i) <= 0 || map.structure(i) != mapping::Structure::kNone) continue;
    const std::int32_t g = i < element_instance.size() ? element_instance[i] : 0;
    if (g == 0 || structural.count(g)) continue;
    predicted.push_back(map.label(i));
    truth.push_back(g);
  }
  PresegQuality q;
  q.num_points = predicted.size();
  q.preseg_purity = Purity(predicted, truth);
  q.rand_index_preseg = RandIndex(predicted, truth);
  q.num_components = std::unordered_set<std::int32_t>(predicted.begin(), predicted.end()).size();
  return q;
}

}  // namespace objscan::segmentation
