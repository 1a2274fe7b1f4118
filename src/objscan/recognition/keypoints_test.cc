#include "objscan/recognition/keypoints.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition {
namespace {

// Distance of each point to its nearest other point, ascending (brute force).
std::vector<double> NearestNeighbourDistances(const std::vector<Eigen::Vector3f>& pts) {
  std::vector<double> nn;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double best = 1e9;
    for (std::size_t j = 0; j < pts.size(); ++j) {
      if (j != i) best = std::min<double>(best, (pts[i] - pts[j]).norm());
    }
    nn.push_back(best);
  }
  std::sort(nn.begin(), nn.end());
  return nn;
}

TEST(KeypointsTest, LloydKeypointsAreSpreadOnAUniformPlane) {
  Rng data_rng(3);
  const auto plane = testing::UniformPlane(2.0, 1.0, 20000, &data_rng);
  KeypointOptions options;
  options.density_voxel_m = 0.0;
  Rng rng(7);
  const std::vector<int> idx = SampleKeypointsLloyd(plane, options, &rng);
  ASSERT_EQ(idx.size(), 500u);
  std::vector<Eigen::Vector3f> kp;
  for (int i : idx) kp.push_back(plane[i]);
  // Hexagonal packing of 500 points on 2 m^2 has spacing sqrt(2 * A / (sqrt(3) * n)) = 0.068 m.
  const double hex_spacing = std::sqrt(2.0 * 2.0 / (std::sqrt(3.0) * 500));
  // A centroidal Voronoi relaxation is near-hexagonal with a few local defects: no two keypoints are
  // closer than 0.4 of the ideal spacing and 95% have their nearest neighbour beyond 0.55 of it.
  const std::vector<double> nn = NearestNeighbourDistances(kp);
  EXPECT_GT(nn.front(), 0.4 * hex_spacing);
  EXPECT_GT(nn[nn.size() / 20], 0.55 * hex_spacing);
  // Random sampling of the same points is far less even: its closest pair is much closer.
  std::vector<Eigen::Vector3f> random(plane.begin(), plane.begin() + 500);
  EXPECT_LT(NearestNeighbourDistances(random).front(), 0.2 * hex_spacing);
  // Every part of the plane is near a keypoint (covering radius close to the hex cell's).
  double worst = 0.0;
  for (int i = 0; i < 20000; i += 7) {
    double best = 1e9;
    for (const auto& k : kp) best = std::min<double>(best, (k - plane[i]).norm());
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, 1.2 * hex_spacing);
}

TEST(KeypointsTest, DeterministicDistinctAndSnappedToInputPoints) {
  Rng data_rng(5);
  const auto plane = testing::UniformPlane(1.0, 1.0, 8000, &data_rng);
  KeypointOptions options;
  Rng a(11), b(11);
  const auto ka = SampleKeypointsLloyd(plane, options, &a);
  const auto kb = SampleKeypointsLloyd(plane, options, &b);
  EXPECT_EQ(ka, kb);
  std::set<int> distinct(ka.begin(), ka.end());
  EXPECT_EQ(distinct.size(), ka.size());
  for (int i : ka) {
    EXPECT_GE(i, 0);
    EXPECT_LT(i, 8000);
  }
}

// The documented algorithm with brute-force searches: the fast implementation (vectorised
// farthest-point sampling, hinted kd-tree searches) must choose exactly the same points.
std::vector<int> ReferenceLloyd(const std::vector<Eigen::Vector3f>& points, const KeypointOptions& options, Rng* rng) {
  const std::vector<int> candidates = VoxelThin(points, options.density_voxel_m);
  const int n_keypoints = options.num_keypoints;
  std::vector<int> relax = candidates;
  if (static_cast<int>(relax.size()) > options.max_relaxation_points) {
    for (int i = 0; i < options.max_relaxation_points; ++i) {
      std::swap(relax[i], relax[rng->UniformInt(i, static_cast<int>(relax.size()) - 1)]);
    }
    relax.resize(options.max_relaxation_points);
    std::sort(relax.begin(), relax.end());
  }
  const int n = static_cast<int>(relax.size());
  std::vector<Eigen::Vector3f> centres;
  std::vector<float> d2(n, std::numeric_limits<float>::infinity());
  int next = rng->UniformInt(0, n - 1);
  for (int k = 0; k < n_keypoints; ++k) {
    centres.push_back(points[relax[next]]);
    int far = 0;
    for (int i = 0; i < n; ++i) {
      d2[i] = std::min(d2[i], (points[relax[i]] - centres.back()).squaredNorm());
      if (d2[i] > d2[far]) far = i;
    }
    next = far;
  }
  for (int it = 0; it < options.lloyd_iterations; ++it) {
    std::vector<Eigen::Vector3d> sums(n_keypoints, Eigen::Vector3d::Zero());
    std::vector<int> counts(n_keypoints, 0);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3f& p = points[relax[i]];
      int best = 0;
      for (int c = 1; c < n_keypoints; ++c) {
        if ((centres[c] - p).squaredNorm() < (centres[best] - p).squaredNorm()) best = c;
      }
      sums[best] += p.cast<double>();
      ++counts[best];
    }
    for (int k = 0; k < n_keypoints; ++k) {
      if (counts[k] > 0) centres[k] = (sums[k] / counts[k]).cast<float>();
    }
  }
  std::vector<char> used(candidates.size(), 0);
  std::vector<int> keypoints;
  for (const auto& c : centres) {
    int best = -1;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      if (used[j]) continue;
      if (best < 0 || (points[candidates[j]] - c).squaredNorm() < (points[candidates[best]] - c).squaredNorm()) {
        best = static_cast<int>(j);
      }
    }
    used[best] = 1;
    keypoints.push_back(candidates[best]);
  }
  return keypoints;
}

TEST(KeypointsTest, MatchesTheBruteForceReference) {
  std::vector<Eigen::Vector3f> pts, normals;
  testing::SofaLike(0.01, &pts, &normals);
  Rng noise(5);
  for (auto& p : pts) p += Eigen::Vector3f(noise.Normal(0, 0.002), noise.Normal(0, 0.002), noise.Normal(0, 0.002));
  KeypointOptions options;
  options.num_keypoints = 150;
  options.max_relaxation_points = 3000;  // fewer than the thinned points: the random subset is used
  ASSERT_GT(VoxelThin(pts, options.density_voxel_m).size(), 3000u);
  Rng rng_fast(9), rng_reference(9);
  EXPECT_EQ(SampleKeypointsLloyd(pts, options, &rng_fast), ReferenceLloyd(pts, options, &rng_reference));
}

// Farthest-point order against a plain scan: each pick is the first point farthest from those picked.
TEST(KeypointsTest, FarthestPointOrderMatchesAPlainScan) {
  Rng rng(3);
  std::vector<Eigen::Vector3f> pts(400);
  for (auto& p : pts) p = Eigen::Vector3f(rng.Uniform01(), rng.Uniform01(), 0.3 * rng.Uniform01());
  const int start = 17, count = 60;
  std::vector<int> expected{start};
  std::vector<float> d2(pts.size(), std::numeric_limits<float>::infinity());
  while (static_cast<int>(expected.size()) < count) {
    std::size_t far = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      d2[i] = std::min(d2[i], (pts[i] - pts[expected.back()]).squaredNorm());
      if (d2[i] > d2[far]) far = i;
    }
    expected.push_back(static_cast<int>(far));
  }
  EXPECT_EQ(FarthestPointOrder(pts, count, start), expected);
  // Three points, five picks: all three, then the first index (every distance is zero) again.
  const std::vector<Eigen::Vector3f> three = {{0, 0, 0}, {1, 0, 0}, {0.4f, 0, 0}};
  EXPECT_EQ(FarthestPointOrder(three, 5, 0), (std::vector<int>{0, 1, 2, 0, 0}));
  EXPECT_TRUE(FarthestPointOrder({}, 3, 0).empty());
  EXPECT_TRUE(FarthestPointOrder(three, 0, 0).empty());
}

TEST(KeypointsTest, FewerPointsThanKeypointsGivesAllPoints) {
  Rng data_rng(1);
  const auto plane = testing::UniformPlane(1.0, 1.0, 120, &data_rng);
  KeypointOptions options;
  options.density_voxel_m = 0.0;
  Rng rng(1);
  const auto k = SampleKeypointsLloyd(plane, options, &rng);
  ASSERT_EQ(k.size(), 120u);
  for (int i = 0; i < 120; ++i) EXPECT_EQ(k[i], i);
}

TEST(KeypointsTest, DensityVoxelMakesKeypointsFollowAreaNotSampling) {
  // Left half sampled 10x more densely than the right half: after voxel thinning the keypoints
  // split about evenly between the halves.
  Rng data_rng(9);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 40000; ++i) pts.emplace_back(data_rng.Uniform(0, 0.5), data_rng.Uniform(0, 1), 0.f);
  for (int i = 0; i < 4000; ++i) pts.emplace_back(data_rng.Uniform(0.5, 1), data_rng.Uniform(0, 1), 0.f);
  KeypointOptions options;
  options.num_keypoints = 200;
  options.density_voxel_m = 0.02;
  Rng rng(2);
  const auto k = SampleKeypointsLloyd(pts, options, &rng);
  ASSERT_EQ(k.size(), 200u);
  int left = 0;
  for (int i : k) left += pts[i].x() < 0.5f ? 1 : 0;
  EXPECT_NEAR(left, 100, 15);
}

}  // namespace
}  // namespace objscan::recognition
