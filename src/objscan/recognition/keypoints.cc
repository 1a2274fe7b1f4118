#include "objscan/recognition/keypoints.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_set>

#include "objscan/geometry/voxel_key.h"
#include "objscan/recognition/kd_tree.h"

namespace objscan::recognition {

void KeypointOptions::Validate() const {
  config::Require(num_keypoints >= 1, "recognition.keypoints.num_keypoints", "must be at least 1");
  config::Require(lloyd_iterations >= 0, "recognition.keypoints.lloyd_iterations", "must be >= 0");
  config::RequireNonNegative("recognition.keypoints.density_voxel_m", density_voxel_m);
  config::Require(max_relaxation_points >= num_keypoints, "recognition.keypoints.max_relaxation_points",
                  "must be >= num_keypoints");
}

std::vector<int> VoxelThin(const std::vector<Eigen::Vector3f>& points, double voxel_m) {
  std::vector<int> kept;
  kept.reserve(points.size());
  if (voxel_m <= 0.0) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  const float inv = static_cast<float>(1.0 / voxel_m);
  std::unordered_set<geometry::VoxelKey, geometry::VoxelKeyHash> seen;
  seen.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    if (seen.insert(geometry::KeyOf(points[i], inv)).second) kept.push_back(static_cast<int>(i));
  }
  return kept;
}

std::vector<int> SampleKeypointsLloyd(const std::vector<Eigen::Vector3f>& points, const KeypointOptions& options,
                                      Rng* rng) {
  std::vector<int> candidates = VoxelThin(points, options.density_voxel_m);
  const int n_keypoints = options.num_keypoints;
  if (static_cast<int>(candidates.size()) <= n_keypoints) return candidates;

  // Relaxation set: a seeded random subset when there are too many points (partial Fisher-Yates).
  std::vector<int> relax = candidates;
  if (static_cast<int>(relax.size()) > options.max_relaxation_points) {
    for (int i = 0; i < options.max_relaxation_points; ++i) {
      const int j = rng->UniformInt(i, static_cast<int>(relax.size()) - 1);
      std::swap(relax[i], relax[j]);
    }
    relax.resize(options.max_relaxation_points);
    std::sort(relax.begin(), relax.end());  // order independent of the shuffle's path
  }
  const int n = static_cast<int>(relax.size());
  std::vector<Eigen::Vector3f> pts(n);
  for (int i = 0; i < n; ++i) pts[i] = points[relax[i]];

  // Farthest-point initialisation from a seeded start.
  std::vector<Eigen::Vector3f> centres;
  centres.reserve(n_keypoints);
  std::vector<float> d2(n, std::numeric_limits<float>::infinity());
  int next = rng->UniformInt(0, n - 1);
  for (int k = 0; k < n_keypoints; ++k) {
    centres.push_back(pts[next]);
    int far = 0;
    float far_d2 = -1.f;
    for (int i = 0; i < n; ++i) {
      const float d = (pts[i] - centres.back()).squaredNorm();
      if (d < d2[i]) d2[i] = d;
      if (d2[i] > far_d2) {
        far_d2 = d2[i];
        far = i;
      }
    }
    next = far;
  }

  // Lloyd: assign every point to its nearest centre, move each centre to its cell's centroid.
  std::vector<Eigen::Vector3d> sums(n_keypoints);
  std::vector<int> counts(n_keypoints);
  KdTree3 centre_tree;
  for (int it = 0; it < options.lloyd_iterations; ++it) {
    centre_tree.Build(centres);
    std::fill(sums.begin(), sums.end(), Eigen::Vector3d::Zero());
    std::fill(counts.begin(), counts.end(), 0);
    for (int i = 0; i < n; ++i) {
      const int c = centre_tree.Nearest(pts[i], nullptr);
      sums[c] += pts[i].cast<double>();
      ++counts[c];
    }
    for (int k = 0; k < n_keypoints; ++k) {
      if (counts[k] > 0) centres[k] = (sums[k] / counts[k]).cast<float>();
    }
  }

  // Snap each centre to the nearest actual point (of all thinned candidates), keeping them distinct.
  std::vector<Eigen::Vector3f> candidate_points(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) candidate_points[i] = points[candidates[i]];
  const KdTree3 point_tree(candidate_points);
  std::vector<char> used(candidates.size(), 0);
  std::vector<int> keypoints;
  keypoints.reserve(n_keypoints);
  std::vector<int> knn;
  for (int k = 0; k < n_keypoints; ++k) {
    int chosen = point_tree.Nearest(centres[k], nullptr);
    if (used[chosen]) {
      chosen = -1;
      for (int kk = 8; chosen < 0 && kk <= static_cast<int>(candidates.size()); kk *= 4) {
        point_tree.KNearest(centres[k], kk, &knn, nullptr);
        for (int idx : knn) {
          if (!used[idx]) {
            chosen = idx;
            break;
          }
        }
      }
      if (chosen < 0) continue;
    }
    used[chosen] = 1;
    keypoints.push_back(candidates[chosen]);
  }
  return keypoints;
}

}  // namespace objscan::recognition
