#pragma once
// Beyond the paper: the category recognizer, trained on the model database when the database is
// loaded (deterministic from its seed, CPU, no downloaded weights). The paper names an object by the
// model that fits it best (M(c), eq. (1)); with a few real models per category a chair fits another
// room's sofa as closely as another room's chair. The classifier pools what all models of a
// category share, in metres: how tall, long and wide a shape is, how high above the floor it stands
// and where its surfaces face up (seats, table tops, shelves), how its surface spreads over height
// and how far apart its points lie (a D2 shape distribution).
//
// Training data are virtual partial scans of every full model: its keypoints as seen from
// views_per_model directions around it (keypoints whose outward normal faces the view), all of them,
// half of a view cut by a random vertical plane (pieces a live scan sees before the rest), and the
// database's own component and pair entries (the pre-segmented pieces of the model); each sample
// stands at one of the heights above the floor its model stands at in the database's scenes.
// Learners (CategoryClassifierOptions::method): a random forest (random_forest.h; the default),
// multinomial logistic regression on standardised features (the first version), a point network that
// reads the sample's points themselves (point_network.h), or the forest and the network together
// (the mean of their posteriors); all class-balanced (the database's composition is not a prior).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/recognition/point_network.h"
#include "objscan/recognition/random_forest.h"
#include "objscan/world/category.h"

namespace objscan::recognition {

class ModelDatabase;

struct CategoryClassifierOptions {
  // "forest" (random forest), "softmax" (logistic regression), "network" (point network) or
  // "forest+network" (the mean of the forest's and the network's posteriors).
  std::string method = "forest";
  int views_per_model = 16;          // training views per full model, half at each elevation
  double low_elevation_deg = 15.0;   // the two elevations the views look down from
  double high_elevation_deg = 45.0;
  double visible_min_cos = 0.1;      // a keypoint is seen from a view when n . view > this
  int half_views_per_model = 8;      // views cut in half by a random vertical plane, per full model
  // How a training view of a full model is made: "keypoints" (the model's keypoints whose normal
  // faces the view: no self-occlusion, no noise) or "rendered" (the model's stored mesh rendered by
  // the live depth sensor with its noise, fused, and described by keypoints like a query: what the
  // recognizer meets in a scan; models without a stored mesh fall back to "keypoints").
  std::string training_views = "keypoints";
  bool include_pieces = true;        // the database's component and pair entries are samples too
  std::uint64_t seed = 1;            // half-view cuts and support heights drawn per sample
  // Model databases whose models are training samples too, beside the recognizer's own (e.g. a
  // furniture library beside a database of a benchmark's models): the classifier learns categories
  // from many shapes while retrieval keeps its database. Loaded when the classifier is trained. The
  // words "procedural" and "sweethome3d" stand for the built-in databases (default_database.h); one
  // holding the recognizer's own models is skipped.
  std::vector<std::string> extra_training_databases = {"procedural"};
  // How samples weigh: "samples" (every sample the same within its class) or "models" (every model
  // the same within its class, however many pieces and views it gave). Classes weigh the same.
  std::string balance = "samples";
  // The forest's depth chosen by held-out validation among these (empty: forest.max_depth as given).
  // Held out is what the recognizer will meet: with training databases of two or more sources (a
  // library and generated models, say) each source in turn, learnt from the others, since the
  // scenes' furniture comes from yet other hands; with one source, half of its models, learnt from
  // the other half (forest.max_depth when no category has models in both halves). Deep trees learn
  // the training shapes one by one and serve shapes of their own source; shallower ones carry a
  // category to shapes of another.
  std::vector<double> validation_depths = {6, 8, 12, 18};  // whole numbers (config lists are real)
  int validation_trees = 16;  // trees per validation forest (the chosen depth then grows forest.num_trees)
  // Keep the trained classifier in objscan's cache folder and read it back on the next run with the
  // same training data and options (classifier_cache.h): the same classifier without training again.
  bool cache = true;
  RandomForestOptions forest;
  // methods with "network": the point network, and whether its head reads ShapeFeatures beside the
  // points' own description.
  PointNetworkOptions network;
  bool network_shape_features = true;
  // method "softmax": full-batch gradient descent from zero.
  int iterations = 300;
  double learning_rate = 0.5;
  double l2_weight = 1e-3;

  template <class V>
  void Visit(V& v) {
    v("method", method);
    v("views_per_model", views_per_model);
    v("low_elevation_deg", low_elevation_deg);
    v("high_elevation_deg", high_elevation_deg);
    v("visible_min_cos", visible_min_cos);
    v("half_views_per_model", half_views_per_model);
    v("training_views", training_views);
    v("include_pieces", include_pieces);
    v("seed", seed);
    v("extra_training_databases", extra_training_databases);
    v("balance", balance);
    v("validation_depths", validation_depths);
    v("validation_trees", validation_trees);
    v("cache", cache);
    v("forest", forest);
    v("network", network);
    v("network_shape_features", network_shape_features);
    v("iterations", iterations);
    v("learning_rate", learning_rate);
    v("l2_weight", l2_weight);
  }
  void Validate() const;
  bool uses_forest() const { return method == "forest" || method == "forest+network"; }
  bool uses_network() const { return method == "network" || method == "forest+network"; }
};

// The shape features of an upright point set with unit normals (Z up, metres; normals may face
// either side of the surface) standing over a floor at height floor_z_m: kNumShapeFeatures values,
// rotation-invariant about Z and independent of where the set stands in XY. The first
// kNumRelativeShapeFeatures do not depend on the floor either (heights from the set's own bottom);
// the others are heights above the floor, surfaces per band of height above the floor, and the D2
// and normal-angle distributions of point pairs, then the layout: the surface on a coarse grid of the
// shape's own box (long side x short side x height, turned so its taller side is positive), each
// column's top and its share of horizontal surface. Fewer than 8 points give all zeros.
constexpr int kNumRelativeShapeFeatures = 26;
constexpr int kLayoutCells = 3;  // the layout grid's cells per axis (the last block of features)
constexpr int kNumShapeFeatures = 53 + kLayoutCells * kLayoutCells * (kLayoutCells + 2);
std::array<float, kNumShapeFeatures> ShapeFeatures(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<Eigen::Vector3f>& normals,
                                                   double floor_z_m = 0.0);

class CategoryClassifier {
 public:
  using Probabilities = std::array<double, world::kNumCategories>;

  CategoryClassifier() = default;
  // Trains on the database's full-model entries (needs their keypoints and keypoint normals) and,
  // with include_pieces, its component and pair entries. A database of one category trains a
  // classifier that always answers it.
  static CategoryClassifier Train(const ModelDatabase& database, const CategoryClassifierOptions& options);
  // The same on the entries of several databases (extra_training_databases is not read).
  static CategoryClassifier Train(const std::vector<const ModelDatabase*>& databases,
                                  const CategoryClassifierOptions& options);
  // From features and labels directly (rows of `features` are samples); what Train calls.
  // `groups` (optional, one per sample): with balance "models", the samples of one group (a model)
  // share one weight, every group of a class weighing the same.
  // `point_sets` (one per sample, EncodePointSet at options.network.max_points) are needed by the
  // methods with a network.
  static CategoryClassifier Fit(const std::vector<std::array<float, kNumShapeFeatures>>& features,
                                const std::vector<world::Category>& labels, const CategoryClassifierOptions& options,
                                const std::vector<int>& groups = {},
                                const std::vector<EncodedPointSet>* point_sets = nullptr);

  bool trained() const { return !classes_.empty(); }
  // P(category | shape); 0 for categories the training set lacks. All zeros when not trained. A
  // classifier with a network needs the points: from features alone it throws std::logic_error.
  Probabilities Classify(const std::array<float, kNumShapeFeatures>& features) const;
  Probabilities Classify(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                         double floor_z_m = 0.0) const;
  bool has_network() const { return network_.trained(); }
  const std::vector<world::Category>& classes() const { return classes_; }
  // The forest's depth limit it was grown with (validation_depths' choice or forest.max_depth); 0 for
  // "softmax" or an untrained classifier.
  int max_depth() const { return max_depth_; }

  // The trained classifier as a file (classifier_cache.h) and back; Load throws InputError naming the
  // file when it is missing, damaged or of another format, and gives back what was saved exactly.
  void Save(const std::string& path) const;
  static CategoryClassifier Load(const std::string& path);

 private:
  std::vector<world::Category> classes_;
  int max_depth_ = 0;
  // method "softmax"
  Eigen::VectorXd mean_, inverse_std_;  // feature standardisation
  Eigen::MatrixXd weights_;             // classes x (features + 1), the last column the bias
  // method "forest"
  RandomForest forest_;
  // methods with "network"
  PointNetwork network_;
  bool network_shape_features_ = true;
};

}  // namespace objscan::recognition
