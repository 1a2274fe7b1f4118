#include "objscan/recognition/retrieval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace objscan::recognition {

void InvertedIndex::Build(const std::vector<const SparseHistogram*>& histograms, const std::vector<int>& item_ids,
                          std::uint32_t num_bins) {
  if (histograms.size() != item_ids.size()) throw std::invalid_argument("InvertedIndex::Build: size mismatch");
  num_bins_ = num_bins;
  item_ids_ = item_ids;
  const std::size_t n = histograms.size();
  std::vector<std::uint32_t> df(num_bins, 0);
  for (const SparseHistogram* h : histograms) {
    for (const HistogramBin& b : *h) {
      if (b.bin >= num_bins) throw std::invalid_argument("InvertedIndex::Build: bin out of range");
      ++df[b.bin];
    }
  }
  idf_.assign(num_bins, 0.f);
  for (std::uint32_t b = 0; b < num_bins; ++b) {
    if (df[b] > 0) idf_[b] = static_cast<float>(std::log((1.0 + n) / df[b]));
  }
  offsets_.assign(num_bins + 1, 0);
  for (std::uint32_t b = 0; b < num_bins; ++b) offsets_[b + 1] = offsets_[b] + df[b];
  posting_item_.assign(offsets_.back(), 0);
  posting_value_.assign(offsets_.back(), 0.f);
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    double norm2 = 0.0;
    for (const HistogramBin& b : *histograms[i]) norm2 += static_cast<double>(b.value * idf_[b.bin]) * (b.value * idf_[b.bin]);
    const double inv = norm2 > 0.0 ? 1.0 / std::sqrt(norm2) : 0.0;
    for (const HistogramBin& b : *histograms[i]) {
      const std::uint32_t slot = fill[b.bin]++;
      posting_item_[slot] = static_cast<std::int32_t>(i);
      posting_value_[slot] = static_cast<float>(b.value * idf_[b.bin] * inv);
    }
  }
}

std::vector<ScoredItem> InvertedIndex::Query(const SparseHistogram& query, int top_k) const {
  std::vector<ScoredItem> result;
  if (item_ids_.empty() || top_k <= 0) return result;
  double norm2 = 0.0;
  for (const HistogramBin& b : query) {
    if (b.bin < num_bins_) norm2 += static_cast<double>(b.value * idf_[b.bin]) * (b.value * idf_[b.bin]);
  }
  if (!(norm2 > 0.0)) return result;
  const float inv = static_cast<float>(1.0 / std::sqrt(norm2));
  std::vector<float> acc(item_ids_.size(), 0.f);
  std::vector<char> seen(item_ids_.size(), 0);
  std::vector<std::int32_t> touched;
  for (const HistogramBin& b : query) {
    if (b.bin >= num_bins_) continue;
    const float w = b.value * idf_[b.bin] * inv;
    if (w == 0.f) continue;
    for (std::uint32_t s = offsets_[b.bin]; s < offsets_[b.bin + 1]; ++s) {
      const std::int32_t item = posting_item_[s];
      if (!seen[item]) {
        seen[item] = 1;
        touched.push_back(item);
      }
      acc[item] += w * posting_value_[s];
    }
  }
  const auto better = [&](std::int32_t a, std::int32_t b) { return acc[a] > acc[b] || (acc[a] == acc[b] && a < b); };
  const std::size_t k = std::min<std::size_t>(top_k, touched.size());
  std::partial_sort(touched.begin(), touched.begin() + k, touched.end(), better);
  result.reserve(k);
  for (std::size_t i = 0; i < k; ++i) result.push_back({item_ids_[touched[i]], acc[touched[i]]});
  return result;
}

}  // namespace objscan::recognition
