#include "objscan/planning/exploration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"

namespace objscan::planning {
namespace {

FrontierCandidate Frontier(double x, double y, int size) {
  FrontierCandidate f;
  f.centroid_world = Eigen::Vector3d(x, y, 0.0);
  f.size_cells = size;
  return f;
}

// Straight-line distance from the origin, except that goals with x < 0 are unreachable.
std::optional<double> PathFromOrigin(const Eigen::Vector3d& goal) {
  if (goal.x() < 0.0) return std::nullopt;
  return goal.head<2>().norm();
}

TEST(ExplorationTest, TradesSizeAgainstTravel) {
  // Big far frontier vs small near one, hand-computed scores.
  const std::vector<FrontierCandidate> frontiers = {Frontier(8, 0, 100), Frontier(2, 0, 40)};
  const FrontierChoice c = ChooseFrontier(frontiers, PathFromOrigin, {}, ExplorationOptions());
  ASSERT_EQ(c.status, FrontierStatus::kOk);
  EXPECT_NEAR(c.scores[0].score, 1.0 + std::exp(-1.0), 1e-12);
  EXPECT_NEAR(c.scores[1].score, 0.4 + std::exp(-0.25), 1e-12);
  EXPECT_EQ(c.best_index, 0);  // 1.368 > 1.179
  ExplorationOptions travel_heavy;
  travel_heavy.travel_weight = 3.0;
  EXPECT_EQ(ChooseFrontier(frontiers, PathFromOrigin, {}, travel_heavy).best_index, 1);
}

TEST(ExplorationTest, UnreachableFrontierIsSkipped) {
  // The largest, nearest frontier cannot be reached.
  const std::vector<FrontierCandidate> frontiers = {Frontier(-1, 0, 500), Frontier(5, 5, 20)};
  FrontierChoice c = ChooseFrontier(frontiers, PathFromOrigin, {}, ExplorationOptions());
  ASSERT_EQ(c.status, FrontierStatus::kOk);
  EXPECT_EQ(c.best_index, 1);
  EXPECT_EQ(c.scores[0].exclusion, FrontierExclusion::kUnreachable);
  EXPECT_NEAR(c.scores[1].size_term, 1.0, 1e-12);  // the unreachable one does not set the maximum

  c = ChooseFrontier({Frontier(-1, 0, 500)}, PathFromOrigin, {}, ExplorationOptions());
  EXPECT_EQ(c.status, FrontierStatus::kNoReachableFrontier);
  EXPECT_EQ(c.best_index, -1);
  EXPECT_EQ(DecideAction(false, c.status), ScanAction::kStuck);
}

TEST(ExplorationTest, SmallAndVisitedFrontiersAreNotCandidates) {
  int queries = 0;
  const PathLengthFn counting = [&](const Eigen::Vector3d& goal) {
    ++queries;
    return PathFromOrigin(goal);
  };
  const std::vector<FrontierCandidate> frontiers = {Frontier(1, 0, 3), Frontier(3, 0, 50), Frontier(6, 0, 10)};
  FrontierChoice c = ChooseFrontier(frontiers, counting, {Eigen::Vector3d(3.2, 0.1, 0.0)}, ExplorationOptions());
  EXPECT_EQ(c.scores[0].exclusion, FrontierExclusion::kTooSmall);
  EXPECT_EQ(c.scores[1].exclusion, FrontierExclusion::kVisited);
  EXPECT_EQ(c.best_index, 2);
  EXPECT_EQ(queries, 1);  // the navigator is only asked about real candidates

  c = ChooseFrontier({Frontier(1, 0, 3)}, counting, {}, ExplorationOptions());
  EXPECT_EQ(c.status, FrontierStatus::kNoFrontier);
  EXPECT_EQ(DecideAction(false, c.status), ScanAction::kDone);
  c = ChooseFrontier({}, counting, {}, ExplorationOptions());
  EXPECT_EQ(c.status, FrontierStatus::kNoFrontier);
}

TEST(ExplorationTest, DecideActionPutsObjectsFirst) {
  EXPECT_EQ(DecideAction(true, FrontierStatus::kOk), ScanAction::kScanObject);
  EXPECT_EQ(DecideAction(true, FrontierStatus::kNoFrontier), ScanAction::kScanObject);
  EXPECT_EQ(DecideAction(false, FrontierStatus::kOk), ScanAction::kExploreFrontier);
  EXPECT_EQ(DecideAction(false, FrontierStatus::kNoFrontier), ScanAction::kDone);
  EXPECT_EQ(DecideAction(false, FrontierStatus::kNoReachableFrontier), ScanAction::kStuck);
}

TEST(ExplorationTest, LookAroundTurnsAFullCircleInPlace) {
  ExplorationOptions options;
  options.look_around_pitches_deg = {-20.0, 10.0};
  const Eigen::Vector3d eye(1.0, 2.0, 1.2);
  const std::vector<geometry::Pose3> views = LookAroundViews(eye, 0.5, options);
  ASSERT_EQ(views.size(), 16u);
  for (std::size_t i = 0; i < views.size(); ++i) {
    EXPECT_TRUE(views[i].translation().isApprox(eye));
    double yaw, pitch;
    geometry::YawPitchOfCamera(views[i], &yaw, &pitch);
    const int k = static_cast<int>(i / 2);
    EXPECT_NEAR(geometry::WrapAngle(yaw - 0.5 - k * M_PI / 4.0), 0.0, 1e-9);
    EXPECT_NEAR(geometry::RadToDeg(pitch), i % 2 == 0 ? -20.0 : 10.0, 1e-9);
  }
}

TEST(ExplorationTest, RejectsBadInput) {
  EXPECT_THROW(ChooseFrontier({Frontier(NAN, 0, 10)}, PathFromOrigin, {}, ExplorationOptions()), InputError);
  ExplorationOptions bad;
  bad.look_around_yaw_steps = 0;
  EXPECT_THROW(bad.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::planning
