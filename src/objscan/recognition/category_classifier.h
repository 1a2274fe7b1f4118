#pragma once
// Beyond the paper: a category classifier trained on the model database's own views, when the
// database is loaded (deterministic, CPU, no downloaded weights). The paper names an object by the
// model that fits it best (M(c), eq. (1)); with a few real models per category a chair fits another
// room's sofa as closely as another room's chair. The classifier pools what all models of a
// category share, in metres: how tall, long and wide a shape is, how its surface spreads over
// height, where it faces up (seats, table tops, shelves) and where it stands vertical. Its
// probabilities are a prior over categories (RecognitionOptions::classifier_weight).
//
// Training: each full-model entry's keypoints as seen from views_per_model directions around it
// (keypoints whose outward normal faces the view), and all of them (the model seen from all around);
// multinomial logistic regression on standardised features, L2-regularised, full-batch gradient
// descent from zero with class-balanced weights (the database's composition is not a prior).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/world/category.h"

namespace objscan::recognition {

class ModelDatabase;

struct CategoryClassifierOptions {
  int views_per_model = 16;          // training views per full model, half at each elevation
  double low_elevation_deg = 15.0;   // the two elevations the views look down from
  double high_elevation_deg = 45.0;
  double visible_min_cos = 0.1;      // a keypoint is seen from a view when n . view > this
  int iterations = 300;
  double learning_rate = 0.5;
  double l2_weight = 1e-3;

  template <class V>
  void Visit(V& v) {
    v("views_per_model", views_per_model);
    v("low_elevation_deg", low_elevation_deg);
    v("high_elevation_deg", high_elevation_deg);
    v("visible_min_cos", visible_min_cos);
    v("iterations", iterations);
    v("learning_rate", learning_rate);
    v("l2_weight", l2_weight);
  }
  void Validate() const;
};

// The shape features of an upright point set with unit normals (Z up, metres; normals may face
// either side of the surface): kNumShapeFeatures values, rotation-invariant about Z and independent
// of where the set stands. Fewer than 8 points give all zeros.
constexpr int kNumShapeFeatures = 26;
std::array<float, kNumShapeFeatures> ShapeFeatures(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<Eigen::Vector3f>& normals);

class CategoryClassifier {
 public:
  using Probabilities = std::array<double, world::kNumCategories>;

  CategoryClassifier() = default;
  // Trains on the database's full-model entries (needs their keypoints and keypoint normals).
  // A database of one category trains a classifier that always answers it.
  static CategoryClassifier Train(const ModelDatabase& database, const CategoryClassifierOptions& options);
  // From features and labels directly (rows of `features` are samples); what Train calls.
  static CategoryClassifier Fit(const std::vector<std::array<float, kNumShapeFeatures>>& features,
                                const std::vector<world::Category>& labels, const CategoryClassifierOptions& options);

  bool trained() const { return !classes_.empty(); }
  // P(category | shape); 0 for categories the training set lacks. All zeros when not trained.
  Probabilities Classify(const std::array<float, kNumShapeFeatures>& features) const;
  Probabilities Classify(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals) const {
    return Classify(ShapeFeatures(points, normals));
  }
  const std::vector<world::Category>& classes() const { return classes_; }

 private:
  std::vector<world::Category> classes_;
  Eigen::VectorXd mean_, inverse_std_;  // feature standardisation
  Eigen::MatrixXd weights_;             // classes x (features + 1), the last column the bias
};

}  // namespace objscan::recognition
