#include "objscan/recognition/recognizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "objscan/common/rng.h"
#include "objscan/recognition/classifier_cache.h"
#include "objscan/recognition/default_database.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/normals.h"

namespace objscan::recognition {

void RecognitionOptions::Validate() const {
  config::Require(num_similar_models >= 1, "recognition.num_similar_models", "must be at least 1");
  config::RequireNonNegative("recognition.max_database_memory_mb", max_database_memory_mb);
  config::Require(shortlist_size >= num_similar_models, "recognition.shortlist_size",
                  "must be >= num_similar_models");
  config::RequireNonNegative("recognition.bow_rank_weight", bow_rank_weight);
  config::RequireNonNegative("recognition.fit_rank_weight", fit_rank_weight);
  config::RequireNonNegative("recognition.objectness_rank_weight", objectness_rank_weight);
  config::RequireNonNegative("recognition.visible_rank_weight", visible_rank_weight);
  config::RequireInRange("recognition.visible_min_cos", visible_min_cos, -1.0, 1.0);
  config::RequireNonNegative("recognition.fscore_rank_weight", fscore_rank_weight);
  config::RequirePositive("recognition.inlier_tolerance_m", inlier_tolerance_m);
  config::RequireNonNegative("recognition.inlier_tolerance_fraction", inlier_tolerance_fraction);
  config::Require(max_per_category >= 0, "recognition.max_per_category", "must be >= 0");
  config::Require(refine_entries >= 0, "recognition.refine_entries", "must be >= 0 (0 = all)");
  config::Require(estimate_points >= 3, "recognition.estimate_points", "must be at least 3");
  config::Require(estimate_model_points == 0 || estimate_model_points >= 3, "recognition.estimate_model_points",
                  "must be 0 (all) or at least 3");
  config::RequireNonNegative("recognition.space_weight", space_weight);
  config::RequireNonNegative("recognition.floor_contact_m", floor_contact_m);
  config::RequireNonNegative("recognition.support_height_tolerance_m", support_height_tolerance_m);
  config::RequireNonNegative("recognition.classifier_weight", classifier_weight);
  classifier.Validate();
  naming.Validate();
  config::Require(space_tolerance >= 0.0 && space_tolerance < 1.0, "recognition.space_tolerance", "must be in [0, 1)");
  alignment.Validate();
}

Recognizer::Recognizer(const ModelDatabase& database, const RecognitionOptions& options)
    : database_(database), options_(options) {
  options_.Validate();
  if (!database_.finalized()) throw std::invalid_argument("Recognizer: database not finalized");
  descriptor_ = MakeDescriptorExtractor(database_.settings().descriptor);
  support_heights_.resize(world::kNumCategories);
  for (const DatabaseModel& m : database_.models()) {
    auto& h = support_heights_[static_cast<std::size_t>(world::CategoryId(m.category))];
    h.insert(h.end(), m.support_heights_m.begin(), m.support_heights_m.end());
  }
  // Models of one category may share their heights (procedural ones all carry their category's).
  for (auto& h : support_heights_) {
    std::sort(h.begin(), h.end());
    h.erase(std::unique(h.begin(), h.end()), h.end());
  }
}

const CategoryClassifier& Recognizer::classifier() const {
  std::call_once(classifier_once_, [this] {
    // The generator's shapes are what a database of generated models already holds (procedural
    // scenes, and the small databases tests build): the built-in procedural database is not loaded.
    const bool generated = !database_.models().empty() &&
                           std::all_of(database_.models().begin(), database_.models().end(), [](const DatabaseModel& m) {
                             return m.source.rfind("procedural/", 0) == 0;
                           });
    std::vector<std::string> names;
    for (const std::string& name : options_.classifier.extra_training_databases) {
      if (!(generated && name == "procedural")) names.push_back(name);
    }
    std::vector<ModelDatabase> extra;
    const std::vector<std::string> paths = ResolveTrainingDatabases(names, DefaultDatabaseCacheDir());
    extra.reserve(paths.size());
    for (const std::string& path : paths) extra.push_back(ModelDatabase::Load(path));
    std::vector<const ModelDatabase*> all = {&database_};
    // A database of the recognizer's own models would only count every sample twice.
    auto same_models = [](const ModelDatabase& a, const ModelDatabase& b) {
      if (a.models().size() != b.models().size() || a.entries().size() != b.entries().size()) return false;
      for (std::size_t i = 0; i < a.models().size(); ++i) {
        const DatabaseModel &x = a.models()[i], &y = b.models()[i];
        if (x.name != y.name || x.category != y.category || x.source != y.source) return false;
      }
      return true;
    };
    for (const ModelDatabase& db : extra) {
      if (!same_models(db, database_)) all.push_back(&db);
    }
    classifier_ = options_.classifier.cache ? TrainOrLoadClassifier(all, options_.classifier, DefaultDatabaseCacheDir(),
                                                                    &classifier_cache_status_)
                                            : CategoryClassifier::Train(all, options_.classifier);
  });
  return classifier_;
}

CategoryClassifier::Probabilities Recognizer::CategoryPosterior(const QueryDescription& query, double floor_z_m) const {
  if (query.keypoints.empty()) return CategoryClassifier::Probabilities{};
  return classifier().Classify(query.keypoints, query.keypoint_normals, floor_z_m);
}

std::vector<float> Recognizer::CategoryOdds(const QueryDescription& query, double floor_z_m) const {
  std::vector<float> odds;
  if (query.keypoints.empty()) return odds;
  const CategoryClassifier::Probabilities p = CategoryPosterior(query, floor_z_m);
  const double best = *std::max_element(p.begin(), p.end());
  odds.assign(p.size(), 0.f);
  if (!(best > 0.0)) return odds;
  for (std::size_t k = 0; k < p.size(); ++k) odds[k] = static_cast<float>(p[k] / best);
  return odds;
}

void Recognizer::SetCategoryPrior(QueryDescription* query) const {
  if (options_.classifier_weight > 0.0) query->category_prior = CategoryOdds(*query);
}

double Recognizer::SupportFactor(int entry, double height_m) const {
  const std::vector<float>& heights =
      support_heights_[static_cast<std::size_t>(world::CategoryId(database_.entries()[entry].category))];
  if (heights.empty()) return 1.0;
  // The nearest support height: the first at or above height_m, or the one before it.
  const auto it = std::lower_bound(heights.begin(), heights.end(), static_cast<float>(height_m));
  double d = std::numeric_limits<double>::infinity();
  if (it != heights.end()) d = static_cast<double>(*it) - height_m;
  if (it != heights.begin()) d = std::min(d, height_m - static_cast<double>(*(it - 1)));
  const double t = options_.support_height_tolerance_m;
  if (d <= t) return 1.0;
  const double excess = (d - t) / t;
  return std::exp(-0.5 * excess * excess);
}

namespace {

// Map normals face the sensor: their mean (over `count` keypoints) points back at it for a view from
// one side; a query seen from all around has a short mean and no single view direction (zero).
Eigen::Vector3f ViewDirection(const Eigen::Vector3f& normal_sum, std::size_t count, bool sensor_normals) {
  if (sensor_normals && normal_sum.norm() > 0.3f * count) return normal_sum.normalized();
  return Eigen::Vector3f::Zero();
}

}  // namespace

QueryDescription Recognizer::Describe(const geometry::PointCloud& query, const geometry::PointCloud* support) const {
  QueryDescription q;
  if (query.empty()) return q;
  // Without the map's normals, estimate them once for both the descriptors and the BoW cells.
  geometry::PointCloud with_normals;
  const geometry::PointCloud* cloud = &query;
  if (!query.HasNormals()) {
    with_normals.points = query.points;
    with_normals.normals = EstimateNormals(query.points);
    cloud = &with_normals;
  }
  const DatabaseSettings& s = database_.settings();
  Rng rng(s.keypoint_seed);  // fixed seed: the same points always get the same keypoints
  Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
  for (int i : SampleKeypointsLloyd(cloud->points, s.keypoints, &rng)) {
    q.keypoints.push_back(cloud->points[i]);
    q.keypoint_normals.push_back(cloud->normals[i]);
    normal_sum += cloud->normals[i];
  }
  q.sensor_normals = query.HasNormals();
  q.view_direction = ViewDirection(normal_sum, q.keypoints.size(), q.sensor_normals);
  for (const auto& p : cloud->points) q.bounds.Extend(p.cast<double>());
  q.diagonal_m = q.bounds.Diagonal();
  q.num_points = cloud->points.size();
  descriptor_->Compute(support ? *support : *cloud, q.keypoints, &q.descriptors);
  q.bow = ComputeSpatialBow(database_.vocabulary(), q.keypoints, q.keypoint_normals, q.descriptors, q.bounds, s.bow);
  SetCategoryPrior(&q);
  return q;
}

QueryDescription Recognizer::Compose(const std::vector<const QueryDescription*>& parts) const {
  QueryDescription q;
  std::size_t total_points = 0;
  for (const QueryDescription* p : parts) {
    if (p != nullptr && !p->empty()) total_points += p->num_points;
  }
  if (total_points == 0) return q;
  const DatabaseSettings& s = database_.settings();
  const int dim = descriptor_->Dimension();
  const int n_p = s.keypoints.num_keypoints;
  Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
  q.sensor_normals = true;
  for (const QueryDescription* p : parts) {
    if (p == nullptr || p->empty()) continue;
    if (p->descriptors.size() != p->keypoints.size() * static_cast<std::size_t>(dim)) {
      throw std::invalid_argument("Recognizer::Compose: a part has no descriptors (not from Describe)");
    }
    const int share = std::max(
        1, static_cast<int>(std::lround(static_cast<double>(n_p) * static_cast<double>(p->num_points) /
                                        static_cast<double>(total_points))));
    std::vector<int> picked(p->keypoints.size());
    std::iota(picked.begin(), picked.end(), 0);
    if (share < static_cast<int>(picked.size())) picked = FarthestPointOrder(p->keypoints, share, 0);
    for (int i : picked) {
      const auto k = static_cast<std::size_t>(i);
      q.keypoints.push_back(p->keypoints[k]);
      q.keypoint_normals.push_back(p->keypoint_normals[k]);
      q.descriptors.insert(q.descriptors.end(), p->descriptors.begin() + static_cast<std::ptrdiff_t>(k * dim),
                           p->descriptors.begin() + static_cast<std::ptrdiff_t>((k + 1) * dim));
      normal_sum += p->keypoint_normals[k];
    }
    q.bounds.Extend(p->bounds);
    q.num_points += p->num_points;
    q.sensor_normals = q.sensor_normals && p->sensor_normals;
  }
  q.view_direction = ViewDirection(normal_sum, q.keypoints.size(), q.sensor_normals);
  q.diagonal_m = q.bounds.Diagonal();
  q.bow = ComputeSpatialBow(database_.vocabulary(), q.keypoints, q.keypoint_normals, q.descriptors, q.bounds, s.bow);
  SetCategoryPrior(&q);
  return q;
}

std::vector<ScoredItem> Recognizer::Candidates(const QueryDescription& query, RetrievalScope scope, int count) const {
  return database_.index(scope).Query(query.bow, count);
}

AlignmentConstraints Recognizer::ConstraintsFor(const QueryDescription& query, const SpaceEvidence* space) const {
  AlignmentConstraints constraints;
  if (options_.floor_contact_m <= 0.0 || space == nullptr || query.empty()) return constraints;
  const std::optional<double> floor = space->FloorHeight();
  if (floor && query.bounds.min_m.z() - *floor <= options_.floor_contact_m) constraints.floor_height_m = *floor;
  return constraints;
}

SimilarModel Recognizer::Match(const QueryDescription& query, int entry, const SpaceEvidence* space) const {
  SimilarModel m;
  m.entry = entry;
  m.alignment = AlignToItem(query.keypoints, database_.keypoint_target(entry), options_.alignment,
                            ConstraintsFor(query, space));
  if (m.alignment.ok()) Measure(query, query.keypoints, KdTree3(query.keypoints), true, 0, space, &m);
  return m;
}

void Recognizer::Measure(const QueryDescription& query, const std::vector<Eigen::Vector3f>& points,
                         const KdTree3& points_tree, bool refined, int model_points, const SpaceEvidence* space,
                         SimilarModel* m) const {
  const AlignmentTarget& target = database_.keypoint_target(m->entry);
  const DatabaseEntry& e = database_.entries()[m->entry];
  const double scale = m->alignment.scale;
  const double diag = scale * query.diagonal_m;
  ObjectnessTerms& o = m->objectness;
  o = ObjectnessTerms();
  o.diagonal_m = diag;
  m->fit = 0.0;
  m->visible_objectness = 0.0;
  m->impossible_fraction = 0.0;
  if (points.empty() || target.empty() || !(diag > 0.0)) {
    m->rank_score = 0.0;
    return;
  }
  // d(c, m): query points mapped into the entry frame, nearest entry keypoint.
  const Eigen::Affine3f T = m->alignment.T_item_query.cast<float>();
  const double tau = std::max(options_.inlier_tolerance_m, options_.inlier_tolerance_fraction * diag);
  const float tau2 = static_cast<float>(tau * tau);
  // The query's inliers are always counted: M(c) reports P, R and F whatever the rank weights. A
  // refined alignment already gives the mean squared distance, so only "a keypoint within tau?" is
  // asked, a search bounded by tau that prunes almost the whole tree (the bound just above tau2
  // makes its strict test d2 <= tau2, the same count as the unbounded search gives).
  double sum = 0.0;
  int query_inliers = 0;
  if (refined) {
    const float bound_d2 = std::nextafter(tau2, std::numeric_limits<float>::infinity());
    for (const auto& p : points) {
      if (target.tree().NearestBounded(T * p, bound_d2, -1, nullptr) >= 0) ++query_inliers;
    }
  } else {
    for (const auto& p : points) {
      float d2 = 0.f;
      target.tree().Nearest(T * p, &d2);
      sum += d2;
      if (d2 <= tau2) ++query_inliers;
    }
  }
  o.similarity_m2 = refined ? m->alignment.mean_squared_distance_m2 : sum / static_cast<double>(points.size());
  // d(m, c): entry keypoints mapped into the query frame (distances there are 1/scale of the entry
  // frame's); each squared distance is kept for the visible term below.
  const Eigen::Affine3f T_query_item = m->alignment.T_item_query.inverse().cast<float>();
  const float scale2 = static_cast<float>(scale * scale);
  const std::vector<Eigen::Vector3f>& model = target.tree().points();
  const std::size_t n_model = model_points > 0 ? std::min<std::size_t>(model_points, model.size()) : model.size();
  std::vector<float> model_d2(n_model);
  const bool check_space = space != nullptr && options_.space_weight > 0.0;
  const bool structure_explains = space != nullptr && options_.structure_completeness &&
                                  e.keypoint_normals.size() == target.tree().points().size();
  std::vector<Eigen::Vector3f> placed;
  if (check_space) placed.resize(n_model);
  sum = 0.0;
  for (std::size_t k = 0; k < n_model; ++k) {
    float d2 = 0.f;
    const Eigen::Vector3f p = T_query_item * model[k];
    if (check_space) placed[k] = p;
    if (structure_explains) {
      // min(nearest query point, structure): the structure's distance bounds the search, which then
      // prunes all but the points nearer than it (a model point on the floor searches nothing).
      const Eigen::Vector3f n = (T_query_item.linear() * e.keypoint_normals[k]).normalized();
      const float structure_d2 = static_cast<float>(space->SquaredDistanceToStructure(p, n));
      if (points_tree.NearestBounded(p, structure_d2, -1, &d2) < 0) d2 = structure_d2;
    } else {
      points_tree.Nearest(p, &d2);
    }
    model_d2[k] = scale2 * d2;
    sum += model_d2[k];
  }
  o.completeness_m2 = sum / static_cast<double>(n_model);
  o.objectness = std::exp(-std::sqrt(o.similarity_m2 + o.completeness_m2) / diag);
  m->fit = std::exp(-std::sqrt(o.similarity_m2) / diag);
  m->visible_objectness = o.objectness;
  // R over the entry keypoints facing the sensor (all of them for a query seen from all around).
  int model_inliers = 0, model_counted = 0;
  const auto count_inlier = [&](std::size_t k) {
    ++model_counted;
    if (model_d2[k] <= tau2) ++model_inliers;
  };
  if (!query.view_direction.isZero() && e.keypoint_normals.size() == model.size()) {
    const Eigen::Vector3f view_item = (T.linear() * query.view_direction).normalized();
    double visible_sum = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < n_model; ++k) {
      if (e.keypoint_normals[k].dot(view_item) <= options_.visible_min_cos) continue;
      visible_sum += model_d2[k];
      ++n;
      count_inlier(k);
    }
    if (n > 0) m->visible_objectness = std::exp(-std::sqrt(o.similarity_m2 + visible_sum / n) / diag);
  }
  if (model_counted == 0) {
    for (std::size_t k = 0; k < n_model; ++k) count_inlier(k);
  }
  m->query_inliers = static_cast<double>(query_inliers) / static_cast<double>(points.size());
  m->model_inliers = model_counted > 0 ? static_cast<double>(model_inliers) / model_counted : 0.0;
  const double pr = m->query_inliers + m->model_inliers;
  m->fscore = pr > 0.0 ? 2.0 * m->query_inliers * m->model_inliers / pr : 0.0;
  m->support_factor = 1.0;
  if (space != nullptr && options_.support_height_tolerance_m > 0.0) {
    if (const std::optional<double> floor = space->FloorHeight()) {
      // The entry's z = 0 (where it stands) placed in the query frame.
      m->support_factor = SupportFactor(m->entry, T_query_item.translation().z() - *floor);
      o.objectness *= m->support_factor;
      m->fit *= m->support_factor;
      m->visible_objectness *= m->support_factor;
      m->fscore *= m->support_factor;
    }
  }
  m->category_factor = 1.0;
  if (!query.category_prior.empty()) {
    const double prior = query.category_prior[static_cast<std::size_t>(world::CategoryId(e.category))];
    m->category_factor = std::pow(std::max(prior, 1e-6), options_.classifier_weight);
    o.objectness *= m->category_factor;
    m->fit *= m->category_factor;
    m->visible_objectness *= m->category_factor;
    m->fscore *= m->category_factor;
  }
  if (check_space) {
    const Eigen::Vector3f center = query.bounds.Center().cast<float>();
    m->impossible_fraction = space->ImpossibleFraction(placed, center);
    const double t = options_.space_tolerance;
    const double excess = std::max(0.0, m->impossible_fraction - t) / (1.0 - t);
    const double factor = std::pow(std::max(0.0, 1.0 - excess), options_.space_weight);
    o.objectness *= factor;
    m->fit *= factor;
    m->visible_objectness *= factor;
    m->fscore *= factor;
  }
  m->rank_score = o.objectness;
}

void Recognizer::ScoreForRanking(const ScoredItem& candidate, SimilarModel* m) const {
  m->bow_score = candidate.score;
  m->rank_score = std::pow(std::max(0.f, candidate.score), options_.bow_rank_weight) *
                  std::pow(m->fit, options_.fit_rank_weight) *
                  std::pow(m->objectness.objectness, options_.objectness_rank_weight) *
                  std::pow(m->visible_objectness, options_.visible_rank_weight) *
                  std::pow(m->fscore, options_.fscore_rank_weight);
}

std::vector<SimilarModel> Recognizer::Retrieve(const QueryDescription& query, RetrievalScope scope,
                                               const SpaceEvidence* space) const {
  std::vector<SimilarModel> chosen;
  if (query.empty()) return chosen;
  const std::vector<ScoredItem> shortlist = Candidates(query, scope, options_.shortlist_size);
  const int n = static_cast<int>(shortlist.size());
  const AlignmentOptions& ao = options_.alignment;
  const AlignmentConstraints constraints = ConstraintsFor(query, space);

  // Stage 1 (only when refining fewer than all): coarse alignment of every entry and a rank estimate
  // from a keypoint subset; `order` lists the shortlist by that estimate, best first.
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::vector<std::vector<AlignmentHypothesis>> coarse(n);
  const bool two_stage = options_.refine_entries > 0 && options_.refine_entries < n;
  if (two_stage) {
    std::vector<Eigen::Vector3f> subset;
    for (int i : StridedSubset(static_cast<int>(query.keypoints.size()), options_.estimate_points))
      subset.push_back(query.keypoints[i]);
    const KdTree3 subset_tree(subset);
    std::vector<double> estimate(n, 0.0);
    for (int i = 0; i < n; ++i) {
      const int entry = shortlist[i].item;
      coarse[i] = CoarseAlign(query.keypoints, database_.keypoint_target(entry), ao, constraints);
      if (coarse[i].empty()) continue;
      SimilarModel m;
      m.entry = entry;
      m.alignment.status = AlignmentStatus::kOk;
      m.alignment.T_item_query = coarse[i].front().T_item_query();
      m.alignment.scale = coarse[i].front().scale;
      Measure(query, subset, subset_tree, false, options_.estimate_model_points, space, &m);
      ScoreForRanking(shortlist[i], &m);
      estimate[i] = m.rank_score;
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return estimate[a] > estimate[b]; });
  }

  // Stage 2: full refinement and measurement in estimate order; at least refine_entries of them, and
  // more while the category limit leaves M(c) short.
  std::vector<SimilarModel> refined;
  refined.reserve(n);
  const KdTree3 keypoint_tree(query.keypoints);
  const int first_batch = two_stage ? options_.refine_entries : n;
  for (int r = 0; r < n; ++r) {
    const int i = order[r];
    SimilarModel m;
    m.entry = shortlist[i].item;
    const AlignmentTarget& target = database_.keypoint_target(m.entry);
    m.alignment = two_stage ? RefineAlignment(query.keypoints, target, coarse[i], ao, constraints)
                            : AlignToItem(query.keypoints, target, ao, constraints);
    if (m.alignment.ok()) Measure(query, query.keypoints, keypoint_tree, true, 0, space, &m);
    ScoreForRanking(shortlist[i], &m);
    refined.push_back(std::move(m));
    if (r + 1 < first_batch) continue;
    // Choose n_s from what is refined so far: best first, at most max_per_category per category.
    std::vector<SimilarModel> sorted = refined;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const SimilarModel& a, const SimilarModel& b) { return a.rank_score > b.rank_score; });
    chosen.clear();
    std::vector<int> per_category(world::kNumCategories, 0);
    for (SimilarModel& s : sorted) {
      if (static_cast<int>(chosen.size()) == options_.num_similar_models) break;
      const int c = world::CategoryId(database_.entries()[s.entry].category);
      if (options_.max_per_category > 0 && per_category[c] >= options_.max_per_category) continue;
      ++per_category[c];
      chosen.push_back(std::move(s));
    }
    if (static_cast<int>(chosen.size()) == options_.num_similar_models) break;
  }
  return chosen;
}

}  // namespace objscan::recognition
