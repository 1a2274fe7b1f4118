#pragma once
// Visual-word codebook over local descriptors: k-means (k-means++ seeding, seeded Rng, deterministic)
// on descriptors mapped to the Hellinger space (square roots of the L1-normalised histogram), so that
// Euclidean distance compares histograms well. Each descriptor is soft-assigned to its nearest words.
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/rng.h"

namespace objscan::recognition {

struct VocabularyOptions {
  int num_words = 128;  // measured: 128 words beat 64 on 15 rooms with two vocabulary seeds
  int kmeans_iterations = 15;
  int max_training_descriptors = 40000;  // a seeded random sample of the database descriptors
  int soft_assignments = 3;              // nearest words per keypoint (paper: three)

  template <class V>
  void Visit(V& v) {
    v("num_words", num_words);
    v("kmeans_iterations", kmeans_iterations);
    v("max_training_descriptors", max_training_descriptors);
    v("soft_assignments", soft_assignments);
  }
  void Validate() const;
};

struct WordAssignment {
  std::int32_t word = -1;
  float weight = 0.f;
};

class Vocabulary {
 public:
  Vocabulary() = default;
  // words: num_words x dimension, row-major, in the Hellinger space.
  Vocabulary(int dimension, std::vector<float> words, float sigma2, int soft_assignments);

  // Trains on n = descriptors.size() / dimension raw descriptors (all-zero rows are ignored).
  static Vocabulary Train(const std::vector<float>& descriptors, int dimension, const VocabularyOptions& options,
                          Rng* rng);

  int dimension() const { return dimension_; }
  int num_words() const { return dimension_ > 0 ? static_cast<int>(words_.size() / dimension_) : 0; }
  int soft_assignments() const { return soft_assignments_; }
  const std::vector<float>& words() const { return words_; }
  // Gaussian width of the soft assignment: mean squared distance of a training descriptor to its word.
  float sigma2() const { return sigma2_; }
  bool empty() const { return words_.empty(); }

  // The nearest soft_assignments() words of one raw descriptor with weights summing to 1 (Gaussian in
  // the distance beyond the nearest word). Returns the number written to `out` (0 for an all-zero
  // descriptor, which carries no shape information).
  int Assign(const float* descriptor, WordAssignment* out) const;

 private:
  int dimension_ = 0;
  std::vector<float> words_;
  // words_ transposed (dimension x num_words): Assign sums every word's distance at once, over the
  // dimensions in order, so each word's sum is the same float a word-by-word loop gives.
  std::vector<float> words_by_dimension_;
  float sigma2_ = 1.f;
  int soft_assignments_ = 3;
};

// Maps a raw non-negative histogram descriptor into the Hellinger space; false when it is all zero.
bool HellingerMap(const float* raw, int dimension, float* out);

}  // namespace objscan::recognition
