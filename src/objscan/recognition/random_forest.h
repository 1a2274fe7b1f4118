#pragma once
// A random forest of classification trees (Breiman 2001) over dense float features: the category
// recognizer's learner (category_classifier.h). Each tree grows on a bootstrap sample with
// `features_per_split` features tried at each node and the weighted Gini impurity's best threshold;
// a leaf holds its class distribution and the forest averages them. Trees are grown in parallel,
// each from its own stream of the seed (DeriveSeed(seed, tree)), so the forest is the same at any
// thread count.
#include <cstdint>
#include <vector>

#include "objscan/io/binary_file.h"

#include "objscan/common/config.h"

namespace objscan::recognition {

struct RandomForestOptions {
  int num_trees = 64;
  int max_depth = 18;
  int min_samples_leaf = 2;
  int features_per_split = 0;  // 0 = round(sqrt(features))
  std::uint64_t seed = 1;
  int threads = 0;  // trees grown in parallel; 0 = hardware concurrency. Same forest at any count.

  template <class V>
  void Visit(V& v) {
    v("num_trees", num_trees);
    v("max_depth", max_depth);
    v("min_samples_leaf", min_samples_leaf);
    v("features_per_split", features_per_split);
    v("seed", seed);
    v("threads", threads);
  }
  void Validate() const;  // field names as recognition.classifier.forest.*
};

// Training data: `features` row-major, num_samples x num_features; `labels` in [0, num_classes);
// `weights` one per sample (class balancing, say), positive.
struct ForestTrainingSet {
  int num_features = 0;
  int num_classes = 0;
  std::vector<float> features;
  std::vector<int> labels;
  std::vector<float> weights;
  int num_samples() const { return static_cast<int>(labels.size()); }
};

class RandomForest {
 public:
  RandomForest() = default;
  // Throws InputError when the set is empty or inconsistent (sizes, labels out of range).
  static RandomForest Train(const ForestTrainingSet& data, const RandomForestOptions& options);

  bool trained() const { return !trees_.empty(); }
  int num_classes() const { return num_classes_; }
  int num_features() const { return num_features_; }
  // Class probabilities (num_classes values summing to 1); empty when not trained.
  std::vector<double> Predict(const float* features) const;

  // The trained forest as bytes (CategoryClassifier's cache file) and back. Read checks every index
  // (features, children, leaves) so that no payload makes Predict read out of bounds; throws
  // InputError through the reader.
  void Write(io::BinaryWriter* out) const;
  static RandomForest Read(io::BinaryReader* in);

 private:
  struct Node {
    std::int32_t feature = -1;  // -1: a leaf
    float threshold = 0.f;      // go left when feature value <= threshold
    std::int32_t left = -1, right = -1;
    std::int32_t distribution = -1;  // leaves: offset of num_classes probabilities in leaf_values_
  };
  struct Tree {
    std::vector<Node> nodes;
    std::vector<float> leaf_values;
  };
  static Tree GrowTree(const ForestTrainingSet& data, const RandomForestOptions& options, int features_per_split,
                       std::uint64_t seed);

  int num_features_ = 0;
  int num_classes_ = 0;
  std::vector<Tree> trees_;
};

}  // namespace objscan::recognition
