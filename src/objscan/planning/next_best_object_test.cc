#include "objscan/planning/next_best_object.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"

namespace objscan::planning {
namespace {

NboObject Obj(int id, double objectness, const Eigen::Vector3d& center, double area, bool complete = false,
              int views = 0) {
  NboObject o;
  o.id = id;
  o.objectness = objectness;
  o.center_world = center;
  o.area_m2 = area;
  o.complete = complete;
  o.views_spent = views;
  return o;
}

RobotView LookingAlongX() {
  RobotView r;
  r.position_world = Eigen::Vector3d::Zero();
  r.view_direction_world = Eigen::Vector3d::UnitX();
  return r;
}

const NboScore& ScoreOf(const NboResult& r, int id) {
  for (const NboScore& s : r.scores) {
    if (s.id == id) return s;
  }
  ADD_FAILURE() << "no score for id " << id;
  return r.scores.front();
}

TEST(NextBestObjectTest, ScoreIsObjectnessPlusWeightedSaliency) {
  // Object 1 at distance 2 straight ahead, object 2 at distance 4 at 90 degrees: hand-computed terms.
  const std::vector<NboObject> objects = {Obj(1, 0.7, {2, 0, 0}, 0.5), Obj(2, 0.4, {0, 4, 0}, 2.0)};
  const NboResult r = SelectNextBestObject(objects, LookingAlongX(), -1, NextBestObjectOptions());
  ASSERT_EQ(r.status, NboStatus::kOk);
  const NboScore& s1 = ScoreOf(r, 1);
  EXPECT_NEAR(s1.distance_term, std::exp(-0.5), 1e-12);
  EXPECT_NEAR(s1.orientation_term, 1.0, 1e-12);
  EXPECT_NEAR(s1.size_term, 0.25, 1e-12);
  EXPECT_NEAR(s1.score, 0.7 + 1.5 * std::exp(-0.5) + 1.0 + 0.25, 1e-12);
  const NboScore& s2 = ScoreOf(r, 2);
  EXPECT_NEAR(s2.distance_term, std::exp(-1.0), 1e-12);
  EXPECT_NEAR(s2.orientation_term, 0.0, 1e-12);
  EXPECT_NEAR(s2.size_term, 1.0, 1e-12);
  EXPECT_NEAR(s2.score, 0.4 + 1.5 * std::exp(-1.0) + 0.0 + 1.0, 1e-12);
  EXPECT_EQ(r.chosen_id, 1);
}

TEST(NextBestObjectTest, ObjectnessDecidesWhenSaliencyIsEqual) {
  // Mirror images about the view axis: identical saliency.
  const std::vector<NboObject> objects = {Obj(1, 0.3, {2, 1, 0}, 1.0), Obj(2, 0.9, {2, -1, 0}, 1.0)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 2);
  // Ablation without objectness: a tie, broken towards the smaller id.
  NextBestObjectOptions no_objectness;
  no_objectness.objectness_weight = 0.0;
  r = SelectNextBestObject(objects, LookingAlongX(), -1, no_objectness);
  EXPECT_EQ(r.chosen_id, 1);
}

TEST(NextBestObjectTest, NearerObjectWinsOnDistance) {
  // Both straight ahead, same area; the far one has slightly higher objectness.
  const std::vector<NboObject> objects = {Obj(1, 0.6, {4, 0, 0}, 1.0), Obj(2, 0.5, {1, 0, 0}, 1.0)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 2);  // 1.5 (e^-0.25 - e^-1) = 0.62 > 0.1
  NextBestObjectOptions no_distance;
  no_distance.distance_weight = 0.0;
  r = SelectNextBestObject(objects, LookingAlongX(), -1, no_distance);
  EXPECT_EQ(r.chosen_id, 1);
}

TEST(NextBestObjectTest, ObjectInViewWinsOnOrientation) {
  // Same distance and area; one ahead, one behind the robot.
  const std::vector<NboObject> objects = {Obj(1, 0.5, {-2, 0, 0}, 1.0), Obj(2, 0.5, {2, 0, 0}, 1.0)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 2);
  EXPECT_NEAR(ScoreOf(r, 1).orientation_term, -1.0, 1e-12);
  NextBestObjectOptions no_orientation;
  no_orientation.orientation_weight = 0.0;
  r = SelectNextBestObject(objects, LookingAlongX(), -1, no_orientation);
  EXPECT_EQ(r.chosen_id, 1);  // tie, smaller id
}

TEST(NextBestObjectTest, LargerObjectWinsOnSize) {
  const std::vector<NboObject> objects = {Obj(1, 0.5, {2, 1, 0}, 1.0), Obj(2, 0.5, {2, -1, 0}, 3.0)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 2);
  EXPECT_NEAR(ScoreOf(r, 1).size_term, 1.0 / 3.0, 1e-12);
  NextBestObjectOptions no_size;
  no_size.size_weight = 0.0;
  r = SelectNextBestObject(objects, LookingAlongX(), -1, no_size);
  EXPECT_EQ(r.chosen_id, 1);
}

TEST(NextBestObjectTest, CompleteObjectsAreOutOfTheRace) {
  // Object 1 would win by far but is complete; it must not count in the normalisations either.
  const std::vector<NboObject> objects = {Obj(1, 0.99, {1, 0, 0}, 10.0, /*complete=*/true),
                                          Obj(2, 0.2, {3, 3, 0}, 1.0), Obj(3, 0.1, {0, 6, 0}, 0.5)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), 1, NextBestObjectOptions());
  ASSERT_EQ(r.status, NboStatus::kOk);
  EXPECT_NE(r.chosen_id, 1);
  EXPECT_FALSE(r.kept_current);
  EXPECT_EQ(ScoreOf(r, 1).exclusion, NboExclusion::kComplete);
  EXPECT_EQ(ScoreOf(r, 1).score, 0.0);
  EXPECT_NEAR(ScoreOf(r, 2).size_term, 1.0, 1e-12);  // max area over the race is object 2's
  EXPECT_NEAR(ScoreOf(r, 3).distance_term, std::exp(-1.0), 1e-12);

  std::vector<NboObject> all_complete = {Obj(1, 0.99, {1, 0, 0}, 1.0, true)};
  r = SelectNextBestObject(all_complete, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.status, NboStatus::kNoCandidate);
  EXPECT_EQ(r.chosen_id, -1);
  r = SelectNextBestObject({}, LookingAlongX(), -1, NextBestObjectOptions());
  EXPECT_EQ(r.status, NboStatus::kNoCandidate);
}

TEST(NextBestObjectTest, KeepsCurrentObjectUntilItsViewBudgetIsSpent) {
  // Object 2 scores higher, but object 1 is the current object of interest.
  std::vector<NboObject> objects = {Obj(1, 0.3, {3, 3, 0}, 0.5, false, 4), Obj(2, 0.9, {1, 0, 0}, 2.0)};
  NboResult r = SelectNextBestObject(objects, LookingAlongX(), 1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 1);
  EXPECT_TRUE(r.kept_current);
  EXPECT_TRUE(r.budget_spent_ids.empty());

  NextBestObjectOptions no_keep;
  no_keep.keep_current_object = false;
  r = SelectNextBestObject(objects, LookingAlongX(), 1, no_keep);
  EXPECT_EQ(r.chosen_id, 2);

  // The fifth view is spent: object 1 is given up and reported.
  objects[0].views_spent = 5;
  r = SelectNextBestObject(objects, LookingAlongX(), 1, NextBestObjectOptions());
  EXPECT_EQ(r.chosen_id, 2);
  EXPECT_FALSE(r.kept_current);
  ASSERT_EQ(r.budget_spent_ids.size(), 1u);
  EXPECT_EQ(r.budget_spent_ids[0], 1);
  EXPECT_EQ(ScoreOf(r, 1).exclusion, NboExclusion::kViewBudgetSpent);

  // A smaller budget applies the same way.
  objects[0].views_spent = 2;
  NextBestObjectOptions budget2;
  budget2.max_views_per_object = 2;
  r = SelectNextBestObject(objects, LookingAlongX(), 1, budget2);
  EXPECT_EQ(r.chosen_id, 2);
}

TEST(NextBestObjectTest, RejectsBadInput) {
  EXPECT_THROW(SelectNextBestObject({Obj(1, 0.5, {1, 0, 0}, 1.0), Obj(1, 0.5, {2, 0, 0}, 1.0)}, LookingAlongX(), -1,
                                    NextBestObjectOptions()),
               InputError);
  EXPECT_THROW(SelectNextBestObject({Obj(1, NAN, {1, 0, 0}, 1.0)}, LookingAlongX(), -1, NextBestObjectOptions()),
               InputError);
  EXPECT_THROW(SelectNextBestObject({Obj(1, 0.5, {1, 0, 0}, -1.0)}, LookingAlongX(), -1, NextBestObjectOptions()),
               InputError);
  NextBestObjectOptions bad;
  bad.max_views_per_object = 0;
  EXPECT_THROW(bad.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::planning
