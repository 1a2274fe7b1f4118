#pragma once
// Inverted index over spatial bag-of-words bins: a query only touches the posting lists of its own
// non-zero bins instead of scanning every item. Scores are cosine similarities of tf-idf weighted
// histograms (idf = log(N / items containing the bin)).
#include <cstdint>
#include <vector>

#include "objscan/recognition/spatial_bow.h"

namespace objscan::recognition {

struct ScoredItem {
  int item = -1;      // the caller's item id
  float score = 0.f;  // cosine similarity in [0, 1]
};

class InvertedIndex {
 public:
  InvertedIndex() = default;

  // Indexes histograms[i] under item_ids[i]; bins must be < num_bins.
  void Build(const std::vector<const SparseHistogram*>& histograms, const std::vector<int>& item_ids,
             std::uint32_t num_bins);

  // The top_k items by score, best first (ties by item id). Items sharing no bin with the query are
  // never returned.
  std::vector<ScoredItem> Query(const SparseHistogram& query, int top_k) const;

  std::size_t num_items() const { return item_ids_.size(); }
  std::size_t num_postings() const { return posting_item_.size(); }

 private:
  std::uint32_t num_bins_ = 0;
  std::vector<float> idf_;                 // per bin
  std::vector<std::uint32_t> offsets_;     // CSR: postings of bin b are [offsets_[b], offsets_[b+1])
  std::vector<std::int32_t> posting_item_; // dense item index
  std::vector<float> posting_value_;       // idf-weighted, L2-normalised item value
  std::vector<int> item_ids_;
};

}  // namespace objscan::recognition
