#pragma once
// Beyond the paper: a small point network (PointNet, Qi et al. 2017: shared per-point layers, a max
// over the points, a classification head) for the category recognizer (category_classifier.h). It
// learns its own description of a partial view from the points themselves, where the forest sees
// only the hand-made ShapeFeatures; the head may read those features too (num_global_features).
//
// Written here rather than with a tensor library: it is small (about 25k weights), trains on the CPU
// in minutes, and its sums run in a fixed order over plain loops, so the same seed gives the same
// weights at any thread count and on any machine that runs the same binary (a library's matrix
// kernels choose their blocking from the machine's caches, which changes the order of float sums).
//
// A point set enters in its own frame (EncodePointSet): centred on its XY centroid, turned so its
// principal horizontal axis is X, heights above the floor and above its own bottom, and the normals'
// absolute components (a scan's normals may face either side). The sign of the X and Y axes is not
// defined by the set: training flips them at random and Predict averages the four flips.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/io/binary_file.h"

namespace objscan::recognition {

constexpr int kPointChannels = 7;  // x, y, height above the floor, height above the set's bottom, |nx|, |ny|, |nz|

// A point set in the network's frame: num_points rows of kPointChannels values.
struct EncodedPointSet {
  std::vector<float> channels;
  int num_points() const { return static_cast<int>(channels.size() / kPointChannels); }
};

// The set (Z up, metres; normals unit, either side) over a floor at height floor_z_m, in the
// network's frame; more than max_points points are thinned to max_points evenly along the list.
EncodedPointSet EncodePointSet(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                               double floor_z_m, int max_points);

struct PointNetworkOptions {
  int point_features = 64;     // width of the first shared per-point layer
  int pooled_features = 128;   // width of the second, maximised over the points
  int head_features = 64;      // width of the head's hidden layer
  int max_points = 128;        // points per set (EncodePointSet)
  int epochs = 24;
  int batch_size = 32;
  double learning_rate = 1e-3;   // Adam's step, decayed to 0 along a half cosine over the epochs
  double weight_decay = 1e-4;    // decoupled (AdamW), per step, times the learning rate
  double keep_min_fraction = 0.7;  // training: each pass keeps a random share in [this, 1] of a set's points
  double yaw_jitter_deg = 10.0;    // training: the set turned by up to this about Z
  double scale_jitter = 0.05;      // training: the set scaled by a factor in [1 - this, 1 + this]
  std::uint64_t seed = 1;
  int threads = 0;  // samples of a batch in parallel; 0 = hardware concurrency. Same weights at any count.

  template <class V>
  void Visit(V& v) {
    v("point_features", point_features);
    v("pooled_features", pooled_features);
    v("head_features", head_features);
    v("max_points", max_points);
    v("epochs", epochs);
    v("batch_size", batch_size);
    v("learning_rate", learning_rate);
    v("weight_decay", weight_decay);
    v("keep_min_fraction", keep_min_fraction);
    v("yaw_jitter_deg", yaw_jitter_deg);
    v("scale_jitter", scale_jitter);
    v("seed", seed);
    v("threads", threads);
  }
  void Validate() const;  // field names as recognition.classifier.network.*
};

// Training data: one encoded set per sample, `global_features` row-major (num_samples x
// num_global_features; empty when 0), labels in [0, num_classes), positive weights.
struct PointNetworkTrainingSet {
  int num_classes = 0;
  int num_global_features = 0;
  std::vector<EncodedPointSet> sets;
  std::vector<float> global_features;
  std::vector<int> labels;
  std::vector<float> weights;
  int num_samples() const { return static_cast<int>(labels.size()); }
};

class PointNetwork {
 public:
  PointNetwork() = default;
  // Minimises the weighted cross-entropy with Adam. Throws InputError when the set is empty or
  // inconsistent (sizes, labels out of range, empty point sets).
  static PointNetwork Train(const PointNetworkTrainingSet& data, const PointNetworkOptions& options);

  bool trained() const { return num_classes_ > 0; }
  int num_classes() const { return num_classes_; }
  int num_global_features() const { return num_global_features_; }
  int max_points() const { return max_points_; }  // what EncodePointSet should thin a query to
  // Class probabilities (num_classes values summing to 1), the mean over the four flips of X and Y;
  // empty when not trained or the set is empty. `global_features` has num_global_features values.
  std::vector<double> Predict(const EncodedPointSet& set, const float* global_features = nullptr) const;

  // Its weights as bytes (the classifier's cache file) and back; Read checks every size.
  void Write(io::BinaryWriter* out) const;
  static PointNetwork Read(io::BinaryReader* in);

  // The mean weighted cross-entropy over a set with its four flips averaged (tests, training logs).
  double Loss(const PointNetworkTrainingSet& data) const;

  // Internals for the tests: the flat parameter vector, and the class probabilities and the gradient
  // of the cross-entropy of one set as given (no flips, no augmentation).
  std::vector<float>& parameters() { return params_; }
  std::vector<double> Probabilities(const EncodedPointSet& set, const float* global_features) const;
  std::vector<float> Gradient(const EncodedPointSet& set, const float* global_features, int label) const;
  static PointNetwork Initialized(int num_classes, int num_global_features, const PointNetworkOptions& options);

 private:
  struct Layout;
  Layout layout() const;
  // One set (its channels as given, `global` standardised): with label >= 0 adds
  // d(weight * cross-entropy)/d(params) to `gradient` and gives the loss; with label < 0 writes the
  // class probabilities to `gradient` instead.
  double Backward(const float* channels, int num_points, const float* global, int label, float weight,
                  float* gradient) const;
  // The head's global features standardised as in training; empty (and `global` not read, so it
  // may be null) when the network reads none.
  std::vector<float> Standardized(const float* global) const;

  int num_classes_ = 0;
  int num_global_features_ = 0;
  int point_features_ = 0, pooled_features_ = 0, head_features_ = 0, max_points_ = 0;
  std::vector<float> params_;
  std::vector<float> global_mean_, global_inverse_std_;
};

}  // namespace objscan::recognition
