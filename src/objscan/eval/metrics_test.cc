#include "objscan/eval/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"

namespace objscan::eval {
namespace {

using world::Category;

// RI by the definition: every pair i < j, agreement when C_ij == P_ij.
double BruteForceRandIndex(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  const std::size_t n = a.size();
  if (n < 2) return 1.0;
  double agree = 0.0;
  double pairs = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      agree += ((a[i] == a[j]) == (b[i] == b[j])) ? 1.0 : 0.0;
      pairs += 1.0;
    }
  }
  return agree / pairs;
}

TEST(RandIndexTest, HandComputedExample) {
  // Pairs of {0,0,1,1} vs {0,0,0,1}: (1,2) agree, (1,3) no, (1,4) agree, (2,3) no, (2,4) agree,
  // (3,4) no: 3 of 6. (Through NonStructuralRandIndex, every point on one listed object instance.)
  const std::vector<GroundTruthInstance> gt = {{1, Category::kChair, true}, {2, Category::kTable, true}};
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({0, 0, 1, 1}, {1, 1, 1, 2}, gt), 0.5);
  // Identical partitions under renaming: 1. All-in-one vs all-apart: 0.
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({5, 5, 7}, {1, 1, 2}, gt), 1.0);
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({0, 0}, {1, 2}, gt), 0.0);
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({}, {}, gt), 1.0);
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({4}, {2}, gt), 1.0);
  EXPECT_THROW(NonStructuralRandIndex({0, 1}, {0}, gt), InputError);
}

TEST(RandIndexTest, MatchesPairCountingOnRandomLabelings) {
  Rng rng(42);
  std::vector<GroundTruthInstance> gt;
  for (int id = 1; id <= 7; ++id) gt.push_back({id, Category::kChair, true});
  for (int trial = 0; trial < 50; ++trial) {
    const int n = rng.UniformInt(0, 60);
    const int ka = rng.UniformInt(1, 6);
    const int kb = rng.UniformInt(1, 6);
    std::vector<std::int32_t> a(static_cast<std::size_t>(n));
    std::vector<std::int32_t> b(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      a[static_cast<std::size_t>(i)] = rng.UniformInt(-1, ka);
      b[static_cast<std::size_t>(i)] = rng.UniformInt(1, kb + 1);
    }
    EXPECT_NEAR(NonStructuralRandIndex(a, b, gt), BruteForceRandIndex(a, b), 1e-12) << "trial " << trial;
  }
}

TEST(RandIndexTest, NonStructuralPointsOnly) {
  const std::vector<GroundTruthInstance> gt = {
      {1, Category::kChair, true}, {2, Category::kTable, true}, {3, Category::kFloor, false}};
  // Points: chair x2, table x2, floor x2, background (kNoInstance) x1. The floor and unlabelled points are merged into
  // the chair's segment, which must not count; on the kept four points the segmentation {0,0,1,1} is
  // exact.
  const std::vector<std::int32_t> segment = {0, 0, 1, 1, 0, 0, 0};
  const std::vector<std::int32_t> instance = {1, 1, 2, 2, 3, 3, world::kNoInstance};
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex(segment, instance, gt), 1.0);
  // Table split in two: pairs (3,4) disagree -> 5 of 6.
  EXPECT_DOUBLE_EQ(NonStructuralRandIndex({0, 0, 1, 2, 0, 0, 0}, instance, gt), 5.0 / 6.0);
}

TEST(RecognitionTest, MajorityInstance) {
  EXPECT_EQ(MajorityInstance({}), world::kNoInstance);
  EXPECT_EQ(MajorityInstance({3, 3, 2, 0, 3}), 3);
  EXPECT_EQ(MajorityInstance({0, 0, 4}), 0);
  EXPECT_EQ(MajorityInstance({5, 4, 5, 4}), 4);  // tie: smaller id
}

// Points: instance 1 has 4 (3 in object 0, 1 in no object), instance 2 has 4 (1 in object 0, 3 in
// object 1), background 0 has 3 (2 in object 2, which so has no instance; 1 in object 1).
TEST(RecognitionTest, ObjectInstanceSharesCountPointsInNoObject) {
  const std::vector<int> object = {0, 0, 0, -1, 0, 1, 1, 1, 2, 2, 1};
  const std::vector<int> instance = {1, 1, 1, 1, 2, 2, 2, 2, 0, 0, 0};
  const std::vector<ObjectInstanceShare> s = ObjectInstanceShares(object, instance, 4);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].instance, 1);
  EXPECT_DOUBLE_EQ(s[0].share, 0.75);
  EXPECT_EQ(s[1].instance, 2);
  EXPECT_DOUBLE_EQ(s[1].share, 0.75);
  EXPECT_EQ(s[2].instance, world::kNoInstance);  // background only
  EXPECT_DOUBLE_EQ(s[2].share, 0.0);
  EXPECT_EQ(s[3].instance, world::kNoInstance);  // no points
  // A tie keeps the smaller instance id.
  const std::vector<ObjectInstanceShare> tie = ObjectInstanceShares({0, 0, -1}, {5, 3, 3}, 1);
  EXPECT_EQ(tie[0].instance, 3);
  EXPECT_DOUBLE_EQ(tie[0].share, 0.5);
  EXPECT_THROW(ObjectInstanceShares({0}, {1, 2}, 1), InputError);
  EXPECT_THROW(ObjectInstanceShares({1}, {1}, 1), InputError);
}

TEST(RecognitionTest, RecallPrecisionWithDuplicateDetection) {
  const std::vector<GroundTruthInstance> gt = {
      {1, Category::kChair, true},   {2, Category::kChair, true}, {3, Category::kMonitor, false},
      {4, Category::kWall, false},   // structural: never in the ground-truth set
      {5, Category::kOther, true},   // category unknown to the database: not in the set
      {6, Category::kTable, true},
  };
  const std::vector<Category> database = {Category::kChair, Category::kMonitor, Category::kTable, Category::kLamp};
  const std::vector<OutputObject> outputs = {
      {Category::kChair, 1},    // TP
      {Category::kChair, 1},    // duplicate of instance 1: FP
      {Category::kMonitor, 3},  // TP
      {Category::kTable, 2},    // wrong category: FP
      {Category::kLamp, world::kNoInstance},  // background: FP
      {Category::kTable, 6},    // TP
      {Category::kLamp, 5},     // instance outside the set: FP
  };
  const RecognitionResult r = MatchRecognitions(gt, outputs, database);
  EXPECT_EQ(r.all.ground_truth, 4);  // 1, 2, 3, 6
  EXPECT_EQ(r.all.outputs, 7);
  EXPECT_EQ(r.all.true_positives, 3);
  EXPECT_DOUBLE_EQ(r.all.Recall(), 0.75);
  EXPECT_DOUBLE_EQ(r.all.Precision(), 3.0 / 7.0);
  EXPECT_EQ(r.output_is_true_positive, (std::vector<bool>{true, false, true, false, false, true, false}));
  EXPECT_EQ(r.matched_instances, (std::vector<int>{1, 3, 6}));
  // Floor: ground truth 1, 2, 6; outputs whose majority instance stands on the floor: the two chair
  // outputs on 1, the table on 2, the table on 6, the lamp on 5.
  EXPECT_EQ(r.floor.ground_truth, 3);
  EXPECT_EQ(r.floor.outputs, 5);
  EXPECT_EQ(r.floor.true_positives, 2);
  EXPECT_DOUBLE_EQ(r.floor.Recall(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.floor.Precision(), 0.4);
  const auto& chair = r.per_category[static_cast<std::size_t>(world::CategoryId(Category::kChair))];
  EXPECT_EQ(chair.ground_truth, 2);
  EXPECT_EQ(chair.outputs, 2);
  EXPECT_EQ(chair.true_positives, 1);
  const auto& table = r.per_category[static_cast<std::size_t>(world::CategoryId(Category::kTable))];
  EXPECT_EQ(table.ground_truth, 1);
  EXPECT_EQ(table.outputs, 2);
  EXPECT_EQ(table.true_positives, 1);
  const auto& lamp = r.per_category[static_cast<std::size_t>(world::CategoryId(Category::kLamp))];
  EXPECT_EQ(lamp.ground_truth, 0);
  EXPECT_EQ(lamp.outputs, 2);
  EXPECT_EQ(r.per_category[static_cast<std::size_t>(world::CategoryId(Category::kWall))].ground_truth, 0);
}

// `other` is never scored: its objects are in no ground-truth set even when the database holds
// `other` models, and an output of category `other` is refused (callers leave such objects out).
TEST(RecognitionTest, OtherIsNeitherGroundTruthNorOutput) {
  EXPECT_FALSE(IsScoredCategory(Category::kOther));
  EXPECT_FALSE(IsScoredCategory(Category::kWall));
  EXPECT_FALSE(IsScoredCategory(Category::kCeiling));
  EXPECT_TRUE(IsScoredCategory(Category::kChair));
  const std::vector<GroundTruthInstance> gt = {{1, Category::kChair, true}, {2, Category::kOther, true}};
  const std::vector<Category> database = {Category::kChair, Category::kOther};
  const RecognitionResult r = MatchRecognitions(gt, {{Category::kChair, 1}}, database);
  EXPECT_EQ(r.all.ground_truth, 1);
  EXPECT_EQ(r.all.true_positives, 1);
  EXPECT_THROW(MatchRecognitions(gt, {{Category::kOther, 2}}, database), std::invalid_argument);
}

TEST(RecognitionTest, OrderDecidesWhichDuplicateCounts) {
  const std::vector<GroundTruthInstance> gt = {{1, Category::kChair, true}};
  const std::vector<OutputObject> outputs = {{Category::kTable, 1}, {Category::kChair, 1}, {Category::kChair, 1}};
  const RecognitionResult r = MatchRecognitions(gt, outputs, {Category::kChair, Category::kTable});
  // A wrong-category output does not use up the instance.
  EXPECT_EQ(r.output_is_true_positive, (std::vector<bool>{false, true, false}));
  EXPECT_EQ(r.all.true_positives, 1);
}

TEST(RecognitionTest, EmptyAndBadInput) {
  const RecognitionResult r = MatchRecognitions({}, {}, {Category::kChair});
  EXPECT_EQ(r.all.Recall(), 0.0);
  EXPECT_EQ(r.all.Precision(), 0.0);
  EXPECT_THROW(MatchRecognitions({{1, Category::kChair, true}, {1, Category::kBed, true}}, {}, {}), InputError);
}

TEST(CoverageTest, ViewQualityFollowsThePaperFormula) {
  CoverageOptions options;  // sigma 0.6, theta_t pi/2, d in [0.5, 4]
  SurfaceVoxel v;
  v.center_world = Eigen::Vector3d(0, 0, 0);
  v.normal_world = Eigen::Vector3d(1, 0, 0);
  // Head-on at d_min: perfect.
  EXPECT_DOUBLE_EQ(ViewQuality(v, Eigen::Vector3d(0.5, 0, 0), options), 1.0);
  // Head-on at 2 m: exp(-(2 - 0.5)^2 / (0.36 * 4)).
  EXPECT_NEAR(ViewQuality(v, Eigen::Vector3d(2, 0, 0), options), std::exp(-2.25 / 1.44), 1e-12);
  // From behind the normal line (unoriented normal): same as from the front.
  EXPECT_NEAR(ViewQuality(v, Eigen::Vector3d(-2, 0, 0), options), std::exp(-2.25 / 1.44), 1e-12);
  // 45 degrees at 1 m: exp(-(pi/4)^2 / (0.36 * pi/2)) * exp(-0.25 / 1.44).
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(ViewQuality(v, Eigen::Vector3d(s, s, 0), options),
              std::exp(-(M_PI / 4) * (M_PI / 4) / (0.36 * M_PI / 2)) * std::exp(-0.25 / 1.44), 1e-12);
  // Outside [d_min, d_max]: 0.
  EXPECT_EQ(ViewQuality(v, Eigen::Vector3d(0.3, 0, 0), options), 0.0);
  EXPECT_EQ(ViewQuality(v, Eigen::Vector3d(4.5, 0, 0), options), 0.0);
}

TEST(CoverageTest, TinyVoxelSet) {
  // v0, v1, v3 belong to instance 1, v2 to instance 2; v3 is never seen.
  std::vector<SurfaceVoxel> voxels(4);
  voxels[0] = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 1};
  voxels[1] = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1), 1};
  voxels[2] = {Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(1, 0, 0), 2};
  voxels[3] = {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0), 1};
  const std::vector<Eigen::Vector3d> cameras = {
      Eigen::Vector3d(2, 0, 0),    // A: sees v0 head-on at 2 m, v1 obliquely at sqrt(5) m, v2 at 3 m
      Eigen::Vector3d(0.3, 0, 0),  // B: sees v0 too close (0.3 m < d_min): does not count
      Eigen::Vector3d(0, 0, 2),    // C: sees v1 head-on at 1 m (its best view)
  };
  const std::vector<std::vector<int>> seen = {{0, 1, 2}, {0}, {1}};
  const double q0 = std::exp(-1.5 * 1.5 / 1.44);
  const double theta_a1 = std::acos(1.0 / std::sqrt(5.0));
  const double q1_a = std::exp(-theta_a1 * theta_a1 / (0.36 * M_PI / 2)) *
                      std::exp(-(std::sqrt(5.0) - 0.5) * (std::sqrt(5.0) - 0.5) / 1.44);
  const double q1_c = std::exp(-0.5 * 0.5 / 1.44);
  ASSERT_GT(q1_c, q1_a);

  // Instance 1 detected: v0 and v1 count, v2 is on an undetected object, v3 unseen.
  const CoverageResult r = ComputeCoverage(voxels, cameras, seen, {1});
  EXPECT_EQ(r.num_voxels, 4);
  EXPECT_EQ(r.num_visible, 3);
  EXPECT_EQ(r.num_covered, 2);
  EXPECT_DOUBLE_EQ(r.rate, 0.5);
  EXPECT_NEAR(r.quality, (q0 + q1_c) / 4.0, 1e-12);

  // Both detected: v2 adds 1/4 to the rate and exp(-2.5^2 / 1.44) / 4 to the quality.
  const CoverageResult both = ComputeCoverage(voxels, cameras, seen, {1, 2});
  EXPECT_DOUBLE_EQ(both.rate, 0.75);
  EXPECT_NEAR(both.quality, (q0 + q1_c + std::exp(-6.25 / 1.44)) / 4.0, 1e-12);

  // Nothing detected: zero coverage although voxels were seen.
  const CoverageResult none = ComputeCoverage(voxels, cameras, seen, {});
  EXPECT_EQ(none.num_visible, 3);
  EXPECT_EQ(none.rate, 0.0);
  EXPECT_EQ(none.quality, 0.0);
}

TEST(CoverageTest, AccumulatorGivesCurvesOverViews) {
  std::vector<SurfaceVoxel> voxels(2);
  voxels[0] = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 1};
  voxels[1] = {Eigen::Vector3d(0, 2, 0), Eigen::Vector3d(1, 0, 0), 1};
  CoverageAccumulator acc(voxels, CoverageOptions{});
  EXPECT_EQ(acc.Result({1}).rate, 0.0);
  acc.AddView(Eigen::Vector3d(1.5, 0, 0), {0});
  EXPECT_DOUBLE_EQ(acc.Result({1}).rate, 0.5);
  EXPECT_NEAR(acc.Result({1}).quality, std::exp(-1.0 / 1.44) / 2.0, 1e-12);
  // A worse view of v0 does not lower its quality; v1 gets seen head-on at d_min.
  acc.AddView(Eigen::Vector3d(3.5, 0, 0), {0});
  acc.AddView(Eigen::Vector3d(0.5, 2, 0), {1});
  EXPECT_DOUBLE_EQ(acc.Result({1}).rate, 1.0);
  EXPECT_NEAR(acc.Result({1}).quality, (std::exp(-1.0 / 1.44) + 1.0) / 2.0, 1e-12);
  EXPECT_THROW(acc.AddView(Eigen::Vector3d::Zero(), {2}), InputError);
  EXPECT_THROW(ComputeCoverage(voxels, {Eigen::Vector3d::Zero()}, {}, {1}), InputError);
  CoverageOptions bad;
  bad.min_range_m = 5.0;
  EXPECT_THROW(bad.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::eval
