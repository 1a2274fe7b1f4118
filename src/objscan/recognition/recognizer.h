#pragma once
// Similar-model retrieval M(c) and objectness O(c, m) against a ModelDatabase (paper §4.2, §6.1):
// a query point set is described like the database entries (Lloyd keypoints, descriptors, spatial
// BoW), a shortlist of entries comes from the inverted index, each is aligned to the query (yaw +
// translation search, trimmed ICP) and scored; the n_s best are returned with their transforms and
// objectness. Const and thread-safe once constructed.
#include <memory>
#include <mutex>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/point_cloud.h"
#include "objscan/recognition/alignment.h"
#include "objscan/recognition/category_classifier.h"
#include "objscan/recognition/category_naming.h"
#include "objscan/recognition/classifier_cache.h"
#include "objscan/recognition/descriptor.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/objectness.h"
#include "objscan/recognition/space_evidence.h"

namespace objscan::recognition {

struct RecognitionOptions {
  int num_similar_models = 5;  // n_s
  int shortlist_size = 20;     // bag-of-words candidates verified by alignment (>= n_s)
  // The shortlist is re-ranked by bow^bow_rank_weight * fit^fit_rank_weight * O^objectness_rank_weight:
  // bow is the bag-of-words cosine, O the objectness of eq. (1) after alignment and fit =
  // exp(-sqrt(d(c, m)) / Diag(c)) its similarity half alone, which does not penalise a partial query
  // for what it has not seen yet.
  double bow_rank_weight = 0.0;
  double fit_rank_weight = 1.0;
  double objectness_rank_weight = 0.0;
  // ... * O_visible^visible_rank_weight, where O_visible is eq. (1) with the completeness term taken
  // only over the model keypoints facing the query's sensor side (see QueryDescription).
  double visible_rank_weight = 1.0;
  double visible_min_cos = 0.2;  // a model keypoint faces the sensor when n . view > this
  // ... * F^fscore_rank_weight, with F the surface F-score of the aligned entry: 2PR / (P + R), P the
  // share of query keypoints within tau of the entry, R the share of the entry's keypoints (those
  // facing the sensor, as for O_visible) within tau of the query, tau = max(inlier_tolerance_m,
  // inlier_tolerance_fraction x Diag(c)). Shares of points within a tolerance count how much of two
  // surfaces agree; eq. (1)'s mean distances are dominated by the many points that agree anyway.
  double fscore_rank_weight = 0.0;
  double inlier_tolerance_m = 0.03;
  double inlier_tolerance_fraction = 0.0;
  // At most this many entries of one category in M(c) (0 = no limit): the post-segmentation's graph
  // cut chooses among categories, so M(c) keeps alternatives instead of five near-identical boxes.
  int max_per_category = 2;
  // Two-stage verification: every shortlist entry gets the coarse alignment and a cheap rank
  // estimate on a subset of the query's keypoints (estimate_points of them); only the refine_entries
  // best by that estimate are refined and measured in full (more when the category limit leaves M(c)
  // short). 0 = refine the whole shortlist.
  int refine_entries = 6;
  int estimate_points = 96;
  // The estimate's completeness term over this many of the entry's keypoints (0 = all): the first
  // ones, which farthest-point initialisation spread evenly over the entry.
  int estimate_model_points = 160;
  // A union of components is described from its parts' cached descriptions (Recognizer::Compose:
  // keypoints in proportion to each part's size, their descriptors kept) instead of from its points
  // (false = Describe every union, as the paper). The post-segmenter asks for many unions of the same
  // few components; composing them skips keypoint relaxation and descriptors for all of them.
  bool compose_unions = true;
  // Space evidence (when Retrieve is given a SpaceEvidence): with v the share of an aligned entry's
  // keypoints lying where no surface can be, O(c, m) and the rank score are multiplied by
  // (1 - max(0, v - space_tolerance) / (1 - space_tolerance))^space_weight. 0 = the paper's
  // objectness, which sees only the query's points.
  double space_weight = 0.0;
  double space_tolerance = 0.1;  // v up to this costs nothing: database variants differ in detail
  // Beyond the paper: in d(m, c) (completeness), an aligned entry keypoint's squared distance is the
  // smaller of that to the query and that to observed structure which can hide it
  // (SpaceEvidence::SquaredDistanceToStructure: the floor for any face, a wall for faces turned to it
  // as scanner.space.facing_min_cos says; needs a SpaceEvidence and the entry's keypoint normals). A
  // wardrobe against a wall never shows its back panel, nor any face its bottom few centimetres:
  // without this, eq. (1) holds those against a model and prefers models without them (open-backed
  // shelves). On by default since be00778 (2026-11-25), with scanner.space.facing_min_cos = -1 (walls
  // explain any face near them); false = the paper's eq. (1).
  bool structure_completeness = true;
  // Beyond the paper: a query whose lowest point lies within this of the detected floor (from the
  // SpaceEvidence given to Retrieve or Match) stands on it, and every entry is aligned standing on the
  // floor too (AlignmentConstraints::floor_height_m): gravity holds furniture down, so a chair may not
  // be lifted onto a table top to fit it. 0 = the paper's alignment, free in z.
  double floor_contact_m = 0.0;
  // Beyond the paper: a hypothesis that stands its model at a height above the floor where the
  // database's scenes never stand a model of its category (DatabaseModel::support_heights_m: a
  // monitor on the floor, a refrigerator on a counter) loses objectness: with d the distance from its
  // height to the nearest height its category stands at and t this tolerance, O(c, m), fit and the
  // rank score are multiplied by exp(-((d - t) / t)^2 / 2) when d > t (alignments and furniture vary
  // by a few centimetres; 2t off costs 40%, 3t 86%). Needs the floor (SpaceEvidence::FloorHeight);
  // categories without support heights keep their score. 0 = off (the paper).
  double support_height_tolerance_m = 0.0;
  // Beyond the paper: a category prior from a classifier trained on the database's own views when the
  // recognizer is built (CategoryClassifier). With P the classifier's probabilities for the query,
  // O(c, m), fit and the rank score of an entry of category k are multiplied by
  // (P(k) / max_j P(j))^classifier_weight: the classifier's first choice keeps its score, the others
  // lose in proportion to how much less likely the classifier finds them. 0 = off (the paper).
  double classifier_weight = 0.0;
  CategoryClassifierOptions classifier;
  // How a segment's category is named from M(c) and the classifier (category_naming.h).
  CategoryNamingOptions naming;
  AlignmentOptions alignment;
  // The memory a model database may take once loaded (about ModelDatabase::kMemoryPerFileByte times
  // its file); a larger one fails to load with one line naming this key instead of running out of
  // memory. 0 = the memory the machine has available when the run starts.
  double max_database_memory_mb = 0.0;

  template <class V>
  void Visit(V& v) {
    v("num_similar_models", num_similar_models);
    v("shortlist_size", shortlist_size);
    v("bow_rank_weight", bow_rank_weight);
    v("fit_rank_weight", fit_rank_weight);
    v("objectness_rank_weight", objectness_rank_weight);
    v("visible_rank_weight", visible_rank_weight);
    v("visible_min_cos", visible_min_cos);
    v("fscore_rank_weight", fscore_rank_weight);
    v("inlier_tolerance_m", inlier_tolerance_m);
    v("inlier_tolerance_fraction", inlier_tolerance_fraction);
    v("max_per_category", max_per_category);
    v("refine_entries", refine_entries);
    v("estimate_points", estimate_points);
    v("estimate_model_points", estimate_model_points);
    v("compose_unions", compose_unions);
    v("space_weight", space_weight);
    v("space_tolerance", space_tolerance);
    v("structure_completeness", structure_completeness);
    v("floor_contact_m", floor_contact_m);
    v("support_height_tolerance_m", support_height_tolerance_m);
    v("classifier_weight", classifier_weight);
    v("classifier", classifier);
    v("naming", naming);
    v("alignment", alignment);
    v("max_database_memory_mb", max_database_memory_mb);
  }
  void Validate() const;
};

// A query described the way the database entries are.
struct QueryDescription {
  std::vector<Eigen::Vector3f> keypoints;  // n_p Lloyd keypoints (world frame)
  std::vector<Eigen::Vector3f> keypoint_normals;
  // Unit direction from the query towards the sensor that saw it, from the map's normals (which face
  // the sensor); zero when unknown or when the query was seen from all around.
  Eigen::Vector3f view_direction = Eigen::Vector3f::Zero();
  geometry::Aabb3 bounds;                  // of the query points
  double diagonal_m = 0.0;                 // Diag(c)
  SparseHistogram bow;
  std::vector<float> descriptors;          // keypoints.size() x descriptor dimension, row-major
  std::size_t num_points = 0;              // query points described (its size, for Compose)
  bool sensor_normals = false;             // normals came with the query (they face the sensor)
  // P(k | query) / max_j P(j | query) per world::CategoryId k, from the recognizer's category
  // classifier (Recognizer::CategoryOdds); empty when RecognitionOptions::classifier_weight is 0.
  std::vector<float> category_prior;
  bool empty() const { return keypoints.empty(); }
};

struct SimilarModel {
  int entry = -1;          // index into ModelDatabase::entries()
  float bow_score = 0.f;   // cosine similarity of the spatial BoW histograms
  AlignmentResult alignment;  // T_item_query: query (world) -> entry (model frame)
  ObjectnessTerms objectness; // eq. (1) after alignment
  double fit = 0.0;           // exp(-sqrt(d(c, m)) / Diag(c))
  double visible_objectness = 0.0;  // eq. (1) with completeness over sensor-facing model keypoints
  double query_inliers = 0.0;  // P: share of query keypoints within the inlier tolerance of the entry
  double model_inliers = 0.0;  // R: share of (sensor-facing) entry keypoints within it of the query
  double fscore = 0.0;         // 2PR / (P + R)
  double impossible_fraction = 0.0;  // share of the aligned entry's keypoints where no surface can be
  double support_factor = 1.0;       // RecognitionOptions::support_height_tolerance_m's factor
  double category_factor = 1.0;      // RecognitionOptions::classifier_weight's factor
  double rank_score = 0.0;
  // The entry's pose in the query's (world) frame: T_world_model = T_item_query^-1.
  Eigen::Affine3d T_world_model() const { return alignment.T_item_query.inverse(); }
};

class Recognizer {
 public:
  // The database must be finalized and outlive the recognizer.
  Recognizer(const ModelDatabase& database, const RecognitionOptions& options);

  // Describes a query. `support` (optional) is a larger surface around the query (e.g. the scene
  // surface) whose points support the descriptors near the query's boundary; by default the query's
  // own points. Points may come with or without normals.
  QueryDescription Describe(const geometry::PointCloud& query, const geometry::PointCloud* support = nullptr) const;

  // The description of the union of disjoint parts from theirs, without their points: each part
  // keeps a farthest-point subset of its keypoints (with their descriptors) in proportion to its
  // share of the points, n_p in all; bounds, view direction and BoW are those of the union.
  // Descriptors near the seams saw only their own part, so this approximates Describe(union).
  QueryDescription Compose(const std::vector<const QueryDescription*>& parts) const;

  // M(c): the n_s most similar entries in `scope`, best first. Empty when nothing shares a word.
  // With `space` (and RecognitionOptions::space_weight > 0), hypotheses that put model surface where
  // none can be lose objectness.
  std::vector<SimilarModel> Retrieve(const QueryDescription& query, RetrievalScope scope,
                                     const SpaceEvidence* space = nullptr) const;

  // Bag-of-words candidates only (no alignment), best first.
  std::vector<ScoredItem> Candidates(const QueryDescription& query, RetrievalScope scope, int count) const;

  // Aligns the query to one entry and measures it (bow_score left 0), with `space` as in Retrieve.
  SimilarModel Match(const QueryDescription& query, int entry, const SpaceEvidence* space = nullptr) const;

  const ModelDatabase& database() const { return database_; }
  const RecognitionOptions& options() const { return options_; }
  // The category classifier, trained on the database's views on first use (then shared; thread-safe).
  const CategoryClassifier& classifier() const;
  // How classifier() came by its classifier when recognition.classifier.cache is on: read from the
  // cache file, or trained, and then why a damaged file was trained again and why the trained one
  // could not be kept (the caller tells the user: the recognizer never prints). Valid once
  // classifier() has returned; before that, or with the cache off, all empty (path "").
  const CachedClassifierStatus& classifier_cache_status() const { return classifier_cache_status_; }
  // P(k | query) / max_j P(j | query) per world::CategoryId k from the classifier (empty for an
  // empty query): how much less likely than its first choice the classifier finds each category.
  // floor_z_m: the height of the floor under the query (world frame).
  std::vector<float> CategoryOdds(const QueryDescription& query, double floor_z_m = 0.0) const;
  // P(k | query) per world::CategoryId k (all zeros for an empty query or no classifier).
  CategoryClassifier::Probabilities CategoryPosterior(const QueryDescription& query, double floor_z_m = 0.0) const;

 private:
  // Objectness, fit and visible objectness of `points` (the query's keypoints, or a subset of them)
  // under m->alignment against m->entry; m->rank_score = objectness. `points_tree` is a kd-tree over
  // `points` in the query frame, built once per query: the completeness term looks the entry's
  // keypoints up in it after mapping them into the query frame, instead of a tree per entry.
  // With `refined`, m->alignment comes from RefineAlignment on query.keypoints == points, whose
  // mean_squared_distance_m2 is then d(c, m) already. The completeness term uses the entry's first
  // model_points keypoints (0 = all).
  // With `space`, the entry's keypoints (as placed) are checked against it and the objectness scaled.
  void Measure(const QueryDescription& query, const std::vector<Eigen::Vector3f>& points, const KdTree3& points_tree,
               bool refined, int model_points, const SpaceEvidence* space, SimilarModel* m) const;
  void ScoreForRanking(const ScoredItem& candidate, SimilarModel* m) const;
  // The constraints of a query's alignments: on the floor when it reaches down to it (floor_contact_m).
  AlignmentConstraints ConstraintsFor(const QueryDescription& query, const SpaceEvidence* space) const;
  // support_height_tolerance_m's factor for an entry whose z = 0 stands at height_m above the floor.
  double SupportFactor(int entry, double height_m) const;
  // Fills query->category_prior from the classifier (when trained).
  void SetCategoryPrior(QueryDescription* query) const;

  const ModelDatabase& database_;
  RecognitionOptions options_;
  std::unique_ptr<DescriptorExtractor> descriptor_;
  // Per category (world::CategoryId): the distinct support heights of its models, ascending.
  std::vector<std::vector<float>> support_heights_;
  mutable std::once_flag classifier_once_;
  mutable CategoryClassifier classifier_;
  mutable CachedClassifierStatus classifier_cache_status_;  // set in classifier()'s call_once
};

}  // namespace objscan::recognition
