#include "objscan/recognition/vocabulary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

namespace objscan::recognition {
namespace {

// Three clusters of 8-bin histograms, each concentrated on different bins.
std::vector<float> ClusteredDescriptors(int per_cluster, Rng* rng) {
  std::vector<float> d;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < per_cluster; ++i) {
      for (int b = 0; b < 8; ++b) {
        const bool hot = b / 3 == c;
        d.push_back(static_cast<float>((hot ? 30.0 : 1.0) + rng->Uniform(0.0, 2.0)));
      }
    }
  }
  return d;
}

TEST(VocabularyTest, KMeansSeparatesClustersAndIsDeterministic) {
  Rng data(1);
  const std::vector<float> d = ClusteredDescriptors(200, &data);
  VocabularyOptions options;
  options.num_words = 3;
  options.max_training_descriptors = 600;
  Rng a(5), b(5);
  const Vocabulary va = Vocabulary::Train(d, 8, options, &a);
  const Vocabulary vb = Vocabulary::Train(d, 8, options, &b);
  EXPECT_EQ(va.words(), vb.words());
  ASSERT_EQ(va.num_words(), 3);
  // Every descriptor of a cluster gets the same nearest word, and the clusters get different words.
  std::set<int> cluster_words;
  for (int c = 0; c < 3; ++c) {
    std::set<int> words;
    for (int i = 0; i < 200; ++i) {
      WordAssignment w[8];
      ASSERT_EQ(va.Assign(&d[(c * 200 + i) * 8], w), 3);
      words.insert(w[0].word);
    }
    EXPECT_EQ(words.size(), 1u);
    cluster_words.insert(*words.begin());
  }
  EXPECT_EQ(cluster_words.size(), 3u);
}

TEST(VocabularyTest, SoftAssignmentIsNearestFirstAndSumsToOne) {
  Rng data(2);
  const std::vector<float> d = ClusteredDescriptors(100, &data);
  VocabularyOptions options;
  options.num_words = 6;
  options.max_training_descriptors = 300;
  Rng rng(3);
  const Vocabulary v = Vocabulary::Train(d, 8, options, &rng);
  WordAssignment w[8];
  ASSERT_EQ(v.Assign(&d[0], w), 3);
  EXPECT_NEAR(w[0].weight + w[1].weight + w[2].weight, 1.0, 1e-5);
  EXPECT_GE(w[0].weight, w[1].weight);
  EXPECT_GE(w[1].weight, w[2].weight);
  EXPECT_NE(w[0].word, w[1].word);
  // The nearest word by brute force in the Hellinger space.
  float mapped[8];
  ASSERT_TRUE(HellingerMap(&d[0], 8, mapped));
  int best = -1;
  float best_d2 = 1e30f;
  for (int k = 0; k < v.num_words(); ++k) {
    float d2 = 0.f;
    for (int b = 0; b < 8; ++b) d2 += std::pow(mapped[b] - v.words()[k * 8 + b], 2.f);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = k;
    }
  }
  EXPECT_EQ(w[0].word, best);
  // An all-zero descriptor carries no information and gets no word.
  const std::vector<float> zero(8, 0.f);
  EXPECT_EQ(v.Assign(zero.data(), w), 0);
}

// The soft assignment is exactly (bit for bit) what a word-by-word scalar loop gives: the m nearest
// words by squared distance summed in dimension order, ties to the lower word, and Gaussian weights
// from those distances. 128 words of 33 dimensions (an FPFH vocabulary's size; 128 is not a multiple
// of every packet width's tail) and 130 words (a tail), on random descriptors.
TEST(VocabularyTest, AssignmentIsExactlyTheWordByWordLoops) {
  for (int num_words : {128, 130}) {
    const int dimension = 33;
    Rng rng(static_cast<std::uint64_t>(num_words));
    std::vector<float> words(static_cast<std::size_t>(num_words) * dimension);
    for (auto& x : words) x = static_cast<float>(rng.Uniform(0.0, 0.4));
    const float sigma2 = 0.05f;
    const int m = 3;
    const Vocabulary v(dimension, words, sigma2, m);
    for (int q = 0; q < 200; ++q) {
      std::vector<float> raw(dimension);
      for (auto& x : raw) x = static_cast<float>(rng.Uniform(0.0, 10.0));
      if (q % 50 == 0) raw.assign(dimension, 1.f);  // many words at similar distances
      std::vector<float> x(dimension);
      ASSERT_TRUE(HellingerMap(raw.data(), dimension, x.data()));
      // Reference: the loops Assign replaced.
      std::vector<std::pair<float, int>> d2;
      for (int w = 0; w < num_words; ++w) {
        float s = 0.f;
        for (int d = 0; d < dimension; ++d) {
          const float e = x[d] - words[static_cast<std::size_t>(w) * dimension + d];
          s += e * e;
        }
        d2.emplace_back(s, w);
      }
      std::stable_sort(d2.begin(), d2.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      double total = 0.0;
      std::vector<float> weight(m);
      for (int i = 0; i < m; ++i) {
        weight[i] = static_cast<float>(std::exp(-(d2[i].first - d2[0].first) / (2.0 * sigma2)));
        total += weight[i];
      }
      WordAssignment out[8];
      ASSERT_EQ(v.Assign(raw.data(), out), m);
      for (int i = 0; i < m; ++i) {
        EXPECT_EQ(out[i].word, d2[i].second) << "query " << q << ", rank " << i;
        EXPECT_EQ(out[i].weight, static_cast<float>(weight[i] / total)) << "query " << q << ", rank " << i;
      }
    }
  }
}

}  // namespace
}  // namespace objscan::recognition
