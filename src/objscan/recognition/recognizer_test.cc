#include "objscan/recognition/recognizer.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "objscan/common/error.h"
#include "objscan/geometry/pose.h"
#include "objscan/io/test_util.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/shape_database_suite.h"

namespace objscan::recognition {
namespace {

using RecognizerTest = testing::ShapeDatabaseSuite<>;

// A fresh, differently spaced sampling of a shape, placed in the world by T_world_model and
// optionally cut to what a camera on the model's +x side sees of its front 70 %.
geometry::PointCloud Query(testing::ShapeFn shape, const Eigen::Affine3d& T_world_model, bool partial) {
  geometry::PointCloud model;
  shape(0.012, &model.points, &model.normals);
  const geometry::Aabb3 box = geometry::Bounds(model);
  const double cut_x = box.min_m.x() + 0.3 * box.Size().x();
  geometry::PointCloud out;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const bool seen = (model.normals[i].x() > 0.5f || model.normals[i].z() > 0.5f) && model.points[i].x() > cut_x;
    if (partial && !seen) continue;
    out.points.push_back((T_world_model * model.points[i].cast<double>()).cast<float>());
    out.normals.push_back((T_world_model.linear() * model.normals[i].cast<double>()).cast<float>());
  }
  return out;
}

Eigen::Affine3d Placement(double yaw_deg, const Eigen::Vector3d& t) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(t);
  T.rotate(Eigen::AngleAxisd(geometry::DegToRad(yaw_deg), Eigen::Vector3d::UnitZ()));
  return T;
}

TEST_F(RecognizerTest, RetrievesTheRightModelAmongDistractorsAndPlacesIt) {
  const Recognizer recognizer(*db_, RecognitionOptions());
  struct Case {
    testing::ShapeFn shape;
    world::Category category;
  };
  const Case cases[] = {{&testing::ChairLike, world::Category::kChair},
                        {&testing::ShelfLike, world::Category::kShelves},
                        {&testing::SofaLike, world::Category::kSofa}};
  for (const Case& c : cases) {
    for (bool partial : {false, true}) {
      SCOPED_TRACE(std::string(world::CategoryName(c.category)) + (partial ? " partial" : " full"));
      const Eigen::Affine3d T_world_model = Placement(70.0, {2.0, -1.0, 0.0});
      const QueryDescription q = recognizer.Describe(Query(c.shape, T_world_model, partial));
      const auto similar = recognizer.Retrieve(q, RetrievalScope::kFullModels);
      ASSERT_FALSE(similar.empty());
      EXPECT_LE(similar.size(), 5u);
      const DatabaseEntry& best = db_->entries()[similar[0].entry];
      EXPECT_EQ(best.category, c.category);
      EXPECT_EQ(best.kind, EntryKind::kFullModel);
      // The returned pose puts the model where it is in the world, up to the shape's own symmetry
      // (shelves turned by 180 degrees are the same shelves): the model's points placed by the
      // estimate lie on the model placed by the truth.
      std::vector<Eigen::Vector3f> truth;
      for (const auto& p : best.points) truth.push_back((T_world_model * p.cast<double>()).cast<float>());
      const KdTree3 truth_tree(truth);
      double sum = 0.0;
      for (const auto& p : best.points) {
        float d2 = 0.f;
        truth_tree.Nearest((similar[0].T_world_model() * p.cast<double>()).cast<float>(), &d2);
        sum += std::sqrt(d2);
      }
      EXPECT_LT(sum / best.points.size(), partial ? 0.03 : 0.015);
      // Objectness: high when complete, clearly lower when partial.
      if (partial) {
        EXPECT_LT(similar[0].objectness.objectness, 0.93);
      } else {
        EXPECT_GT(similar[0].objectness.objectness, 0.95);
      }
    }
  }
}

// Space evidence with a floor and nothing else.
class FloorOnly : public SpaceEvidence {
 public:
  explicit FloorOnly(double floor_m) : floor_m_(floor_m) {}
  double ImpossibleFraction(const std::vector<Eigen::Vector3f>&, const Eigen::Vector3f&) const override { return 0.0; }
  std::optional<double> FloorHeight() const override { return floor_m_; }

 private:
  double floor_m_;
};

// recognition.floor_contact_m: a query reaching down to the floor has every entry aligned standing
// on it (the entry's z = 0 at the floor's height); a query off the floor, or the option at 0, leaves
// the alignment free in z.
TEST_F(RecognizerTest, AQueryOnTheFloorHasEveryEntryStandOnIt) {
  RecognitionOptions options;
  options.floor_contact_m = 0.05;
  const Recognizer recognizer(*db_, options);
  const double floor_m = 0.25;
  const FloorOnly floor(floor_m);
  // The chair's legs reach 1 cm above the floor, within floor_contact_m of it.
  const QueryDescription on_floor =
      recognizer.Describe(Query(&testing::ChairLike, Placement(30.0, {1.0, 2.0, floor_m + 0.01}), true));
  const auto similar = recognizer.Retrieve(on_floor, RetrievalScope::kFullModels, &floor);
  ASSERT_FALSE(similar.empty());
  for (const SimilarModel& m : similar) {
    SCOPED_TRACE(db_->entries()[m.entry].name);
    EXPECT_NEAR(m.T_world_model().translation().z(), floor_m, 1e-6);
  }
  int entry = similar.front().entry;
  EXPECT_NEAR(recognizer.Match(on_floor, entry, &floor).T_world_model().translation().z(), floor_m, 1e-6);
  // Without the floor (no evidence, or the option at 0) the chair is placed where its legs are.
  EXPECT_NEAR(recognizer.Match(on_floor, entry).T_world_model().translation().z(), floor_m + 0.01, 0.01);
  const Recognizer free_z(*db_, RecognitionOptions());
  const SimilarModel free_match = free_z.Match(on_floor, entry, &floor);
  EXPECT_GT(std::abs(free_match.T_world_model().translation().z() - floor_m), 1e-4);
  // A chair standing on a box 0.3 m high does not touch the floor: its alignment stays free.
  const QueryDescription raised =
      recognizer.Describe(Query(&testing::ChairLike, Placement(30.0, {1.0, 2.0, floor_m + 0.3}), true));
  EXPECT_NEAR(recognizer.Match(raised, entry, &floor).T_world_model().translation().z(), floor_m + 0.3, 0.01);
}

// recognition.support_height_tolerance_m: a hypothesis standing its model where its category never
// stands loses objectness by exp(-((d - t) / t)^2 / 2), nothing within t of a support height.
TEST_F(RecognizerTest, AModelWhereItsCategoryNeverStandsLosesObjectness) {
  const double floor_m = 0.1;
  const FloorOnly floor(floor_m);
  const Recognizer plain(*db_, RecognitionOptions());
  const QueryDescription q =
      plain.Describe(Query(&testing::ChairLike, Placement(30.0, {1.0, 2.0, floor_m}), false));
  const auto similar = plain.Retrieve(q, RetrievalScope::kFullModels, &floor);
  ASSERT_FALSE(similar.empty());
  const int entry = similar.front().entry;
  const SimilarModel unscaled = plain.Match(q, entry, &floor);
  const double height_m = unscaled.T_world_model().translation().z() - floor_m;  // ~0: on the floor
  EXPECT_NEAR(height_m, 0.0, 0.02);
  EXPECT_DOUBLE_EQ(unscaled.support_factor, 1.0);
  // The database's models of the entry's category stand at 0.5 m (the test restores them).
  const world::Category category = db_->entries()[entry].category;
  std::vector<std::vector<float>> saved;
  for (DatabaseModel& m : db_->mutable_models()) {
    saved.push_back(m.support_heights_m);
    if (m.category == category) m.support_heights_m = {0.5f};
  }
  RecognitionOptions options;
  options.support_height_tolerance_m = 0.1;
  const Recognizer with_support(*db_, options);
  const SimilarModel scaled = with_support.Match(q, entry, &floor);
  const double excess = (0.5 - height_m - 0.1) / 0.1;
  EXPECT_NEAR(scaled.support_factor, std::exp(-0.5 * excess * excess), 1e-4);
  EXPECT_NEAR(scaled.objectness.objectness, unscaled.objectness.objectness * scaled.support_factor, 1e-9);
  EXPECT_NEAR(scaled.fit, unscaled.fit * scaled.support_factor, 1e-9);
  // Without the floor nothing is known of the height: no factor.
  EXPECT_DOUBLE_EQ(with_support.Match(q, entry).support_factor, 1.0);
  // Within the tolerance of a support height: no factor.
  for (DatabaseModel& m : db_->mutable_models()) {
    if (m.category == category) m.support_heights_m = {static_cast<float>(height_m + 0.08)};
  }
  EXPECT_DOUBLE_EQ(Recognizer(*db_, options).Match(q, entry, &floor).support_factor, 1.0);
  for (std::size_t i = 0; i < saved.size(); ++i) db_->mutable_models()[i].support_heights_m = saved[i];
}

// Space evidence that calls impossible every point above a height (world z).
class CeilingEvidence : public SpaceEvidence {
 public:
  explicit CeilingEvidence(float ceiling_z_m) : ceiling_z_m_(ceiling_z_m) {}
  double ImpossibleFraction(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f&) const override {
    if (points.empty()) return 0.0;
    std::size_t n = 0;
    for (const auto& p : points) n += p.z() > ceiling_z_m_ ? 1 : 0;
    return static_cast<double>(n) / points.size();
  }

 private:
  float ceiling_z_m_;
};

// With space evidence each hypothesis's objectness is scaled by the penalty of the share v of its
// placed keypoints the evidence rejects: (1 - max(0, v - t) / (1 - t))^w, recomputed here from the
// returned pose; weight 0 (the paper) ignores the evidence.
TEST_F(RecognizerTest, SpaceEvidenceScalesObjectnessByTheImpossibleShare) {
  RecognitionOptions options;
  options.refine_entries = 0;  // every shortlist entry refined: the same poses with and without evidence
  const Eigen::Affine3d T_world_model = Placement(30.0, {1.0, 0.5, 0.0});
  // A partial chair: its unseen back half could be anywhere above the seat; the evidence forbids
  // everything higher than 0.5 m.
  const CeilingEvidence evidence(0.5f);
  const Recognizer plain(*db_, options);
  const QueryDescription q = plain.Describe(Query(&testing::ChairLike, T_world_model, true));
  const auto base = plain.Retrieve(q, RetrievalScope::kAllEntries);
  const auto ignored = plain.Retrieve(q, RetrievalScope::kAllEntries, &evidence);
  ASSERT_EQ(base.size(), ignored.size());
  for (std::size_t i = 0; i < base.size(); ++i) {
    EXPECT_EQ(base[i].entry, ignored[i].entry);
    EXPECT_DOUBLE_EQ(base[i].objectness.objectness, ignored[i].objectness.objectness);
    EXPECT_EQ(ignored[i].impossible_fraction, 0.0);
  }
  options.space_weight = 2.0;
  options.space_tolerance = 0.1;
  const Recognizer checked(*db_, options);
  const auto scaled = checked.Retrieve(q, RetrievalScope::kAllEntries, &evidence);
  ASSERT_FALSE(scaled.empty());
  int penalised = 0;
  for (const SimilarModel& m : scaled) {
    auto it = std::find_if(base.begin(), base.end(), [&](const SimilarModel& b) { return b.entry == m.entry; });
    const SimilarModel unscaled = it != base.end() ? *it : plain.Match(q, m.entry);
    ASSERT_EQ(unscaled.entry, m.entry);
    // v from the pose, as the recognizer places the entry's keypoints.
    const auto& model = db_->keypoint_target(m.entry).tree().points();
    std::vector<Eigen::Vector3f> placed;
    for (const auto& p : model) placed.push_back((m.T_world_model() * p.cast<double>()).cast<float>());
    const double v = evidence.ImpossibleFraction(placed, Eigen::Vector3f::Zero());
    EXPECT_NEAR(m.impossible_fraction, v, 1e-12);
    const double factor = std::pow(1.0 - std::max(0.0, v - 0.1) / 0.9, 2.0);
    EXPECT_NEAR(m.objectness.objectness, factor * unscaled.objectness.objectness, 1e-9) << "entry " << m.entry;
    penalised += v > 0.1 ? 1 : 0;
  }
  EXPECT_GT(penalised, 0);  // the chair's back rises above 0.5 m
}

// Structure evidence: a wall x = x0 facing +x, against which faces turned to -x rest, and,
// optionally, everything (explains all).
class PlaneStructure : public SpaceEvidence {
 public:
  explicit PlaneStructure(double x0_m, bool everything = false) : x0_m_(x0_m), everything_(everything) {}
  double ImpossibleFraction(const std::vector<Eigen::Vector3f>&, const Eigen::Vector3f&) const override { return 0.0; }
  double SquaredDistanceToStructure(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const override {
    if (everything_) return 0.0;
    return n.x() <= -0.5f ? std::pow(p.x() - x0_m_, 2) : std::numeric_limits<double>::infinity();
  }

 private:
  double x0_m_;
  bool everything_;
};

// With structure_completeness, d(m, c) takes for each placed model keypoint the nearer of the query's
// points and the structure; recomputed here by brute force. Off (the paper), the evidence changes
// nothing; explaining everything leaves only d(c, m).
TEST_F(RecognizerTest, StructureExplainsModelSurfaceInTheCompletenessTerm) {
  const Eigen::Affine3d T_world_model = Placement(0.0, {1.0, 0.5, 0.0});
  RecognitionOptions paper;
  paper.structure_completeness = false;
  const Recognizer plain(*db_, paper);
  const QueryDescription q = plain.Describe(Query(&testing::ChairLike, T_world_model, true));
  const auto similar = plain.Retrieve(q, RetrievalScope::kFullModels);
  ASSERT_FALSE(similar.empty());
  const int entry = similar[0].entry;
  const SimilarModel base = plain.Match(q, entry);
  ASSERT_TRUE(base.alignment.ok());
  // The chair's unseen back lies on its -x side: a wall there, at the model's back.
  const geometry::Aabb3 box = geometry::Bounds(Query(&testing::ChairLike, T_world_model, false));
  const PlaneStructure wall(box.min_m.x());
  EXPECT_DOUBLE_EQ(plain.Match(q, entry, &wall).objectness.objectness, base.objectness.objectness);

  RecognitionOptions options;
  options.structure_completeness = true;
  EXPECT_TRUE(RecognitionOptions().structure_completeness) << "the default since be00778 (2026-11-25)";
  const Recognizer explained(*db_, options);
  EXPECT_DOUBLE_EQ(explained.Match(q, entry).objectness.objectness, base.objectness.objectness);  // no evidence
  const SimilarModel m = explained.Match(q, entry, &wall);
  ASSERT_TRUE(m.alignment.ok());
  EXPECT_DOUBLE_EQ(m.objectness.similarity_m2, base.objectness.similarity_m2);
  const KdTree3 query_tree(q.keypoints);
  double sum = 0.0;
  const auto& model = db_->keypoint_target(entry).tree().points();
  const auto& normals = db_->entries()[entry].keypoint_normals;
  ASSERT_EQ(normals.size(), model.size());
  int against_wall = 0;
  for (std::size_t k = 0; k < model.size(); ++k) {
    const Eigen::Vector3f placed = (m.T_world_model() * model[k].cast<double>()).cast<float>();
    const Eigen::Vector3f n = (m.T_world_model().linear() * normals[k].cast<double>()).normalized().cast<float>();
    float d2 = 0.f;
    query_tree.Nearest(placed, &d2);
    const double structure_d2 = wall.SquaredDistanceToStructure(placed, n);
    against_wall += std::isfinite(structure_d2) ? 1 : 0;
    sum += std::min(static_cast<double>(d2), structure_d2);
  }
  EXPECT_GT(against_wall, 0);
  EXPECT_NEAR(m.objectness.completeness_m2, sum / model.size(), 1e-6);
  EXPECT_LT(m.objectness.completeness_m2, base.objectness.completeness_m2);
  EXPECT_GT(m.objectness.objectness, base.objectness.objectness);
  const PlaneStructure all(0.0, true);
  const SimilarModel whole = explained.Match(q, entry, &all);
  EXPECT_EQ(whole.objectness.completeness_m2, 0.0);
  EXPECT_NEAR(whole.objectness.objectness,
              std::exp(-std::sqrt(whole.objectness.similarity_m2) / whole.objectness.diagonal_m), 1e-12);
}

// Refining only the entries ranked best by the coarse stage must choose what refining the whole
// shortlist chooses on clear cases, with identical measurements for the models both return.
TEST_F(RecognizerTest, TwoStageRetrievalAgreesWithRefiningTheWholeShortlist) {
  RecognitionOptions staged_options;
  staged_options.refine_entries = 5;
  staged_options.shortlist_size = 12;
  RecognitionOptions full_options = staged_options;
  full_options.refine_entries = 0;
  const Recognizer staged(*db_, staged_options), full(*db_, full_options);
  for (testing::ShapeFn shape : {&testing::ChairLike, &testing::ShelfLike, &testing::SofaLike}) {
    for (bool partial : {false, true}) {
      const QueryDescription q = staged.Describe(Query(shape, Placement(-35.0, {0.5, 1.5, 0.0}), partial));
      for (RetrievalScope scope : {RetrievalScope::kFullModels, RetrievalScope::kAllEntries}) {
        const auto a = staged.Retrieve(q, scope);
        const auto b = full.Retrieve(q, scope);
        ASSERT_FALSE(a.empty());
        ASSERT_FALSE(b.empty());
        EXPECT_EQ(a.size(), b.size());
        EXPECT_EQ(db_->entries()[a[0].entry].category, db_->entries()[b[0].entry].category);
        for (const SimilarModel& m : a) {
          for (const SimilarModel& n : b) {
            if (m.entry == n.entry) {
              EXPECT_DOUBLE_EQ(m.rank_score, n.rank_score);
            }
          }
        }
      }
    }
  }
}

// recognition.classifier.extra_training_databases: another database's models train the classifier
// too (its posterior changes), a file holding the recognizer's own models adds nothing (the same
// classifier as without it), and a missing file names itself.
TEST_F(RecognizerTest, ExtraTrainingDatabasesAddOtherModelsOnly) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("objscan_recognizer_extra_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string own = (dir / "own.db").string(), other = (dir / "other.db").string();
  db_->Save(own);
  BuildDatabaseFromScans({testing::ShapeModels(0.01)[0]}, testing::SmallDatabaseOptions()).Save(other);
  const geometry::PointCloud cloud = Query(&testing::ChairLike, Placement(40.0, {1.0, 0.5, 0.0}), true);
  auto posterior = [&](const std::vector<std::string>& extra) {
    RecognitionOptions options;
    options.classifier.extra_training_databases = extra;
    const Recognizer r(*db_, options);
    return r.CategoryPosterior(r.Describe(cloud));
  };
  const auto alone = posterior({});
  EXPECT_EQ(posterior({own}), alone);
  EXPECT_NE(posterior({other}), alone);
  EXPECT_THROW(posterior({(dir / "missing.db").string()}), InputError);
  fs::remove_all(dir);
}

// The recognizer keeps how its classifier came from the cache ($OBJSCAN_CACHE_DIR): trained and
// kept, then read back, then (the file cut short) trained again with the damage said, and a cache
// that cannot be written says why; nothing before the classifier is first asked for.
TEST_F(RecognizerTest, TheClassifierCacheStatusSaysWhatHappenedToTheCacheFile) {
  io::testing::TempDir dir;
  RecognitionOptions options;
  options.classifier.extra_training_databases = {};
  options.classifier.forest.num_trees = 8;
  options.classifier.forest.threads = 1;
  options.classifier.validation_depths = {};
  auto status_of = [&](const std::string& cache_dir) {
    const io::testing::ScopedEnv env("OBJSCAN_CACHE_DIR", cache_dir);
    const Recognizer r(*db_, options);
    EXPECT_EQ(r.classifier_cache_status().path, "");
    EXPECT_TRUE(r.classifier().trained());
    return r.classifier_cache_status();
  };
  const std::string cache = dir.File("cache");
  const CachedClassifierStatus trained = status_of(cache);
  EXPECT_FALSE(trained.loaded);
  EXPECT_EQ(trained.damage, "");
  EXPECT_EQ(trained.write_error, "");
  EXPECT_EQ(trained.path.rfind(cache + "/classifier-", 0), 0u) << trained.path;
  ASSERT_TRUE(std::filesystem::exists(trained.path));
  const CachedClassifierStatus loaded = status_of(cache);
  EXPECT_TRUE(loaded.loaded);
  EXPECT_EQ(loaded.path, trained.path);
  EXPECT_EQ(loaded.damage, "");
  std::filesystem::resize_file(trained.path, 100);
  const CachedClassifierStatus damaged = status_of(cache);
  EXPECT_FALSE(damaged.loaded);
  EXPECT_NE(damaged.damage.find(trained.path + ": truncated category classifier"), std::string::npos)
      << damaged.damage;
  EXPECT_EQ(damaged.write_error, "");
  EXPECT_TRUE(status_of(cache).loaded);  // replaced by the classifier trained again
  io::testing::WriteText(dir.File("not-a-folder"), "x");
  const CachedClassifierStatus unwritable = status_of(dir.File("not-a-folder"));
  EXPECT_FALSE(unwritable.loaded);
  EXPECT_EQ(unwritable.damage, "");
  EXPECT_NE(unwritable.write_error.find(dir.File("not-a-folder")), std::string::npos) << unwritable.write_error;
  // With the cache off there is no file to speak of.
  options.classifier.cache = false;
  EXPECT_EQ(status_of(cache).path, "");
}

// recognition.classifier_weight: the query carries the database-trained classifier's P(k) / max P,
// and each entry's objectness, fit and rank score are those without the prior times
// (P(k) / max P)^w; 0 leaves the paper's scores (no prior at all).
TEST_F(RecognizerTest, TheCategoryPriorScalesScoresByTheClassifiersOdds) {
  RecognitionOptions plain_options;
  plain_options.classifier.extra_training_databases = {};  // the database's own models only
  const Recognizer plain(*db_, plain_options);
  RecognitionOptions options = plain_options;
  options.classifier_weight = 0.5;
  const Recognizer with_prior(*db_, options);
  ASSERT_TRUE(with_prior.classifier().trained());
  const geometry::PointCloud cloud = Query(&testing::ChairLike, Placement(40.0, {1.0, 0.5, 0.0}), false);
  const QueryDescription q_plain = plain.Describe(cloud);
  const QueryDescription q = with_prior.Describe(cloud);
  EXPECT_TRUE(q_plain.category_prior.empty());
  ASSERT_EQ(q.category_prior.size(), static_cast<std::size_t>(world::kNumCategories));
  EXPECT_FLOAT_EQ(*std::max_element(q.category_prior.begin(), q.category_prior.end()), 1.0f);
  // The shapes are far apart: the classifier trained on their views names the whole chair a chair.
  EXPECT_FLOAT_EQ(q.category_prior[world::CategoryId(world::Category::kChair)], 1.0f);
  const auto similar = with_prior.Retrieve(q, RetrievalScope::kFullModels);
  ASSERT_FALSE(similar.empty());
  EXPECT_EQ(db_->entries()[similar[0].entry].category, world::Category::kChair);
  for (const SimilarModel& m : similar) {
    const DatabaseEntry& e = db_->entries()[m.entry];
    SCOPED_TRACE(e.name);
    const double expected = std::pow(std::max(1e-6, static_cast<double>(q.category_prior[world::CategoryId(e.category)])), 0.5);
    EXPECT_NEAR(m.category_factor, expected, 1e-12);
    const SimilarModel unscaled = plain.Match(q_plain, m.entry);
    const SimilarModel scaled = with_prior.Match(q, m.entry);
    EXPECT_NEAR(scaled.objectness.objectness, unscaled.objectness.objectness * expected, 1e-9);
    EXPECT_NEAR(scaled.fit, unscaled.fit * expected, 1e-9);
  }
  // Composed unions carry the prior too; without the weight the odds are there on request.
  EXPECT_EQ(with_prior.Compose({&q}).category_prior, q.category_prior);
  EXPECT_EQ(plain.CategoryOdds(q_plain), q.category_prior);
  EXPECT_TRUE(plain.CategoryOdds(QueryDescription()).empty());
}

TEST_F(RecognizerTest, ScopeSelectsFullModelsOrAllEntries) {
  const Recognizer recognizer(*db_, RecognitionOptions());
  // A single table leg: among all entries its best match is a leg component of the table; among
  // full models only full models come back.
  geometry::PointCloud leg;
  testing::BoxSurface({0, 0, 0}, {0.05, 0.05, 0.70}, 0.01, &leg.points, &leg.normals);
  const QueryDescription q = recognizer.Describe(leg);
  const auto all = recognizer.Retrieve(q, RetrievalScope::kAllEntries);
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(db_->entries()[all[0].entry].kind, EntryKind::kComponent);
  EXPECT_EQ(db_->entries()[all[0].entry].category, world::Category::kTable);
  EXPECT_GT(all[0].objectness.objectness, 0.9);
  for (const auto& m : recognizer.Retrieve(q, RetrievalScope::kFullModels))
    EXPECT_EQ(db_->entries()[m.entry].kind, EntryKind::kFullModel);
}

TEST_F(RecognizerTest, DescribeIsDeterministicAndEmptyQueryGivesNothing) {
  const Recognizer recognizer(*db_, RecognitionOptions());
  const geometry::PointCloud cloud = Query(&testing::ChairLike, Placement(10, {0, 0, 0}), true);
  const QueryDescription a = recognizer.Describe(cloud);
  const QueryDescription b = recognizer.Describe(cloud);
  EXPECT_EQ(a.keypoints, b.keypoints);
  ASSERT_EQ(a.bow.size(), b.bow.size());
  for (std::size_t i = 0; i < a.bow.size(); ++i) EXPECT_EQ(a.bow[i].value, b.bow[i].value);
  EXPECT_TRUE(recognizer.Retrieve(recognizer.Describe(geometry::PointCloud()), RetrievalScope::kAllEntries).empty());
}

// Compose: one part is that part; two halves of a shape give n_p keypoints shared by size, the
// union's bounds, and retrieve the same model as describing the union's points.
TEST_F(RecognizerTest, ComposedUnionMatchesDescribingItsPoints) {
  const Recognizer recognizer(*db_, RecognitionOptions());
  const geometry::PointCloud cloud = Query(&testing::TableLike, Placement(25, {1, -2, 0}), false);
  const QueryDescription whole = recognizer.Describe(cloud);
  const QueryDescription same = recognizer.Compose({&whole});
  EXPECT_EQ(same.keypoints, whole.keypoints);
  EXPECT_EQ(same.descriptors, whole.descriptors);
  EXPECT_EQ(same.num_points, whole.num_points);

  // Split at a height: the top (about a third of the points) and the legs below it.
  const geometry::Aabb3 box = geometry::Bounds(cloud);
  const float cut_z = static_cast<float>(box.min_m.z() + 0.8 * box.Size().z());
  geometry::PointCloud top, legs;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    geometry::PointCloud& part = cloud.points[i].z() > cut_z ? top : legs;
    part.points.push_back(cloud.points[i]);
    part.normals.push_back(cloud.normals[i]);
  }
  ASSERT_GT(top.size(), 100u);
  ASSERT_GT(legs.size(), 100u);
  const QueryDescription d_top = recognizer.Describe(top), d_legs = recognizer.Describe(legs);
  const QueryDescription composed = recognizer.Compose({&d_top, &d_legs});
  const int n_p = db_->settings().keypoints.num_keypoints;
  EXPECT_NEAR(static_cast<double>(composed.keypoints.size()), n_p, 2.0);
  EXPECT_EQ(composed.descriptors.size(), composed.keypoints.size() * whole.descriptors.size() / whole.keypoints.size());
  EXPECT_EQ(composed.num_points, cloud.size());
  int from_top = 0;
  for (const auto& k : composed.keypoints) from_top += k.z() > cut_z ? 1 : 0;
  const double top_share = static_cast<double>(top.size()) / static_cast<double>(cloud.size());
  EXPECT_NEAR(static_cast<double>(from_top) / composed.keypoints.size(), top_share, 0.01);
  EXPECT_TRUE(composed.bounds.min_m.isApprox(box.min_m, 1e-6));
  EXPECT_TRUE(composed.bounds.max_m.isApprox(box.max_m, 1e-6));
  EXPECT_NEAR(composed.diagonal_m, box.Diagonal(), 1e-6);

  const auto by_points = recognizer.Retrieve(whole, RetrievalScope::kFullModels);
  const auto by_parts = recognizer.Retrieve(composed, RetrievalScope::kFullModels);
  ASSERT_FALSE(by_points.empty());
  ASSERT_FALSE(by_parts.empty());
  EXPECT_EQ(db_->entries()[by_parts[0].entry].category, db_->entries()[by_points[0].entry].category);
  EXPECT_EQ(by_parts[0].entry, by_points[0].entry);
  EXPECT_NEAR(by_parts[0].objectness.objectness, by_points[0].objectness.objectness, 0.05);

  QueryDescription no_descriptors = d_top;
  no_descriptors.descriptors.clear();
  EXPECT_THROW(recognizer.Compose({&no_descriptors, &d_legs}), std::invalid_argument);
  EXPECT_TRUE(recognizer.Compose({}).empty());
}

}  // namespace
}  // namespace objscan::recognition
