#include "objscan/recognition/vocabulary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

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

}  // namespace
}  // namespace objscan::recognition
