#include "objscan/recognition/random_forest.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"

namespace objscan::recognition {

void RandomForestOptions::Validate() const {
  config::Require(num_trees >= 1, "recognition.classifier.forest.num_trees", "must be at least 1");
  config::Require(max_depth >= 1, "recognition.classifier.forest.max_depth", "must be at least 1");
  config::Require(min_samples_leaf >= 1, "recognition.classifier.forest.min_samples_leaf", "must be at least 1");
  config::Require(features_per_split >= 0, "recognition.classifier.forest.features_per_split", "must be >= 0");
  config::Require(threads >= 0, "recognition.classifier.forest.threads", "must be >= 0");
}

namespace {

// Weighted Gini impurity times the node weight: W - sum_c w_c^2 / W (0 for an empty side).
double WeightedGini(const std::vector<double>& class_weight, double total) {
  if (total <= 0.0) return 0.0;
  double sum_sq = 0.0;
  for (double w : class_weight) sum_sq += w * w;
  return total - sum_sq / total;
}

}  // namespace

RandomForest::Tree RandomForest::GrowTree(const ForestTrainingSet& data, const RandomForestOptions& options,
                                          int features_per_split, std::uint64_t seed) {
  Rng rng(seed);
  const int n = data.num_samples();
  const int d = data.num_features;
  const int classes = data.num_classes;
  // Bootstrap sample (with replacement), as indices.
  std::vector<int> samples(static_cast<std::size_t>(n));
  for (int& s : samples) s = rng.UniformInt(0, n - 1);
  std::sort(samples.begin(), samples.end());

  Tree tree;
  struct Pending {
    int node, begin, end, depth;
  };
  std::vector<Pending> stack;
  tree.nodes.emplace_back();
  stack.push_back({0, 0, n, 0});
  std::vector<int> feature_order(static_cast<std::size_t>(d));
  std::vector<std::pair<float, int>> sorted;
  std::vector<double> node_weight(static_cast<std::size_t>(classes)), left_weight(static_cast<std::size_t>(classes));
  auto value = [&](int sample, int feature) {
    return data.features[static_cast<std::size_t>(sample) * static_cast<std::size_t>(d) + static_cast<std::size_t>(feature)];
  };
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    std::fill(node_weight.begin(), node_weight.end(), 0.0);
    double total = 0.0;
    for (int i = p.begin; i < p.end; ++i) {
      const int s = samples[static_cast<std::size_t>(i)];
      node_weight[static_cast<std::size_t>(data.labels[static_cast<std::size_t>(s)])] += data.weights[static_cast<std::size_t>(s)];
      total += data.weights[static_cast<std::size_t>(s)];
    }
    const int count = p.end - p.begin;
    int classes_present = 0;
    for (double w : node_weight) classes_present += w > 0.0 ? 1 : 0;
    int best_feature = -1;
    float best_threshold = 0.f;
    if (p.depth < options.max_depth && count >= 2 * options.min_samples_leaf && classes_present > 1) {
      const double parent = WeightedGini(node_weight, total);
      double best_impurity = parent - 1e-12 * std::max(1.0, total);
      // features_per_split distinct features, a partial Fisher-Yates shuffle.
      for (int j = 0; j < d; ++j) feature_order[static_cast<std::size_t>(j)] = j;
      for (int k = 0; k < features_per_split; ++k) {
        const int pick = rng.UniformInt(k, d - 1);
        std::swap(feature_order[static_cast<std::size_t>(k)], feature_order[static_cast<std::size_t>(pick)]);
        const int f = feature_order[static_cast<std::size_t>(k)];
        sorted.clear();
        for (int i = p.begin; i < p.end; ++i) {
          const int s = samples[static_cast<std::size_t>(i)];
          sorted.emplace_back(value(s, f), s);
        }
        std::sort(sorted.begin(), sorted.end());
        if (sorted.front().first == sorted.back().first) continue;
        std::fill(left_weight.begin(), left_weight.end(), 0.0);
        double left_total = 0.0;
        for (int i = 0; i + 1 < count; ++i) {
          const int s = sorted[static_cast<std::size_t>(i)].second;
          const double w = data.weights[static_cast<std::size_t>(s)];
          left_weight[static_cast<std::size_t>(data.labels[static_cast<std::size_t>(s)])] += w;
          left_total += w;
          if (i + 1 < options.min_samples_leaf || count - (i + 1) < options.min_samples_leaf) continue;
          if (sorted[static_cast<std::size_t>(i)].first == sorted[static_cast<std::size_t>(i + 1)].first) continue;
          // Right side's Gini from the node's and the left's class weights.
          double left_sq = 0.0, right_sq = 0.0;
          for (int c = 0; c < classes; ++c) {
            const double l = left_weight[static_cast<std::size_t>(c)];
            const double r = node_weight[static_cast<std::size_t>(c)] - l;
            left_sq += l * l;
            right_sq += r * r;
          }
          const double right_total = total - left_total;
          if (left_total <= 0.0 || right_total <= 0.0) continue;
          const double impurity = (left_total - left_sq / left_total) + (right_total - right_sq / right_total);
          if (impurity < best_impurity) {
            best_impurity = impurity;
            best_feature = f;
            best_threshold = 0.5f * (sorted[static_cast<std::size_t>(i)].first + sorted[static_cast<std::size_t>(i + 1)].first);
            // The midpoint of two adjacent floats may round to the upper one.
            if (!(best_threshold < sorted[static_cast<std::size_t>(i + 1)].first)) {
              best_threshold = sorted[static_cast<std::size_t>(i)].first;
            }
          }
        }
      }
    }
    if (best_feature < 0) {
      Node& leaf = tree.nodes[static_cast<std::size_t>(p.node)];
      leaf.distribution = static_cast<std::int32_t>(tree.leaf_values.size());
      for (double w : node_weight) tree.leaf_values.push_back(static_cast<float>(w / total));
      continue;
    }
    const auto middle = std::partition(samples.begin() + p.begin, samples.begin() + p.end,
                                       [&](int s) { return value(s, best_feature) <= best_threshold; });
    const int split = static_cast<int>(middle - samples.begin());
    const int left = static_cast<int>(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    Node& node = tree.nodes[static_cast<std::size_t>(p.node)];
    node.feature = best_feature;
    node.threshold = best_threshold;
    node.left = left;
    node.right = left + 1;
    // Keep each side's samples in index order so the partition does not depend on the sort.
    std::sort(samples.begin() + p.begin, samples.begin() + split);
    std::sort(samples.begin() + split, samples.begin() + p.end);
    stack.push_back({left + 1, split, p.end, p.depth + 1});
    stack.push_back({left, p.begin, split, p.depth + 1});
  }
  return tree;
}

RandomForest RandomForest::Train(const ForestTrainingSet& data, const RandomForestOptions& options) {
  options.Validate();
  const int n = data.num_samples();
  if (n == 0 || data.num_features <= 0 || data.num_classes <= 0) {
    throw InputError("random forest: no training samples");
  }
  if (data.features.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(data.num_features) ||
      data.weights.size() != static_cast<std::size_t>(n)) {
    throw InputError("random forest: features, labels and weights differ in length");
  }
  for (int i = 0; i < n; ++i) {
    const int label = data.labels[static_cast<std::size_t>(i)];
    const float w = data.weights[static_cast<std::size_t>(i)];
    if (label < 0 || label >= data.num_classes) throw InputError("random forest: a label is out of range");
    if (!(w > 0.f) || !std::isfinite(w)) throw InputError("random forest: a sample weight is not positive");
  }
  for (float v : data.features) {
    if (!std::isfinite(v)) throw InputError("random forest: a feature value is not finite");
  }
  RandomForest forest;
  forest.num_features_ = data.num_features;
  forest.num_classes_ = data.num_classes;
  const int features_per_split =
      options.features_per_split > 0
          ? std::min(options.features_per_split, data.num_features)
          : std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(data.num_features)))));
  forest.trees_.resize(static_cast<std::size_t>(options.num_trees));
  int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, options.num_trees);
  std::atomic<int> next{0};
  auto work = [&] {
    for (int t = next++; t < options.num_trees; t = next++) {
      forest.trees_[static_cast<std::size_t>(t)] =
          GrowTree(data, options, features_per_split, DeriveSeed(options.seed, static_cast<std::uint64_t>(t)));
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return forest;
}

std::vector<double> RandomForest::Predict(const float* features) const {
  std::vector<double> p;
  if (!trained()) return p;
  p.assign(static_cast<std::size_t>(num_classes_), 0.0);
  for (const Tree& tree : trees_) {
    int i = 0;
    while (tree.nodes[static_cast<std::size_t>(i)].feature >= 0) {
      const Node& node = tree.nodes[static_cast<std::size_t>(i)];
      i = features[node.feature] <= node.threshold ? node.left : node.right;
    }
    const float* leaf = &tree.leaf_values[static_cast<std::size_t>(tree.nodes[static_cast<std::size_t>(i)].distribution)];
    for (int c = 0; c < num_classes_; ++c) p[static_cast<std::size_t>(c)] += leaf[c];
  }
  for (double& v : p) v /= static_cast<double>(trees_.size());
  return p;
}

void RandomForest::Write(io::BinaryWriter* out) const {
  out->Pod(static_cast<std::int32_t>(num_features_));
  out->Pod(static_cast<std::int32_t>(num_classes_));
  out->Pod(static_cast<std::uint32_t>(trees_.size()));
  for (const Tree& tree : trees_) {
    out->Pod(static_cast<std::uint32_t>(tree.nodes.size()));
    for (const Node& node : tree.nodes) {
      out->Pod(node.feature);
      out->Pod(node.threshold);
      out->Pod(node.left);
      out->Pod(node.right);
      out->Pod(node.distribution);
    }
    out->Vector(tree.leaf_values);
  }
}

RandomForest RandomForest::Read(io::BinaryReader* in) {
  RandomForest forest;
  forest.num_features_ = in->Pod<std::int32_t>("forest");
  forest.num_classes_ = in->Pod<std::int32_t>("forest");
  if (forest.num_features_ < 1 || forest.num_classes_ < 1) in->Fail("forest without features or classes");
  const std::uint32_t num_trees = in->Count(4, "forest trees");
  forest.trees_.resize(num_trees);
  for (Tree& tree : forest.trees_) {
    constexpr std::size_t kNodeBytes = 4 + 4 + 4 + 4 + 4;
    tree.nodes.resize(in->Count(kNodeBytes, "forest nodes"));
    for (Node& node : tree.nodes) {
      node.feature = in->Pod<std::int32_t>("forest nodes");
      node.threshold = in->Pod<float>("forest nodes");
      node.left = in->Pod<std::int32_t>("forest nodes");
      node.right = in->Pod<std::int32_t>("forest nodes");
      node.distribution = in->Pod<std::int32_t>("forest nodes");
    }
    tree.leaf_values = in->Vector<float>("forest leaves");
    if (tree.nodes.empty()) in->Fail("a forest tree without nodes");
    // Children come after their parent (so every walk ends) and leaves point inside the leaf values.
    const auto num_nodes = static_cast<std::int64_t>(tree.nodes.size());
    for (std::int64_t i = 0; i < num_nodes; ++i) {
      const Node& node = tree.nodes[static_cast<std::size_t>(i)];
      if (node.feature >= 0) {
        if (node.feature >= forest.num_features_ || node.left <= i || node.right <= i || node.left >= num_nodes ||
            node.right >= num_nodes) {
          in->Fail("a forest node's feature or children out of range");
        }
      } else if (node.distribution < 0 ||
                 static_cast<std::size_t>(node.distribution) + static_cast<std::size_t>(forest.num_classes_) >
                     tree.leaf_values.size()) {
        in->Fail("a forest leaf out of range");
      }
    }
  }
  return forest;
}

}  // namespace objscan::recognition
