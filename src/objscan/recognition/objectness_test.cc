#include "objscan/recognition/objectness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition {
namespace {

std::vector<Eigen::Vector3f> Keypoints(const std::vector<Eigen::Vector3f>& pts, std::uint64_t seed) {
  KeypointOptions options;
  Rng rng(seed);
  std::vector<Eigen::Vector3f> kp;
  for (int i : SampleKeypointsLloyd(pts, options, &rng)) kp.push_back(pts[i]);
  return kp;
}

class ObjectnessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<Eigen::Vector3f> normals;
    testing::ChairLike(0.01, &chair_, &normals);
    chair_kp_ = Keypoints(chair_, 1);
  }
  std::vector<Eigen::Vector3f> chair_, chair_kp_;
};

TEST_F(ObjectnessTest, IdenticalPointSetsHaveObjectnessOne) {
  const auto t = ComputeObjectness(chair_kp_, chair_kp_, Eigen::Affine3d::Identity());
  EXPECT_DOUBLE_EQ(t.similarity_m2, 0.0);
  EXPECT_DOUBLE_EQ(t.completeness_m2, 0.0);
  EXPECT_DOUBLE_EQ(t.objectness, 1.0);
}

TEST_F(ObjectnessTest, MatchesEquationOneByBruteForce) {
  // Small sets: d(X,Y) and O computed by hand.
  std::vector<Eigen::Vector3f> c = {{0, 0, 0}, {1, 0, 0}};
  std::vector<Eigen::Vector3f> m = {{0, 0, 0.1f}, {1, 0, 0}, {2, 0, 0}};
  const auto t = ComputeObjectness(c, m, Eigen::Affine3d::Identity());
  const double d_cm = (0.01 + 0.0) / 2.0;
  const double d_mc = (0.01 + 0.0 + 1.0) / 3.0;
  EXPECT_NEAR(t.similarity_m2, d_cm, 1e-7);
  EXPECT_NEAR(t.completeness_m2, d_mc, 1e-7);
  EXPECT_NEAR(t.diagonal_m, 1.0, 1e-12);
  EXPECT_NEAR(t.objectness, std::exp(-std::sqrt(d_cm + d_mc) / 1.0), 1e-6);
}

TEST_F(ObjectnessTest, UsesTheAlignmentTransform) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  T.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  std::vector<Eigen::Vector3f> moved;
  for (const auto& p : chair_kp_) moved.push_back((T.inverse() * p.cast<double>()).cast<float>());
  EXPECT_NEAR(ComputeObjectness(moved, chair_kp_, T).objectness, 1.0, 1e-5);
  EXPECT_LT(ComputeObjectness(moved, chair_kp_, Eigen::Affine3d::Identity()).objectness, 0.8);
}

TEST_F(ObjectnessTest, FallsAsTheQueryIsCropped) {
  double previous = 1.01;
  for (double keep_z : {1.0, 0.7, 0.45, 0.3}) {
    std::vector<Eigen::Vector3f> cropped;
    for (const auto& p : chair_) {
      if (p.z() <= keep_z) cropped.push_back(p);
    }
    const auto c_kp = Keypoints(cropped, 2);
    const double o = ComputeObjectness(c_kp, chair_kp_, Eigen::Affine3d::Identity()).objectness;
    EXPECT_LT(o, previous) << "crop at z <= " << keep_z;
    previous = o;
  }
  EXPECT_LT(previous, 0.65);  // only the legs are left
}

TEST_F(ObjectnessTest, FallsAsNoiseGrows) {
  double previous = 1.01;
  for (double sigma : {0.0, 0.01, 0.02, 0.04}) {
    Rng rng(4);
    std::vector<Eigen::Vector3f> noisy = chair_;
    for (auto& p : noisy) p += Eigen::Vector3f(rng.Normal(0, sigma), rng.Normal(0, sigma), rng.Normal(0, sigma));
    const auto c_kp = Keypoints(noisy, 2);
    const double o = ComputeObjectness(c_kp, chair_kp_, Eigen::Affine3d::Identity()).objectness;
    EXPECT_LT(o, previous) << "sigma " << sigma;
    previous = o;
  }
}

TEST_F(ObjectnessTest, CompleteFreshSamplingScoresAboveTheCompletionThreshold) {
  // The same surface sampled again (different seed) is a complete object: O > 0.96 (paper §6.1).
  std::vector<Eigen::Vector3f> resampled, normals;
  testing::ChairLike(0.0085, &resampled, &normals);
  const auto c_kp = Keypoints(resampled, 99);
  EXPECT_GT(ComputeObjectness(c_kp, chair_kp_, Eigen::Affine3d::Identity()).objectness, 0.96);
}

}  // namespace
}  // namespace objscan::recognition
