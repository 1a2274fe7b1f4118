#include "objscan/scanning/report/fragment_absorption.h"

#include <gtest/gtest.h>

#include <cmath>

namespace objscan::scanning {
namespace {

// Surface points of an axis-aligned box [0, size] (model frame, z up), spacing `step_m`.
std::vector<Eigen::Vector3f> BoxSurface(const Eigen::Vector3f& size, float step_m) {
  std::vector<Eigen::Vector3f> out;
  for (float x = 0.f; x <= size.x() + 1e-6f; x += step_m) {
    for (float y = 0.f; y <= size.y() + 1e-6f; y += step_m) {
      for (float z = 0.f; z <= size.z() + 1e-6f; z += step_m) {
        const bool on = x < 1e-6f || y < 1e-6f || z < 1e-6f || x > size.x() - step_m + 1e-6f ||
                        y > size.y() - step_m + 1e-6f || z > size.z() - step_m + 1e-6f;
        if (on) out.emplace_back(x, y, z);
      }
    }
  }
  return out;
}

geometry::Pose3 Placement(double yaw_rad, const Eigen::Vector3d& t) {
  geometry::Pose3 T = geometry::Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = t;
  return T;
}

std::vector<Eigen::Vector3f> Transformed(const std::vector<Eigen::Vector3f>& points, const geometry::Pose3& T,
                                         const Eigen::Vector3f& offset = Eigen::Vector3f::Zero()) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : points) out.push_back((T * (p + offset).cast<double>()).cast<float>());
  return out;
}

class FragmentAbsorptionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = BoxSurface(Eigen::Vector3f(1.2f, 0.6f, 0.5f), 0.02f);
    T_world_model_ = Placement(0.5, Eigen::Vector3d(2.0, 1.0, 0.0));
    // The host: the model's surface without its top, seen in the world (slightly off the model).
    FragmentCandidate host;
    for (const auto& p : model_) {
      if (p.z() < 0.49f) host.points_world.push_back((T_world_model_ * (p + Eigen::Vector3f(0, 0, 0.01f)).cast<double>()).cast<float>());
    }
    host.objectness = 0.9;
    host.model_points = model_;
    host.T_world_model = T_world_model_;
    objects_.push_back(host);
    // A fragment: a 30 x 30 cm patch of the model's top, 2 cm above it.
    FragmentCandidate top;
    for (const auto& p : model_) {
      if (p.z() > 0.49f && p.x() < 0.3f && p.y() < 0.3f) top.points_world.push_back(p);
    }
    top.points_world = Transformed(top.points_world, T_world_model_, Eigen::Vector3f(0, 0, 0.02f));
    top.objectness = 0.85;
    objects_.push_back(top);
    // A neighbour: a small box standing 10 cm beside the model's +x end.
    FragmentCandidate beside;
    beside.points_world =
        Transformed(BoxSurface(Eigen::Vector3f(0.3f, 0.3f, 0.4f), 0.02f), T_world_model_, Eigen::Vector3f(1.3f, 0, 0));
    beside.objectness = 0.9;
    objects_.push_back(beside);
  }
  std::vector<Eigen::Vector3f> model_;
  geometry::Pose3 T_world_model_;
  std::vector<FragmentCandidate> objects_;
};

TEST_F(FragmentAbsorptionTest, PieceOnTheHostsModelJoinsItANeighbourDoesNot) {
  const std::vector<int> host = AbsorbExplainedFragments(objects_, FragmentAbsorptionOptions());
  EXPECT_EQ(host, (std::vector<int>{0, 0, 2}));
}

TEST_F(FragmentAbsorptionTest, UnsureHostOrLargeFragmentKeepsEverythingApart) {
  auto unsure = objects_;
  unsure[0].objectness = 0.7;  // below min_host_objectness
  EXPECT_EQ(AbsorbExplainedFragments(unsure, FragmentAbsorptionOptions()), (std::vector<int>{0, 1, 2}));
  FragmentAbsorptionOptions small_ratio;
  small_ratio.max_size_ratio = 0.01;  // the top patch has ~5% of the host's points
  EXPECT_EQ(AbsorbExplainedFragments(objects_, small_ratio), (std::vector<int>{0, 1, 2}));
  auto replaced = objects_;
  replaced[1].may_be_absorbed = false;
  EXPECT_EQ(AbsorbExplainedFragments(replaced, FragmentAbsorptionOptions()), (std::vector<int>{0, 1, 2}));
}

TEST_F(FragmentAbsorptionTest, FragmentMustLieOnTheSurfaceNotJustNearTheBox) {
  // The same patch lifted 10 cm above the top: inside the grown box test's reach only partly, and
  // never within distance_m of the surface.
  auto lifted = objects_;
  for (auto& p : lifted[1].points_world) p.z() += 0.08f;
  EXPECT_EQ(AbsorbExplainedFragments(lifted, FragmentAbsorptionOptions())[1], 1);
  // Half on, half off: below min_explained_fraction.
  auto half = objects_;
  for (std::size_t i = 0; i < half[1].points_world.size(); i += 2) half[1].points_world[i].z() += 0.3f;
  EXPECT_EQ(AbsorbExplainedFragments(half, FragmentAbsorptionOptions())[1], 1);
}

TEST_F(FragmentAbsorptionTest, ModelOnlyHostAbsorbsAndLargestHostGoesFirst) {
  // A completed object: no points left in the map, only its size and model.
  auto with_completed = objects_;
  with_completed[0].points_world.clear();
  with_completed[0].num_points = 5000;
  with_completed[0].may_be_absorbed = false;
  EXPECT_EQ(AbsorbExplainedFragments(with_completed, FragmentAbsorptionOptions()), (std::vector<int>{0, 0, 2}));
  // A second, smaller host whose model also covers the patch: the larger one takes it.
  auto two_hosts = objects_;
  FragmentCandidate small_host = objects_[0];
  small_host.points_world.resize(small_host.points_world.size() / 3);
  two_hosts.push_back(small_host);
  const std::vector<int> host = AbsorbExplainedFragments(two_hosts, FragmentAbsorptionOptions());
  EXPECT_EQ(host[1], 0);
  EXPECT_EQ(host[3], 0);  // itself a piece of the larger host's model
}

}  // namespace
}  // namespace objscan::scanning
