#pragma once
// Evaluation of a model database (`objscan db eval`): recognition of unseen models (procedural ones,
// or the user's own: a model folder, the models of worlds) from one and from three views (category
// accuracy of the best and of the n_s retrieved full models), and the objectness of database models
// scanned afresh, completely and from one view.
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/progress.h"
#include "objscan/recognition/classifier_cache.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/recognition/virtual_scan.h"

namespace objscan::recognition {

struct DatabaseEvalOptions {
  // At most this many query models of each category (the first ones of the given sources); 0 = all.
  int queries_per_category = 5;
  // Unseen models are DatabaseModelSeed(first_query_index + k): far beyond any database build's
  // indices, and never a procedural scene's model.
  std::uint64_t first_query_index = 1000000;
  int objectness_models_per_category = 2;
  bool query_noise = true;            // queries carry the live sensor noise
  double min_elevation_deg = 15.0;    // query views look down on the model from this range
  double max_elevation_deg = 45.0;
  double multi_view_step_deg = 45.0;  // azimuth step between the views of a multi-view query
  // Piece queries: a single view cut by a random vertical plane through its centroid, one side kept
  // (half an object, as the live pre-segmentation often sees one before the rest joins it).
  bool piece_queries = true;
  // Draws per query model: each draw scans the model again from new random views (every kind of
  // query: 1 view, 3 views, piece). One model is a large step of a category's top-1 (1.3 points of
  // the 78 scored OASC dev models); more draws of the same models halve the noise of the views, not
  // of the models. Draw 0 is the same at any count.
  int draws_per_model = 1;
  std::uint64_t seed = 7;
  int threads = 0;
  VirtualScanOptions scan;
  RecognitionOptions recognition;

  template <class V>
  void Visit(V& v) {
    v("queries_per_category", queries_per_category);
    v("first_query_index", first_query_index);
    v("objectness_models_per_category", objectness_models_per_category);
    v("query_noise", query_noise);
    v("min_elevation_deg", min_elevation_deg);
    v("max_elevation_deg", max_elevation_deg);
    v("multi_view_step_deg", multi_view_step_deg);
    v("piece_queries", piece_queries);
    v("draws_per_model", draws_per_model);
    v("seed", seed);
    v("threads", threads);
    v("scan", scan);
    v("recognition", recognition);
  }
  void Validate() const;
};

struct ViewCountAccuracy {
  int views = 0;
  bool piece = false;  // half of a single view
  int queries = 0;
  double top1_category_accuracy = 0.0;  // the category the recognizer names (RecognizedCategory)
  double top5_category_accuracy = 0.0;  // the true category among the n_s retrieved
  double retrieval_top1_accuracy = 0.0;  // the category of the best retrieved model alone (the paper)
  double classifier_top1_accuracy = 0.0;  // the category classifier's first choice alone
};

struct DatabaseEvalResult {
  double top1_category_accuracy = 0.0;  // single views
  double top5_category_accuracy = 0.0;  // single views
  double objectness_complete_mean = 0.0;
  double objectness_partial_mean = 0.0;
  double ms_per_query = 0.0;            // describe + retrieve (+ align, objectness) per query
  double classifier_train_s = 0.0;      // training the category classifier on the database
  int classifier_max_depth = 0;         // the depth its forest was grown to (validation_depths' choice)
  CachedClassifierStatus classifier_cache;  // how it came from the cache (Recognizer::classifier_cache_status)
  double classify_ms_per_query = 0.0;   // the classifier's features and posterior per query
  std::vector<ViewCountAccuracy> by_views;  // 1 and 3 views
  int objectness_models = 0;
  // One entry of a query's M(c), best first, with the terms its rank score is made of: what a
  // different ranking would have chosen can be worked out from these without scanning again.
  struct Retrieved {
    std::string model;  // the entry's DatabaseModel::name
    world::Category category = world::Category::kOther;
    double rank_score = 0.0;
    double bow = 0.0;                 // bag-of-words cosine
    double fit = 0.0;                 // exp(-sqrt(d(c, m)) / Diag(c))
    double objectness = 0.0;          // eq. (1)
    double visible_objectness = 0.0;  // eq. (1), completeness over sensor-facing entry keypoints
    double query_inliers = 0.0;       // SimilarModel::query_inliers, model_inliers, fscore
    double model_inliers = 0.0;
    double fscore = 0.0;
  };
  // Per query: true and predicted category, for confusion analysis, and M(c).
  struct Query {
    world::Category truth = world::Category::kOther;
    world::Category predicted = world::Category::kOther;  // RecognizedCategory
    world::Category retrieved_category = world::Category::kOther;  // of the best retrieved model
    int views = 1;
    bool piece = false;
    int draw = 0;  // DatabaseEvalOptions::draws_per_model
    bool top5 = false;
    std::string model;  // the query's ModelSource::name
    std::vector<Retrieved> retrieved;
    // The category classifier's own first choice and posterior, and whether it is trained at all.
    bool classified = false;
    world::Category classifier_choice = world::Category::kOther;
    CategoryClassifier::Probabilities posterior{};
  };
  std::vector<Query> queries;
  // Query sources left out because the database has no model of their category, and the number of
  // query models evaluated (each from 1 and from 3 views).
  std::vector<std::string> skipped_queries;
  int query_models = 0;
};

// The procedural query models: for each furniture category of the database, queries_per_category
// unseen models (DatabaseModelSeed(first_query_index + k)).
std::vector<ModelSource> ProceduralQuerySources(const ModelDatabase& database, const DatabaseEvalOptions& options);

// Recognizes each query source (normalised like a database model, placed at a random yaw and offset,
// scanned with the database's virtual scanner) against `database`. Sources of a category the database
// lacks are skipped (listed in the result); throws InputError when no query is left.
DatabaseEvalResult EvaluateDatabase(const ModelDatabase& database, const std::vector<ModelSource>& queries,
                                    const DatabaseEvalOptions& options, const ProgressCallback& progress = nullptr);

// The same on ProceduralQuerySources(database, options).
DatabaseEvalResult EvaluateDatabase(const ModelDatabase& database, const DatabaseEvalOptions& options,
                                    const ProgressCallback& progress = nullptr);

}  // namespace objscan::recognition
