#include "objscan/recognition/category_classifier.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "objscan/common/error.h"
#include "objscan/common/parallel_for.h"
#include "objscan/common/rng.h"
#include "objscan/io/binary_file.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/virtual_scan.h"

namespace objscan::recognition {

void CategoryClassifierOptions::Validate() const {
  config::Require(method == "forest" || method == "softmax" || method == "network" || method == "forest+network",
                  "recognition.classifier.method",
                  "must be 'forest', 'softmax', 'network' or 'forest+network', not '" + method + "'");
  config::Require(training_views == "keypoints" || training_views == "rendered", "recognition.classifier.training_views",
                  "must be 'keypoints' or 'rendered', not '" + training_views + "'");
  config::Require(balance == "samples" || balance == "models", "recognition.classifier.balance",
                  "must be 'samples' or 'models', not '" + balance + "'");
  for (double depth : validation_depths) {
    config::Require(depth >= 1.0 && depth <= 64.0 && depth == std::floor(depth), "recognition.classifier.validation_depths",
                    "every depth must be a whole number from 1 to 64");
  }
  config::Require(validation_trees >= 1, "recognition.classifier.validation_trees", "must be at least 1");
  config::Require(half_views_per_model >= 0, "recognition.classifier.half_views_per_model", "must be >= 0");
  forest.Validate();
  network.Validate();
  config::Require(views_per_model >= 0, "recognition.classifier.views_per_model", "must be >= 0");
  config::RequireInRange("recognition.classifier.low_elevation_deg", low_elevation_deg, -89.0, 89.0);
  config::RequireInRange("recognition.classifier.high_elevation_deg", high_elevation_deg, -89.0, 89.0);
  config::RequireInRange("recognition.classifier.visible_min_cos", visible_min_cos, -1.0, 1.0);
  config::Require(iterations >= 1, "recognition.classifier.iterations", "must be at least 1");
  config::RequirePositive("recognition.classifier.learning_rate", learning_rate);
  config::RequireNonNegative("recognition.classifier.l2_weight", l2_weight);
}

namespace {

// The q-quantile of `values` (reordered in place).
float Quantile(std::vector<float>* values, double q) {
  const std::size_t k = std::min(values->size() - 1, static_cast<std::size_t>(q * static_cast<double>(values->size())));
  std::nth_element(values->begin(), values->begin() + static_cast<std::ptrdiff_t>(k), values->end());
  return (*values)[k];
}

// Band edges (m above the shape's bottom) of the height histogram and of the horizontal surfaces.
constexpr std::array<float, 9> kHeightEdgesM = {0.15f, 0.3f, 0.45f, 0.6f, 0.75f, 0.9f, 1.1f, 1.4f, 1.8f};
constexpr std::array<float, 4> kSurfaceEdgesM = {0.3f, 0.6f, 0.9f, 1.3f};

template <std::size_t N>
int Band(const std::array<float, N>& edges, float height_m) {
  return static_cast<int>(std::upper_bound(edges.begin(), edges.end(), height_m) - edges.begin());
}

// Bands of height above the floor for horizontal surfaces: seats near 0.45 m, tables near 0.75 m,
// counters near 0.9 m, shelves and tops higher up.
constexpr std::array<float, 8> kFloorSurfaceEdgesM = {0.15f, 0.35f, 0.55f, 0.7f, 0.85f, 1.05f, 1.4f, 1.9f};
// D2: distances between point pairs, in metres.
constexpr std::array<float, 9> kPairDistanceEdgesM = {0.05f, 0.1f, 0.2f, 0.3f, 0.45f, 0.65f, 0.9f, 1.3f, 1.8f};
constexpr std::array<float, 3> kPairCosEdges = {0.25f, 0.5f, 0.75f};
constexpr int kPairsPerPoint = 8;

constexpr float kHorizontalMinAbsNz = 0.7f;  // |n_z| above this: a surface facing up or down
constexpr float kVerticalMaxAbsNz = 0.3f;    // below this: a vertical surface
constexpr double kTrim = 0.02;               // extents between the 2% and 98% quantiles

// Scores -> probabilities in place (a vector or a matrix row), shifted by the maximum for range.
template <class V>
void Softmax(V&& scores) {
  scores = (scores.array() - scores.maxCoeff()).exp();
  scores /= scores.sum();
}

}  // namespace

std::array<float, kNumShapeFeatures> ShapeFeatures(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<Eigen::Vector3f>& normals, double floor_z_m) {
  std::array<float, kNumShapeFeatures> f{};
  const std::size_t n = std::min(points.size(), normals.size());
  if (n < 8) return f;
  std::vector<float> values(n);
  for (std::size_t i = 0; i < n; ++i) values[i] = points[i].z();
  const float bottom = Quantile(&values, kTrim);
  const float top = Quantile(&values, 1.0 - kTrim);
  const float height = std::max(0.f, top - bottom);
  // Horizontal principal axes.
  Eigen::Vector2d mean_xy = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) mean_xy += points[i].head<2>().cast<double>();
  mean_xy /= static_cast<double>(n);
  Eigen::Matrix2d cov_xy = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d = points[i].head<2>().cast<double>() - mean_xy;
    cov_xy += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig_xy(cov_xy);
  float extent[2];
  for (int a = 0; a < 2; ++a) {
    const Eigen::Vector2d axis = eig_xy.eigenvectors().col(a);
    for (std::size_t i = 0; i < n; ++i) values[i] = static_cast<float>((points[i].head<2>().cast<double>() - mean_xy).dot(axis));
    const float lo = Quantile(&values, kTrim);
    extent[a] = Quantile(&values, 1.0 - kTrim) - lo;
  }
  const float long_side = std::max(extent[0], extent[1]);
  const float short_side = std::min(extent[0], extent[1]);
  int k = 0;
  f[k++] = std::log(height + 0.05f);
  f[k++] = std::log(long_side + 0.05f);
  f[k++] = std::log(short_side + 0.05f);
  f[k++] = short_side / (long_side + 1e-3f);
  f[k++] = height / (height + long_side + 1e-3f);
  // How the surface spreads over height, and where it faces up or down.
  std::array<float, kHeightEdgesM.size() + 1> height_share{};
  std::array<float, kSurfaceEdgesM.size() + 1> horizontal_share{};
  float vertical = 0.f, in_top_fifth = 0.f, radial = 0.f;
  std::vector<float> horizontal_heights;
  const double half_long_side = std::max(1e-3f, 0.5f * long_side);
  for (std::size_t i = 0; i < n; ++i) {
    const float h = std::clamp(points[i].z() - bottom, 0.f, height);
    height_share[static_cast<std::size_t>(Band(kHeightEdgesM, h))] += 1.f;
    const float nz = std::abs(normals[i].z());
    if (nz > kHorizontalMinAbsNz) {
      horizontal_share[static_cast<std::size_t>(Band(kSurfaceEdgesM, h))] += 1.f;
      horizontal_heights.push_back(h);
    }
    if (nz < kVerticalMaxAbsNz) vertical += 1.f;
    if (h > 0.8f * height) in_top_fifth += 1.f;
    radial += static_cast<float>((points[i].head<2>().cast<double>() - mean_xy).norm() / half_long_side);
  }
  const float inv_n = 1.f / static_cast<float>(n);
  for (float s : height_share) f[k++] = s * inv_n;
  for (float s : horizontal_share) f[k++] = s * inv_n;
  f[k++] = vertical * inv_n;
  f[k++] = horizontal_heights.empty() ? 0.f : Quantile(&horizontal_heights, 0.5);
  // Flatness: the 3D spread's smaller principal variances against the largest.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) mean += points[i].cast<double>();
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = points[i].cast<double>() - mean;
    cov += d * d.transpose();
  }
  const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues();  // ascending
  const double largest = std::max(lambda(2), 1e-12);
  f[k++] = static_cast<float>(lambda(1) / largest);
  f[k++] = static_cast<float>(lambda(0) / largest);
  f[k++] = in_top_fifth * inv_n;
  f[k++] = radial * inv_n;
  // Above the floor.
  const float floor_z = static_cast<float>(floor_z_m);
  f[k++] = std::clamp(bottom - floor_z, -0.5f, 3.f);
  f[k++] = std::clamp(top - floor_z, -0.5f, 3.f);
  std::array<float, kFloorSurfaceEdgesM.size() + 1> floor_surface_share{};
  std::vector<float> horizontal_above_floor;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(normals[i].z()) <= kHorizontalMinAbsNz) continue;
    const float h = points[i].z() - floor_z;
    floor_surface_share[static_cast<std::size_t>(Band(kFloorSurfaceEdgesM, h))] += 1.f;
    horizontal_above_floor.push_back(h);
  }
  for (float s : floor_surface_share) f[k++] = s * inv_n;
  // Point pairs: each point with kPairsPerPoint others at fixed strides through the set (the
  // keypoints' order carries no geometry, so these are as good as random pairs and need no seed).
  std::array<float, kPairDistanceEdgesM.size() + 1> distance_share{};
  std::array<float, kPairCosEdges.size() + 1> cos_share{};
  for (std::size_t i = 0; i < n; ++i) {
    for (int p = 1; p <= kPairsPerPoint; ++p) {
      const std::size_t j = (i + 1 + static_cast<std::size_t>(static_cast<double>(n - 1) * p / (kPairsPerPoint + 1))) % n;
      if (j == i) continue;
      distance_share[static_cast<std::size_t>(Band(kPairDistanceEdgesM, (points[i] - points[j]).norm()))] += 1.f;
      cos_share[static_cast<std::size_t>(Band(kPairCosEdges, std::abs(normals[i].dot(normals[j]))))] += 1.f;
    }
  }
  const float inv_pairs = 1.f / static_cast<float>(n * kPairsPerPoint);
  for (float s : distance_share) f[k++] = s * inv_pairs;
  for (float s : cos_share) f[k++] = s * inv_pairs;
  if (horizontal_above_floor.empty()) {
    f[k++] = -0.5f;
    f[k++] = -0.5f;
  } else {
    f[k++] = std::clamp(Quantile(&horizontal_above_floor, 0.25), -0.5f, 3.f);
    f[k++] = std::clamp(Quantile(&horizontal_above_floor, 0.75), -0.5f, 3.f);
  }
  // Layout: where the surface lies in the shape's own box, on a kLayoutCells^3 grid along the long
  // side, the short side and the height. The bands above see a chair's seat and a table's top at
  // their heights, not whether the tall part stands at one side (a chair's back, a bed's head) or
  // over all of it (a table, a cabinet). Each horizontal axis is turned so that the taller half of
  // the surface lies on its positive side: the layout does not depend on how the shape is turned.
  // Points spread over the two nearest cells of each axis (tent weights), so a point moving a little
  // moves the features a little.
  const Eigen::Vector2d axis_long = eig_xy.eigenvectors().col(1), axis_short = eig_xy.eigenvectors().col(0);
  std::vector<Eigen::Vector3f> local(n);  // (along long, along short, height above bottom)
  double lean_long = 0.0, lean_short = 0.0, mean_h = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean_h += points[i].z() - bottom;
  mean_h /= static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d = points[i].head<2>().cast<double>() - mean_xy;
    const double h = points[i].z() - bottom;
    local[i] = Eigen::Vector3f(static_cast<float>(d.dot(axis_long)), static_cast<float>(d.dot(axis_short)),
                               static_cast<float>(h));
    lean_long += local[i].x() * (h - mean_h);
    lean_short += local[i].y() * (h - mean_h);
  }
  std::array<float, 3> lo{}, span{};
  for (int a = 0; a < 3; ++a) {
    for (std::size_t i = 0; i < n; ++i) values[i] = local[i][a] * (a == 0 && lean_long < 0.0 ? -1.f : 1.f) *
                                                     (a == 1 && lean_short < 0.0 ? -1.f : 1.f);
    lo[static_cast<std::size_t>(a)] = Quantile(&values, kTrim);
    span[static_cast<std::size_t>(a)] = std::max(1e-3f, Quantile(&values, 1.0 - kTrim) - lo[static_cast<std::size_t>(a)]);
  }
  constexpr int c = kLayoutCells;
  std::array<float, c * c * c> occupancy{};
  std::array<float, c * c> column_top{}, column_horizontal{}, column_weight{};
  auto tent = [](float t, int* cell, float* upper_weight) {  // t in [0, 1] -> two cells and a weight
    const float x = std::clamp(t * c - 0.5f, 0.f, static_cast<float>(c - 1));
    *cell = std::min(static_cast<int>(x), c - 2);
    *upper_weight = x - static_cast<float>(*cell);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const float u = (local[i].x() * (lean_long < 0.0 ? -1.f : 1.f) - lo[0]) / span[0];
    const float v = (local[i].y() * (lean_short < 0.0 ? -1.f : 1.f) - lo[1]) / span[1];
    const float h = std::clamp((local[i].z() - lo[2]) / span[2], 0.f, 1.f);
    int cu, cv, ch;
    float wu, wv, wh;
    tent(u, &cu, &wu);
    tent(v, &cv, &wv);
    tent(h, &ch, &wh);
    const bool horizontal = std::abs(normals[i].z()) > kHorizontalMinAbsNz;
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        const float w_col = (a ? wu : 1.f - wu) * (b ? wv : 1.f - wv);
        const int col = (cu + a) * c + (cv + b);
        column_weight[static_cast<std::size_t>(col)] += w_col;
        column_top[static_cast<std::size_t>(col)] = std::max(column_top[static_cast<std::size_t>(col)], w_col > 0.25f ? h : 0.f);
        if (horizontal) column_horizontal[static_cast<std::size_t>(col)] += w_col;
        for (int e = 0; e < 2; ++e) {
          occupancy[static_cast<std::size_t>(col * c + ch + e)] += w_col * (e ? wh : 1.f - wh);
        }
      }
    }
  }
  for (float s : occupancy) f[k++] = s * inv_n;
  for (float s : column_top) f[k++] = s;
  for (std::size_t col = 0; col < column_horizontal.size(); ++col) {
    f[k++] = column_weight[col] > 0.f ? column_horizontal[col] / column_weight[col] : 0.f;
  }
  return f;
}
static_assert(kNumRelativeShapeFeatures == 26 &&
                  kNumShapeFeatures == 26 + 2 + 9 + 10 + 4 + 2 + kLayoutCells * kLayoutCells * (kLayoutCells + 2),
              "ShapeFeatures' layout and its counts disagree");

CategoryClassifier CategoryClassifier::Fit(const std::vector<std::array<float, kNumShapeFeatures>>& features,
                                           const std::vector<world::Category>& labels,
                                           const CategoryClassifierOptions& options, const std::vector<int>& groups,
                                           const std::vector<EncodedPointSet>* point_sets) {
  options.Validate();
  if (options.uses_network() && !features.empty() && (point_sets == nullptr || point_sets->size() != features.size())) {
    throw std::invalid_argument("CategoryClassifier::Fit: the network needs one point set per sample");
  }
  CategoryClassifier c;
  if (features.empty() || features.size() != labels.size()) return c;
  std::array<int, world::kNumCategories> count{};
  for (world::Category l : labels) ++count[static_cast<std::size_t>(world::CategoryId(l))];
  std::array<int, world::kNumCategories> class_of{};
  for (int id = 0; id < world::kNumCategories; ++id) {
    class_of[static_cast<std::size_t>(id)] = -1;
    if (count[static_cast<std::size_t>(id)] == 0) continue;
    class_of[static_cast<std::size_t>(id)] = static_cast<int>(c.classes_.size());
    c.classes_.push_back(static_cast<world::Category>(id));
  }
  const int n = static_cast<int>(features.size());
  const int d = kNumShapeFeatures;
  const int classes = static_cast<int>(c.classes_.size());
  // Standardised design matrix with a bias column.
  Eigen::MatrixXd x(n, d + 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < d; ++j) x(i, j) = features[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  c.mean_ = x.leftCols(d).colwise().mean().transpose();
  c.inverse_std_.resize(d);
  for (int j = 0; j < d; ++j) {
    const double var = (x.col(j).array() - c.mean_(j)).square().mean();
    c.inverse_std_(j) = var > 1e-12 ? 1.0 / std::sqrt(var) : 0.0;
    x.col(j) = (x.col(j).array() - c.mean_(j)) * c.inverse_std_(j);
  }
  x.col(d).setOnes();
  // One-hot targets, each class weighing the same in all.
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(n, classes);
  Eigen::VectorXd w(n);
  const bool by_models = options.balance == "models" && groups.size() == features.size();
  std::map<int, int> group_size;                    // samples per group
  std::array<std::set<int>, world::kNumCategories> groups_of;  // groups per class
  if (by_models) {
    for (int i = 0; i < n; ++i) {
      ++group_size[groups[static_cast<std::size_t>(i)]];
      groups_of[static_cast<std::size_t>(world::CategoryId(labels[static_cast<std::size_t>(i)]))].insert(
          groups[static_cast<std::size_t>(i)]);
    }
  }
  for (int i = 0; i < n; ++i) {
    const int id = world::CategoryId(labels[static_cast<std::size_t>(i)]);
    y(i, class_of[static_cast<std::size_t>(id)]) = 1.0;
    w(i) = by_models ? 1.0 / (static_cast<double>(classes) * groups_of[static_cast<std::size_t>(id)].size() *
                              group_size[groups[static_cast<std::size_t>(i)]])
                     : 1.0 / (static_cast<double>(classes) * count[static_cast<std::size_t>(id)]);
  }
  if (classes == 1) return c;
  if (options.uses_network()) {
    PointNetworkTrainingSet data;
    data.num_classes = classes;
    data.num_global_features = options.network_shape_features ? d : 0;
    for (int i = 0; i < n; ++i) {
      const EncodedPointSet& set = (*point_sets)[static_cast<std::size_t>(i)];
      if (set.num_points() == 0) continue;
      data.sets.push_back(set);
      if (options.network_shape_features) {
        const auto& row = features[static_cast<std::size_t>(i)];
        data.global_features.insert(data.global_features.end(), row.begin(), row.end());
      }
      data.labels.push_back(class_of[static_cast<std::size_t>(world::CategoryId(labels[static_cast<std::size_t>(i)]))]);
      data.weights.push_back(static_cast<float>(w(i) * n));
    }
    if (data.num_samples() > 0) c.network_ = PointNetwork::Train(data, options.network);
    c.network_shape_features_ = options.network_shape_features;
  }
  if (options.uses_forest()) {
    ForestTrainingSet data;
    data.num_features = d;
    data.num_classes = classes;
    data.features.reserve(static_cast<std::size_t>(n) * d);
    for (const auto& row : features) data.features.insert(data.features.end(), row.begin(), row.end());
    for (int i = 0; i < n; ++i) {
      data.labels.push_back(class_of[static_cast<std::size_t>(world::CategoryId(labels[static_cast<std::size_t>(i)]))]);
      data.weights.push_back(static_cast<float>(w(i) * n));
    }
    c.forest_ = RandomForest::Train(data, options.forest);
    c.max_depth_ = options.forest.max_depth;
  }
  if (options.method != "softmax") return c;
  c.weights_ = Eigen::MatrixXd::Zero(classes, d + 1);
  Eigen::MatrixXd p(n, classes);
  for (int it = 0; it < options.iterations; ++it) {
    p.noalias() = x * c.weights_.transpose();
    for (int i = 0; i < n; ++i) Softmax(p.row(i));
    const Eigen::MatrixXd residual = (p - y).array().colwise() * w.array();
    Eigen::MatrixXd gradient = residual.transpose() * x;
    gradient.leftCols(d) += options.l2_weight * c.weights_.leftCols(d);
    c.weights_ -= options.learning_rate * gradient;
  }
  return c;
}

namespace {

// The depth of validation_depths whose forests name held-out samples best: the mean over folds of
// the accuracy per class (classes the fold's training part and held-out part both have). Folds are
// the sources (one per training database) when there are two or more, else two halves of the models.
// Nothing when no fold could be scored (one model per category, say).
std::optional<int> SelectDepthByHeldOutValidation(const std::vector<std::array<float, kNumShapeFeatures>>& features,
                                   const std::vector<world::Category>& labels, const std::vector<int>& groups,
                                   const std::vector<int>& sources, const CategoryClassifierOptions& options) {
  std::set<int> distinct_sources(sources.begin(), sources.end());
  std::vector<int> fold(features.size());
  int num_folds = 0;
  if (distinct_sources.size() >= 2) {
    std::map<int, int> fold_of_source;
    for (int s : distinct_sources) fold_of_source[s] = num_folds++;
    for (std::size_t i = 0; i < fold.size(); ++i) fold[i] = fold_of_source[sources[i]];
  } else {
    num_folds = 2;
    for (std::size_t i = 0; i < fold.size(); ++i) {
      fold[i] = static_cast<int>(DeriveSeed(options.seed, static_cast<std::uint64_t>(groups[i])) % 2);
    }
  }
  CategoryClassifierOptions fit_options = options;
  fit_options.method = "forest";  // the depth is the forest's
  fit_options.validation_depths.clear();
  fit_options.forest.num_trees = std::min(options.forest.num_trees, options.validation_trees);
  // Each fold's training part, gathered once for every depth.
  struct TrainingPart {
    std::vector<std::array<float, kNumShapeFeatures>> features;
    std::vector<world::Category> labels;
    std::vector<int> groups;
  };
  std::vector<TrainingPart> parts(static_cast<std::size_t>(num_folds));
  for (std::size_t i = 0; i < features.size(); ++i) {
    for (int f = 0; f < num_folds; ++f) {
      if (fold[i] == f) continue;
      TrainingPart& part = parts[static_cast<std::size_t>(f)];
      part.features.push_back(features[i]);
      part.labels.push_back(labels[i]);
      part.groups.push_back(groups[i]);
    }
  }
  std::optional<int> best_depth;
  double best_score = -1.0;
  for (double depth_value : options.validation_depths) {
    const int depth = static_cast<int>(depth_value);
    fit_options.forest.max_depth = depth;
    double score_sum = 0.0;
    int scored_folds = 0;
    for (int f = 0; f < num_folds; ++f) {
      const TrainingPart& part = parts[static_cast<std::size_t>(f)];
      const CategoryClassifier c = CategoryClassifier::Fit(part.features, part.labels, fit_options, part.groups);
      if (!c.trained()) continue;
      std::array<int, world::kNumCategories> right{}, seen{};
      for (std::size_t i = 0; i < features.size(); ++i) {
        if (fold[i] != f) continue;
        const auto k = static_cast<std::size_t>(world::CategoryId(labels[i]));
        if (std::find(c.classes().begin(), c.classes().end(), labels[i]) == c.classes().end()) continue;
        const CategoryClassifier::Probabilities p = c.Classify(features[i]);
        ++seen[k];
        if (std::max_element(p.begin(), p.end()) - p.begin() == static_cast<std::ptrdiff_t>(k)) ++right[k];
      }
      double accuracy_sum = 0.0;
      int classes = 0;
      for (std::size_t k = 0; k < seen.size(); ++k) {
        if (seen[k] == 0) continue;
        accuracy_sum += static_cast<double>(right[k]) / seen[k];
        ++classes;
      }
      if (classes == 0) continue;
      score_sum += accuracy_sum / classes;
      ++scored_folds;
    }
    if (scored_folds == 0) continue;
    const double score = score_sum / scored_folds;
    if (score > best_score) {
      best_score = score;
      best_depth = depth;
    }
  }
  return best_depth;
}

}  // namespace

namespace {

// Training view v of a full model: azimuths evenly around it, alternately at the low and the high
// elevation; the half views come after the whole ones, turned by half a step.
struct TrainingView {
  bool half;
  double azimuth_rad, elevation_rad;
};
TrainingView TrainingViewAt(const CategoryClassifierOptions& options, int v) {
  const bool half = v >= options.views_per_model;
  const int u = half ? v - options.views_per_model : v;
  const int per_ring = half ? options.half_views_per_model : options.views_per_model;
  return {half, 2.0 * M_PI * (u + (half ? 0.5 : 0.0)) / per_ring,
          (u % 2 == 0 ? options.low_elevation_deg : options.high_elevation_deg) * M_PI / 180.0};
}

// A full model whose training views are rendered from its stored mesh (training_views "rendered").
struct RenderJob {
  const ModelDatabase* database;
  const DatabaseEntry* entry;
  int source, group;
};

// The rendered views of each job, appended in job order: whole views at the training azimuths and
// elevations, then halves of views (HalfOf, as the evaluation cuts its pieces), each fused alone
// with the sensor's noise and described by keypoints as Recognizer::Describe describes a query.
// Models are rendered in parallel (forest.threads), each from its own seed: the same samples at
// any thread count.
void AddRenderedViews(const std::vector<RenderJob>& jobs, const CategoryClassifierOptions& options,
                      std::vector<std::array<float, kNumShapeFeatures>>* features, std::vector<world::Category>* labels,
                      std::vector<int>* groups, std::vector<int>* sources, std::vector<EncodedPointSet>* point_sets) {
  if (jobs.empty()) return;
  std::vector<std::vector<std::array<float, kNumShapeFeatures>>> per_job(jobs.size());
  std::vector<std::vector<EncodedPointSet>> sets_per_job(jobs.size());
  VirtualScanOptions scan;
  scan.sensor.threads = 1;  // parallel over models instead
  const int n_jobs = static_cast<int>(jobs.size());
  ParallelForBlocks(n_jobs, options.forest.threads, [&](int j) {
    const RenderJob& job = jobs[static_cast<std::size_t>(j)];
    const DatabaseModel& model = job.database->models()[static_cast<std::size_t>(job.entry->model_index)];
    const DatabaseSettings& settings = job.database->settings();
    Rng rng(DeriveSeed(options.seed, static_cast<std::uint64_t>(j)));
    const geometry::Aabb3 bounds = geometry::Bounds(model.mesh);
    const int views = options.views_per_model + options.half_views_per_model;
    for (int v = 0; v < views; ++v) {
      const TrainingView view = TrainingViewAt(options, v);
      geometry::PointCloud surface = ScanSurface(
          model.mesh, {ViewFrom(bounds, view.azimuth_rad, view.elevation_rad, scan)}, scan, /*noise=*/true, &rng);
      if (view.half) surface = HalfOf(surface, &rng);
      if (surface.points.size() < 8 || !surface.HasNormals()) continue;
      Rng keypoint_rng(settings.keypoint_seed);  // as Recognizer::Describe
      std::vector<Eigen::Vector3f> points, normals;
      for (int i : SampleKeypointsLloyd(surface.points, settings.keypoints, &keypoint_rng)) {
        points.push_back(surface.points[static_cast<std::size_t>(i)]);
        normals.push_back(surface.normals[static_cast<std::size_t>(i)]);
      }
      if (points.size() < 8) continue;
      double floor_z_m = 0.0;
      if (!model.support_heights_m.empty()) {
        floor_z_m = -static_cast<double>(
            model.support_heights_m[static_cast<std::size_t>(rng.UniformInt(0, static_cast<int>(model.support_heights_m.size()) - 1))]);
      }
      per_job[static_cast<std::size_t>(j)].push_back(ShapeFeatures(points, normals, floor_z_m));
      if (point_sets != nullptr) {
        sets_per_job[static_cast<std::size_t>(j)].push_back(
            EncodePointSet(points, normals, floor_z_m, options.network.max_points));
      }
    }
  });
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (point_sets != nullptr) {
      for (auto& set : sets_per_job[j]) point_sets->push_back(std::move(set));
    }
    for (const auto& f : per_job[j]) {
      features->push_back(f);
      labels->push_back(jobs[j].entry->category);
      groups->push_back(jobs[j].group);
      sources->push_back(jobs[j].source);
    }
  }
}

}  // namespace

CategoryClassifier CategoryClassifier::Train(const ModelDatabase& database, const CategoryClassifierOptions& options) {
  return Train(std::vector<const ModelDatabase*>{&database}, options);
}

CategoryClassifier CategoryClassifier::Train(const std::vector<const ModelDatabase*>& databases,
                                             const CategoryClassifierOptions& options) {
  options.Validate();
  std::vector<std::array<float, kNumShapeFeatures>> features;
  std::vector<world::Category> labels;
  std::vector<EncodedPointSet> point_sets;  // methods with a network: each sample's points
  std::vector<Eigen::Vector3f> seen_points, seen_normals, half_points, half_normals;
  Rng rng(options.seed);
  // A height above the floor the entry's model stands at in the database's scenes (0 when unknown),
  // drawn per sample: the floor lies that far below the model frame's z = 0.
  const ModelDatabase* database = nullptr;  // the one whose entries are being read
  int source = 0;                           // its index
  std::vector<int> groups;                  // the model of each sample, unique over the databases
  std::vector<int> sources;                 // the database of each sample
  int group_base = 0;
  auto floor_z_of = [&](const DatabaseEntry& e) {
    if (e.model_index < 0 || e.model_index >= static_cast<std::int32_t>(database->models().size())) return 0.0;
    const std::vector<float>& heights = database->models()[static_cast<std::size_t>(e.model_index)].support_heights_m;
    if (heights.empty()) return 0.0;
    return -static_cast<double>(heights[static_cast<std::size_t>(rng.UniformInt(0, static_cast<int>(heights.size()) - 1))]);
  };
  auto add = [&](const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                 const DatabaseEntry& e) {
    if (points.size() < 8) return;
    const double floor_z_m = floor_z_of(e);
    features.push_back(ShapeFeatures(points, normals, floor_z_m));
    if (options.uses_network()) point_sets.push_back(EncodePointSet(points, normals, floor_z_m, options.network.max_points));
    labels.push_back(e.category);
    groups.push_back(group_base + e.model_index);
    sources.push_back(source);
  };
  std::vector<RenderJob> render_jobs;  // full models whose views are rendered, after the loop below
  for (std::size_t d = 0; d < databases.size(); ++d) {
    database = databases[d];
    source = static_cast<int>(d);
    if (d > 0) group_base += static_cast<int>(databases[d - 1]->models().size()) + 1;
    for (const DatabaseEntry& e : database->entries()) {
      if (e.keypoints.size() != e.keypoint_normals.size()) continue;
      if (e.kind != EntryKind::kFullModel) {
        if (options.include_pieces && options.method != "softmax") add(e.keypoints, e.keypoint_normals, e);
        continue;
      }
      add(e.keypoints, e.keypoint_normals, e);
      if (options.training_views != "keypoints" && e.model_index >= 0 &&
          e.model_index < static_cast<std::int32_t>(database->models().size()) &&
          !database->models()[static_cast<std::size_t>(e.model_index)].mesh.triangles.empty()) {
        render_jobs.push_back({database, &e, source, group_base + e.model_index});
        continue;
      }
      const int views = options.views_per_model + (options.method != "softmax" ? options.half_views_per_model : 0);
      for (int v = 0; v < views; ++v) {
        const TrainingView training_view = TrainingViewAt(options, v);
        const bool half = training_view.half;
        const double azimuth = training_view.azimuth_rad, elevation = training_view.elevation_rad;
        const Eigen::Vector3f view(static_cast<float>(std::cos(elevation) * std::cos(azimuth)),
                                   static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                                   static_cast<float>(std::sin(elevation)));
        seen_points.clear();
        seen_normals.clear();
        for (std::size_t i = 0; i < e.keypoints.size(); ++i) {
          if (e.keypoint_normals[i].dot(view) <= options.visible_min_cos) continue;
          seen_points.push_back(e.keypoints[i]);
          seen_normals.push_back(e.keypoint_normals[i]);
        }
        if (!half) {
          add(seen_points, seen_normals, e);
          continue;
        }
        // A random vertical plane through the view's centroid keeps one side.
        if (seen_points.empty()) continue;
        Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
        for (const auto& q : seen_points) centroid += q;
        centroid /= static_cast<float>(seen_points.size());
        const double cut = rng.Uniform(0.0, 2.0 * M_PI);
        const Eigen::Vector3f side(static_cast<float>(std::cos(cut)), static_cast<float>(std::sin(cut)), 0.f);
        half_points.clear();
        half_normals.clear();
        for (std::size_t i = 0; i < seen_points.size(); ++i) {
          if ((seen_points[i] - centroid).dot(side) < 0.f) continue;
          half_points.push_back(seen_points[i]);
          half_normals.push_back(seen_normals[i]);
        }
        add(half_points, half_normals, e);
      }
    }
  }
  AddRenderedViews(render_jobs, options, &features, &labels, &groups, &sources,
                   options.uses_network() ? &point_sets : nullptr);
  if (!options.uses_forest() || options.validation_depths.empty() || features.empty()) {
    return Fit(features, labels, options, groups, &point_sets);
  }
  CategoryClassifierOptions fit_options = options;
  fit_options.forest.max_depth = SelectDepthByHeldOutValidation(features, labels, groups, sources, options)
                                     .value_or(options.forest.max_depth);
  return Fit(features, labels, fit_options, groups, &point_sets);
}

CategoryClassifier::Probabilities CategoryClassifier::Classify(const std::vector<Eigen::Vector3f>& points,
                                                               const std::vector<Eigen::Vector3f>& normals,
                                                               double floor_z_m) const {
  const std::array<float, kNumShapeFeatures> features = ShapeFeatures(points, normals, floor_z_m);
  if (!network_.trained()) return Classify(features);
  Probabilities out{};
  std::vector<double> p =
      network_.Predict(EncodePointSet(points, normals, floor_z_m, network_.max_points()),
                       network_shape_features_ ? features.data() : nullptr);
  if (p.empty()) return out;  // no finite point
  if (forest_.trained()) {
    const std::vector<double> f = forest_.Predict(features.data());
    for (std::size_t c = 0; c < p.size(); ++c) p[c] = 0.5 * (p[c] + f[c]);
  }
  for (std::size_t c = 0; c < classes_.size(); ++c) out[static_cast<std::size_t>(world::CategoryId(classes_[c]))] = p[c];
  return out;
}

CategoryClassifier::Probabilities CategoryClassifier::Classify(const std::array<float, kNumShapeFeatures>& features) const {
  if (network_.trained()) throw std::logic_error("CategoryClassifier::Classify: a classifier with a network needs the points");
  Probabilities out{};
  if (!trained()) return out;
  if (classes_.size() == 1) {
    out[static_cast<std::size_t>(world::CategoryId(classes_.front()))] = 1.0;
    return out;
  }
  if (forest_.trained()) {
    const std::vector<double> p = forest_.Predict(features.data());
    for (std::size_t c = 0; c < classes_.size(); ++c) out[static_cast<std::size_t>(world::CategoryId(classes_[c]))] = p[c];
    return out;
  }
  Eigen::VectorXd x(kNumShapeFeatures + 1);
  for (int j = 0; j < kNumShapeFeatures; ++j) {
    x(j) = (static_cast<double>(features[static_cast<std::size_t>(j)]) - mean_(j)) * inverse_std_(j);
  }
  x(kNumShapeFeatures) = 1.0;
  Eigen::VectorXd score = weights_ * x;
  Softmax(score);
  for (std::size_t c = 0; c < classes_.size(); ++c) {
    out[static_cast<std::size_t>(world::CategoryId(classes_[c]))] = score(static_cast<Eigen::Index>(c));
  }
  return out;
}

namespace {

constexpr io::BinaryFileFormat kClassifierFormat = {"OBJSCCL\n", 3, "category classifier",
                                                    "delete it: it is trained again"};

void WriteMatrix(const Eigen::MatrixXd& m, io::BinaryWriter* w) {
  w->Pod(static_cast<std::uint32_t>(m.rows()));
  w->Pod(static_cast<std::uint32_t>(m.cols()));
  w->Array(m.data(), static_cast<std::size_t>(m.size()));
}

Eigen::MatrixXd ReadMatrix(io::BinaryReader* r) {
  const std::uint32_t rows = r->Pod<std::uint32_t>("matrix");
  const std::uint32_t cols = r->Pod<std::uint32_t>("matrix");
  if (rows > (1u << 16) || cols > (1u << 16)) r->Fail("matrix too large");
  Eigen::MatrixXd m(rows, cols);
  r->Array(m.data(), static_cast<std::size_t>(m.size()), "matrix");
  return m;
}

}  // namespace

void CategoryClassifier::Save(const std::string& path) const {
  io::BinaryWriter w;
  w.Pod(static_cast<std::int32_t>(kNumShapeFeatures));
  w.Pod(static_cast<std::uint32_t>(classes_.size()));
  for (world::Category c : classes_) w.String(world::CategoryName(c));
  // The learners: 1 the forest, 2 the network (3 both), 0 softmax weights.
  w.Pod(static_cast<std::uint8_t>((forest_.trained() ? 1 : 0) | (network_.trained() ? 2 : 0)));
  if (forest_.trained()) {
    w.Pod(static_cast<std::int32_t>(max_depth_));
    forest_.Write(&w);
  }
  if (network_.trained()) {
    w.Pod(static_cast<std::uint8_t>(network_shape_features_ ? 1 : 0));
    network_.Write(&w);
  }
  if (!forest_.trained() && !network_.trained()) {
    WriteMatrix(mean_, &w);
    WriteMatrix(inverse_std_, &w);
    WriteMatrix(weights_, &w);
  }
  io::WriteBinaryFile(path, kClassifierFormat, w.buffer());
}

CategoryClassifier CategoryClassifier::Load(const std::string& path) {
  const std::vector<char> bytes = io::ReadVerifiedBinaryFile(path, kClassifierFormat);
  io::BinaryReader r(bytes.data() + io::kBinaryHeaderSize, bytes.size() - io::kBinaryHeaderSize, path,
                     kClassifierFormat.kind);
  CategoryClassifier c;
  if (r.Pod<std::int32_t>("features") != kNumShapeFeatures) r.Fail("another number of shape features");
  const std::uint32_t num_classes = r.Count(4, "classes");
  for (std::uint32_t i = 0; i < num_classes; ++i) {
    const std::string name = r.String("classes");
    const auto category = world::ParseCategory(name);
    if (!category) r.Fail("unknown category '" + name + "'");
    c.classes_.push_back(*category);
  }
  const std::uint8_t learners = r.Pod<std::uint8_t>("learner");
  if (learners > 3) r.Fail("an unknown learner");
  if (learners & 1) {
    c.max_depth_ = r.Pod<std::int32_t>("max_depth");
    if (c.max_depth_ < 1) r.Fail("a forest depth below 1");
    c.forest_ = RandomForest::Read(&r);
    if (c.forest_.num_features() != kNumShapeFeatures || c.forest_.num_classes() != static_cast<int>(num_classes))
      r.Fail("the forest's features or classes disagree with the classifier's");
  }
  if (learners & 2) {
    const std::uint8_t shape_features = r.Pod<std::uint8_t>("network inputs");
    if (shape_features > 1) r.Fail("an unknown network input");
    c.network_shape_features_ = shape_features == 1;
    c.network_ = PointNetwork::Read(&r);
    if (c.network_.num_classes() != static_cast<int>(num_classes) ||
        c.network_.num_global_features() != (c.network_shape_features_ ? kNumShapeFeatures : 0))
      r.Fail("the network's inputs or classes disagree with the classifier's");
  }
  if (learners == 0 && num_classes > 1) {
    c.mean_ = ReadMatrix(&r);
    c.inverse_std_ = ReadMatrix(&r);
    c.weights_ = ReadMatrix(&r);
    if (c.mean_.size() != kNumShapeFeatures || c.inverse_std_.size() != kNumShapeFeatures ||
        c.weights_.rows() != static_cast<Eigen::Index>(num_classes) || c.weights_.cols() != kNumShapeFeatures + 1)
      r.Fail("softmax weights of the wrong shape");
  } else if (learners == 0) {  // one class: empty matrices
    ReadMatrix(&r);
    ReadMatrix(&r);
    ReadMatrix(&r);
  }
  if (!r.AtEnd()) r.Fail("trailing bytes");
  return c;
}

}  // namespace objscan::recognition
