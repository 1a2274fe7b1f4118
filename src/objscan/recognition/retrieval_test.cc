#include "objscan/recognition/retrieval.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "objscan/common/rng.h"

namespace objscan::recognition {
namespace {

SparseHistogram RandomHistogram(std::uint32_t num_bins, int nonzero, Rng* rng) {
  std::map<std::uint32_t, float> h;
  for (int i = 0; i < nonzero; ++i) h[static_cast<std::uint32_t>(rng->UniformInt(0, num_bins - 1))] += rng->Uniform(0.1, 1.0);
  SparseHistogram out;
  for (const auto& [b, v] : h) out.push_back({b, v});
  return out;
}

// Cosine of idf-weighted histograms, computed densely.
double BruteForceScore(const SparseHistogram& q, const SparseHistogram& x, const std::vector<double>& idf) {
  std::vector<double> a(idf.size(), 0.0), b(idf.size(), 0.0);
  for (const auto& e : q) a[e.bin] = e.value * idf[e.bin];
  for (const auto& e : x) b[e.bin] = e.value * idf[e.bin];
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < idf.size(); ++i) {
    ab += a[i] * b[i];
    aa += a[i] * a[i];
    bb += b[i] * b[i];
  }
  return ab / std::sqrt(aa * bb);
}

TEST(RetrievalTest, InvertedIndexMatchesBruteForceCosine) {
  Rng rng(1);
  const std::uint32_t num_bins = 300;
  std::vector<SparseHistogram> items;
  for (int i = 0; i < 80; ++i) items.push_back(RandomHistogram(num_bins, 40, &rng));
  std::vector<const SparseHistogram*> ptrs;
  std::vector<int> ids;
  for (int i = 0; i < 80; ++i) {
    ptrs.push_back(&items[i]);
    ids.push_back(1000 + i);
  }
  InvertedIndex index;
  index.Build(ptrs, ids, num_bins);
  std::vector<double> df(num_bins, 0.0), idf(num_bins, 0.0);
  for (const auto& h : items)
    for (const auto& e : h) df[e.bin] += 1.0;
  for (std::uint32_t b = 0; b < num_bins; ++b) idf[b] = df[b] > 0 ? std::log((1.0 + 80) / df[b]) : 0.0;

  const SparseHistogram query = RandomHistogram(num_bins, 30, &rng);
  const auto top = index.Query(query, 10);
  ASSERT_EQ(top.size(), 10u);
  std::vector<std::pair<double, int>> brute;
  for (int i = 0; i < 80; ++i) brute.emplace_back(BruteForceScore(query, items[i], idf), 1000 + i);
  std::sort(brute.begin(), brute.end(), [](auto a, auto b) { return a.first > b.first; });
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(top[k].item, brute[k].second) << k;
    EXPECT_NEAR(top[k].score, brute[k].first, 1e-4);
  }
}

TEST(RetrievalTest, FindsTheRightItemAmongDistractors) {
  Rng rng(2);
  const std::uint32_t num_bins = 500;
  std::vector<SparseHistogram> items;
  for (int i = 0; i < 200; ++i) items.push_back(RandomHistogram(num_bins, 60, &rng));
  std::vector<const SparseHistogram*> ptrs;
  std::vector<int> ids;
  for (int i = 0; i < 200; ++i) {
    ptrs.push_back(&items[i]);
    ids.push_back(i);
  }
  InvertedIndex index;
  index.Build(ptrs, ids, num_bins);
  // A partial, perturbed copy of item 137: half its bins, values jittered.
  SparseHistogram query;
  for (std::size_t k = 0; k < items[137].size(); k += 2)
    query.push_back({items[137][k].bin, items[137][k].value * static_cast<float>(rng.Uniform(0.7, 1.3))});
  const auto top = index.Query(query, 5);
  ASSERT_FALSE(top.empty());
  EXPECT_EQ(top[0].item, 137);
  // A query sharing no bin with anything finds nothing.
  InvertedIndex small;
  const SparseHistogram only = {{3, 1.f}};
  small.Build({&only}, {0}, 10);
  EXPECT_TRUE(small.Query({{4, 1.f}}, 5).empty());
}

}  // namespace
}  // namespace objscan::recognition
