#include "objscan/render/normal_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace objscan::render {
namespace {

double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

TEST(NormalSamplerTest, MomentsTailsAndDistributionOfAStandardNormal) {
  const NormalSampler normal;
  Rng rng(2024);
  const int n = 1000000;
  std::vector<double> samples(n);
  double sum = 0, sum2 = 0, sum4 = 0;
  int beyond2 = 0, beyond3 = 0, beyond_tail = 0;
  for (double& x : samples) {
    x = normal(rng);
    sum += x;
    sum2 += x * x;
    sum4 += x * x * x * x;
    beyond2 += std::abs(x) > 2.0;
    beyond3 += std::abs(x) > 3.0;
    beyond_tail += std::abs(x) > 3.5;  // only reachable through the tail branch
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 0.005);
  EXPECT_NEAR(var, 1.0, 0.006);
  EXPECT_NEAR(sum4 / n, 3.0, 0.05);
  EXPECT_NEAR(beyond2 / double(n), 2 * Phi(-2.0), 0.0008);
  EXPECT_NEAR(beyond3 / double(n), 2 * Phi(-3.0), 0.0002);
  EXPECT_NEAR(beyond_tail / double(n), 2 * Phi(-3.5), 0.0001);
  EXPECT_GT(beyond_tail, 300);
  // Kolmogorov-Smirnov distance to the normal CDF (1.95 / sqrt(n) is the 0.1% critical value).
  std::sort(samples.begin(), samples.end());
  double ks = 0.0;
  for (int i = 0; i < n; i += 7) {
    const double F = Phi(samples[i]);
    ks = std::max({ks, std::abs(F - double(i) / n), std::abs(F - double(i + 1) / n)});
  }
  EXPECT_LT(ks, 1.95 / std::sqrt(double(n)));
}

TEST(NormalSamplerTest, SameSeedSameSequence) {
  const NormalSampler normal;
  Rng a(5), b(5), c(6);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double x = normal(a);
    EXPECT_EQ(x, normal(b));
    differs |= x != normal(c);
  }
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace objscan::render
