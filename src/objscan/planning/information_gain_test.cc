#include "objscan/planning/information_gain.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"

namespace objscan::planning {
namespace {

TEST(InformationGainTest, CandidateProbabilitiesNormaliseObjectness) {
  const std::vector<double> p = CandidateProbabilities({0.8, 0.4, 0.4});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_DOUBLE_EQ(p[0], 0.5);
  EXPECT_DOUBLE_EQ(p[1], 0.25);
  EXPECT_DOUBLE_EQ(p[2], 0.25);
  const std::vector<double> uniform = CandidateProbabilities({0.0, 0.0});
  EXPECT_DOUBLE_EQ(uniform[0], 0.5);
  EXPECT_THROW(CandidateProbabilities({0.5, -0.1}), InputError);
}

TEST(InformationGainTest, EntropyOfUniformIsLogN) {
  const double p[4] = {0.25, 0.25, 0.25, 0.25};
  EXPECT_NEAR(Entropy(p, 4), std::log(4.0), 1e-15);
  const double certain[2] = {1.0, 0.0};
  EXPECT_EQ(Entropy(certain, 2), 0.0);
}

TEST(InformationGainTest, TwoModelsOneVoxelOnlyOneModelPredictsIt) {
  // p = (1/2, 1/2), f = (1, 0): seeing the voxel (or not) tells the models apart completely.
  const double p[2] = {0.5, 0.5};
  const float f[2] = {1.0f, 0.0f};
  const double h = Entropy(p, 2);
  double h0, h1;
  OutcomeEntropies(p, f, 2, h, &h0, &h1);
  EXPECT_NEAR(h, std::log(2.0), 1e-15);
  EXPECT_NEAR(h0, 0.0, 1e-15);  // empty voxel: certainly m_2
  EXPECT_NEAR(h1, 0.0, 1e-15);  // occupied voxel: certainly m_1
  EXPECT_NEAR(h - ConditionalEntropy(f[0], h0, h1), std::log(2.0), 1e-15);
  EXPECT_NEAR(h - ConditionalEntropy(f[1], h0, h1), std::log(2.0), 1e-15);
}

TEST(InformationGainTest, TwoModelsOneVoxelSoftValuesMatchHandComputation) {
  // p = (0.75, 0.25), f = (0.5, 0.2).
  //   H     = -(0.75 ln 0.75 + 0.25 ln 0.25)                           = 0.5623351446188083
  //   d = 1: p(m|1) = (0.375, 0.05) / 0.425 = (0.88235, 0.11765),  H_x(1) = 0.362210557135449
  //   d = 0: p(m|0) = (0.375, 0.2) / 0.575  = (0.65217, 0.34783),  H_x(0) = 0.646090505060809
  //   H(x|m_1) = 0.5 H_x(0) + 0.5 H_x(1),  H(x|m_2) = 0.8 H_x(0) + 0.2 H_x(1)
  //   gains: 0.058184613520679274 and -0.026979370856928697; G = 0.03689361742627728
  const double p[2] = {0.75, 0.25};
  const float f[2] = {0.5f, 0.2f};
  const double h = Entropy(p, 2);
  double h0, h1;
  OutcomeEntropies(p, f, 2, h, &h0, &h1);
  const double tol = 1e-7;  // f is float: 0.2f is 0.2 + 3e-9
  EXPECT_NEAR(h, 0.5623351446188083, 1e-15);
  EXPECT_NEAR(h0, 0.646090505060809, tol);
  EXPECT_NEAR(h1, 0.362210557135449, tol);
  const double g1 = h - ConditionalEntropy(f[0], h0, h1);
  const double g2 = h - ConditionalEntropy(f[1], h0, h1);
  EXPECT_NEAR(g1, 0.058184613520679274, tol);
  EXPECT_NEAR(g2, -0.026979370856928697, tol);
  EXPECT_NEAR(p[0] * g1 + p[1] * g2, 0.03689361742627728, tol);
}

TEST(InformationGainTest, AgreeingModelsGiveNoGain) {
  const double p[3] = {0.5, 0.3, 0.2};
  const float f[3] = {0.4f, 0.4f, 0.4f};
  const double h = Entropy(p, 3);
  double h0, h1;
  OutcomeEntropies(p, f, 3, h, &h0, &h1);
  EXPECT_NEAR(h0, h, 1e-12);
  EXPECT_NEAR(h1, h, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(h - ConditionalEntropy(f[i], h0, h1), 0.0, 1e-12);
}

TEST(InformationGainTest, ImpossibleOutcomeKeepsPriorEntropy) {
  // No candidate puts anything here: "occupied" cannot happen, "empty" leaves the prior unchanged.
  const double p[2] = {0.6, 0.4};
  const float f[2] = {0.0f, 0.0f};
  const double h = Entropy(p, 2);
  double h0, h1;
  OutcomeEntropies(p, f, 2, h, &h0, &h1);
  EXPECT_NEAR(h0, h, 1e-15);
  EXPECT_EQ(h1, h);
}

}  // namespace
}  // namespace objscan::planning
