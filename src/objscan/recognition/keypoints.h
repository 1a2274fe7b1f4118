#pragma once
// Keypoints by Lloyd's algorithm (paper §4.2: n_p = 500 keypoints uniformly spread over a point set):
// a centroidal Voronoi relaxation of the points, initialised by farthest-point sampling from a seeded
// start, each centre finally snapped to the nearest actual point. Same input and seed, same keypoints.
#include <Eigen/Core>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/rng.h"

namespace objscan::recognition {

struct KeypointOptions {
  int num_keypoints = 500;           // n_p
  int lloyd_iterations = 8;          // assign/recentre rounds after farthest-point initialisation
  double density_voxel_m = 0.01;     // the input is thinned to one point per voxel so keypoints
                                     // follow surface area, not the sensor's sampling density
  int max_relaxation_points = 6000;  // at most this many points drive the relaxation (random subset)

  template <class V>
  void Visit(V& v) {
    v("num_keypoints", num_keypoints);
    v("lloyd_iterations", lloyd_iterations);
    v("density_voxel_m", density_voxel_m);
    v("max_relaxation_points", max_relaxation_points);
  }
  void Validate() const;
};

// Indices into `points` of min(n_p, distinct points) keypoints, all distinct. Points closer than a
// density voxel count once. `rng` picks the first farthest-point seed and the relaxation subset.
std::vector<int> SampleKeypointsLloyd(const std::vector<Eigen::Vector3f>& points, const KeypointOptions& options,
                                      Rng* rng);

// `count` indices into `points` in farthest-point order from index `start`: each next one is the
// point farthest from those already picked (the first such index on ties). Once every point is
// picked, the rest repeat; empty for no points.
std::vector<int> FarthestPointOrder(const std::vector<Eigen::Vector3f>& points, int count, int start);

// Thins points to one per voxel (the first in input order); returns the kept indices in input order.
std::vector<int> VoxelThin(const std::vector<Eigen::Vector3f>& points, double voxel_m);

}  // namespace objscan::recognition
