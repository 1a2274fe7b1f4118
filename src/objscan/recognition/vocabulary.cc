#include "objscan/recognition/vocabulary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Core>

namespace objscan::recognition {

void VocabularyOptions::Validate() const {
  config::Require(num_words >= 2, "recognition.vocabulary.num_words", "must be at least 2");
  config::Require(kmeans_iterations >= 0, "recognition.vocabulary.kmeans_iterations", "must be >= 0");
  config::Require(max_training_descriptors >= num_words, "recognition.vocabulary.max_training_descriptors",
                  "must be >= num_words");
  config::Require(soft_assignments >= 1 && soft_assignments <= 8, "recognition.vocabulary.soft_assignments",
                  "must be in [1, 8]");
}

bool HellingerMap(const float* raw, int dimension, float* out) {
  double sum = 0.0;
  for (int d = 0; d < dimension; ++d) sum += std::max(0.f, raw[d]);
  if (!(sum > 0.0)) return false;
  const double inv = 1.0 / sum;
  for (int d = 0; d < dimension; ++d) out[d] = static_cast<float>(std::sqrt(std::max(0.f, raw[d]) * inv));
  return true;
}

namespace {

inline float SquaredDistance(const float* a, const float* b, int dimension) {
  float s = 0.f;
  for (int d = 0; d < dimension; ++d) {
    const float e = a[d] - b[d];
    s += e * e;
  }
  return s;
}

int NearestWord(const float* x, const std::vector<float>& words, int dimension, float* d2_out) {
  const int k = static_cast<int>(words.size() / dimension);
  int best = 0;
  float best_d2 = std::numeric_limits<float>::infinity();
  for (int w = 0; w < k; ++w) {
    const float d2 = SquaredDistance(x, &words[static_cast<std::size_t>(w) * dimension], dimension);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = w;
    }
  }
  if (d2_out) *d2_out = best_d2;
  return best;
}

}  // namespace

Vocabulary::Vocabulary(int dimension, std::vector<float> words, float sigma2, int soft_assignments)
    : dimension_(dimension), words_(std::move(words)), sigma2_(sigma2), soft_assignments_(soft_assignments) {
  if (dimension_ <= 0 || words_.size() % dimension_ != 0) throw std::invalid_argument("Vocabulary: bad word array");
  const int k = num_words();
  words_by_dimension_.resize(words_.size());
  for (int w = 0; w < k; ++w) {
    for (int d = 0; d < dimension_; ++d) {
      words_by_dimension_[static_cast<std::size_t>(d) * k + w] = words_[static_cast<std::size_t>(w) * dimension_ + d];
    }
  }
}

Vocabulary Vocabulary::Train(const std::vector<float>& descriptors, int dimension, const VocabularyOptions& options,
                             Rng* rng) {
  options.Validate();
  // Hellinger-mapped, non-empty descriptors.
  const std::size_t n_raw = descriptors.size() / dimension;
  std::vector<float> data;
  data.reserve(descriptors.size());
  std::vector<float> mapped(dimension);
  for (std::size_t i = 0; i < n_raw; ++i) {
    if (HellingerMap(&descriptors[i * dimension], dimension, mapped.data()))
      data.insert(data.end(), mapped.begin(), mapped.end());
  }
  std::size_t n = data.size() / dimension;
  if (n == 0) throw std::invalid_argument("Vocabulary::Train: no non-empty descriptors");
  // Seeded subsample (partial Fisher-Yates on rows).
  if (n > static_cast<std::size_t>(options.max_training_descriptors)) {
    const std::size_t m = options.max_training_descriptors;
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = i + static_cast<std::size_t>(rng->Uniform01() * (n - i));
      if (j != i) std::swap_ranges(&data[i * dimension], &data[i * dimension] + dimension, &data[j * dimension]);
    }
    data.resize(m * dimension);
    n = m;
  }
  const int k = static_cast<int>(std::min<std::size_t>(options.num_words, n));

  // k-means++ seeding.
  std::vector<float> words;
  words.reserve(static_cast<std::size_t>(k) * dimension);
  std::vector<float> d2(n, std::numeric_limits<float>::infinity());
  std::size_t first = static_cast<std::size_t>(rng->Uniform01() * n);
  words.insert(words.end(), &data[first * dimension], &data[first * dimension] + dimension);
  for (int w = 1; w < k; ++w) {
    const float* last = &words[static_cast<std::size_t>(w - 1) * dimension];
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      d2[i] = std::min(d2[i], SquaredDistance(&data[i * dimension], last, dimension));
      total += d2[i];
    }
    std::size_t pick = n - 1;
    if (total > 0.0) {
      double r = rng->Uniform01() * total;
      for (std::size_t i = 0; i < n; ++i) {
        r -= d2[i];
        if (r <= 0.0) {
          pick = i;
          break;
        }
      }
    } else {
      pick = static_cast<std::size_t>(rng->Uniform01() * n);
    }
    words.insert(words.end(), &data[pick * dimension], &data[pick * dimension] + dimension);
  }

  // Lloyd iterations; an emptied word is re-seeded at the point farthest from its word.
  std::vector<int> assign(n, 0);
  std::vector<double> sums(static_cast<std::size_t>(k) * dimension);
  std::vector<int> counts(k);
  double mean_d2 = 0.0;
  for (int it = 0; it <= options.kmeans_iterations; ++it) {
    mean_d2 = 0.0;
    std::size_t farthest = 0;
    float farthest_d2 = -1.f;
    for (std::size_t i = 0; i < n; ++i) {
      float d = 0.f;
      assign[i] = NearestWord(&data[i * dimension], words, dimension, &d);
      mean_d2 += d;
      if (d > farthest_d2) {
        farthest_d2 = d;
        farthest = i;
      }
    }
    mean_d2 /= static_cast<double>(n);
    if (it == options.kmeans_iterations) break;
    std::fill(sums.begin(), sums.end(), 0.0);
    std::fill(counts.begin(), counts.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      double* s = &sums[static_cast<std::size_t>(assign[i]) * dimension];
      for (int d = 0; d < dimension; ++d) s[d] += data[i * dimension + d];
      ++counts[assign[i]];
    }
    for (int w = 0; w < k; ++w) {
      float* word = &words[static_cast<std::size_t>(w) * dimension];
      if (counts[w] == 0) {
        std::copy(&data[farthest * dimension], &data[farthest * dimension] + dimension, word);
        continue;
      }
      for (int d = 0; d < dimension; ++d) word[d] = static_cast<float>(sums[static_cast<std::size_t>(w) * dimension + d] / counts[w]);
    }
  }
  return Vocabulary(dimension, std::move(words), static_cast<float>(std::max(mean_d2, 1e-12)), options.soft_assignments);
}

int Vocabulary::Assign(const float* descriptor, WordAssignment* out) const {
  float mapped[64];
  std::vector<float> mapped_heap;
  float* x = mapped;
  if (dimension_ > 64) {
    mapped_heap.resize(dimension_);
    x = mapped_heap.data();
  }
  if (!HellingerMap(descriptor, dimension_, x)) return 0;
  const int k = num_words();
  const int m = std::min(soft_assignments_, k);
  // Squared distances to all words: per dimension, one pass over the words' contiguous coordinates
  // (Eigen's packets: the words in parallel lanes). Each word still sums its terms in dimension order,
  // one rounding per product and per sum as in SquaredDistance: the same floats, several times faster.
  float d2_stack[256];
  std::vector<float> d2_heap;
  float* d2_all = d2_stack;
  if (k > 256) {
    d2_heap.resize(static_cast<std::size_t>(k));
    d2_all = d2_heap.data();
  }
  Eigen::Map<Eigen::ArrayXf> sums(d2_all, k);
  sums.setZero();
  for (int d = 0; d < dimension_; ++d) {
    const Eigen::Map<const Eigen::ArrayXf> column(&words_by_dimension_[static_cast<std::size_t>(d) * k], k);
    sums += (x[d] - column).square();
  }
  // Keep the m best (insertion into a tiny sorted list).
  WordAssignment best[8];
  float best_d2[8];
  int have = 0;
  for (int w = 0; w < k; ++w) {
    const float d2 = d2_all[w];
    if (have == m && d2 >= best_d2[m - 1]) continue;
    int pos = have < m ? have++ : m - 1;
    while (pos > 0 && best_d2[pos - 1] > d2) {
      best_d2[pos] = best_d2[pos - 1];
      best[pos] = best[pos - 1];
      --pos;
    }
    best_d2[pos] = d2;
    best[pos].word = w;
  }
  double total = 0.0;
  for (int i = 0; i < have; ++i) {
    best[i].weight = static_cast<float>(std::exp(-(best_d2[i] - best_d2[0]) / (2.0 * sigma2_)));
    total += best[i].weight;
  }
  for (int i = 0; i < have; ++i) {
    out[i] = best[i];
    out[i].weight = static_cast<float>(best[i].weight / total);
  }
  return have;
}

}  // namespace objscan::recognition
