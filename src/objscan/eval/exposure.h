#pragma once
// Which ground-truth surface voxels a camera in the room could ever see. The surface of a mesh
// includes faces no camera reaches: the underside of a bed resting on the floor, the back of a
// cabinet flush against a wall, the inside of a closed box. Counting them in V_S caps the coverage
// rate well below 1 whatever the robot does.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "objscan/world/scene.h"

namespace objscan::eval {

// Steps of at most `step_m` along the edge from a to b (at least 1).
inline int SampleCount(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double step_m) {
  return std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
}

// Calls fn(p) for (SampleCount(a, b) + 1) * (SampleCount(a, c) + 1) points spread over triangle
// (a, b, c), at most `step_m` apart along its edges (points beyond the b-c edge are folded back).
template <class Fn>
void SampleTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double step_m,
                    Fn&& fn) {
  const int nu = SampleCount(a, b, step_m);
  const int nv = SampleCount(a, c, step_m);
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
      if (u + v > 1.0) {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      fn(a + u * (b - a) + v * (c - a));
    }
  }
}

// For each of `voxel_centers_world` (voxels of side `voxel_m`): 1 when one of its six face
// neighbours is empty (touched by no triangle of the scene, walls and floor included) and joined to
// the voxel holding `seed_world` through empty voxels between the floor's top and the layer below
// the walls' top (when the scene has floors and walls); 0 otherwise. `seed_world` is a point of the
// room's free space (e.g. the robot's first camera position); when its voxel is not empty, the
// nearest empty voxel within two voxels is used. All 0 when there is none.
//
// With a camera height band (heights above the floor's top, or above z = 0 without a floor), a
// voxel exposed only through its lower face counts when part of it lies above the band's lowest
// camera (a face seen from below needs a camera below it: the underside of a bed frame 12 cm above
// the floor is hidden from a camera no lower than 30 cm), and one exposed only through its upper
// face when part of it lies below the band's highest camera (the top of a 2 m wardrobe is hidden
// from a camera no higher than 1.8 m). Side faces count at any height. The default band holds every
// height.
struct CameraHeightBand {
  double min_height_m = -std::numeric_limits<double>::infinity();
  double max_height_m = std::numeric_limits<double>::infinity();
};
std::vector<char> ExposedVoxels(const world::Scene& scene, const std::vector<Eigen::Vector3d>& voxel_centers_world,
                                double voxel_m, const Eigen::Vector3d& seed_world, const CameraHeightBand& band = {});

// The room's air as ExposedVoxels sees it: the empty voxels joined to the seed (between the floor's
// top and the layer below the walls' top). Where a camera of the robot can be.
class RoomAir {
 public:
  // Throws InputError as ExposedVoxels. Holds no air when the seed has no empty voxel near it.
  RoomAir(const world::Scene& scene, double voxel_m, const Eigen::Vector3d& seed_world);

  bool Contains(const Eigen::Vector3d& p_world) const;

  // Limits where a camera can be to the robot's reach: within max_reach_m (horizontally) of a base
  // position whose disk of base_radius_m is air from the floor up to base_height_m, joined on the
  // floor to the seed's column (or to the nearest such position within 1 m of it; with none, no
  // limit). Contains() is unchanged; CameraCanBeAt() applies the limit.
  void RestrictToRobotReach(double base_radius_m, double base_height_m, double max_reach_m);
  bool CameraCanBeAt(const Eigen::Vector3d& p_world) const;

  double voxel_m() const { return voxel_m_; }
  double floor_top_m() const { return floor_top_m_; }  // 0 without a floor

  // ExposedVoxels on this air.
  std::vector<char> Exposed(const std::vector<Eigen::Vector3d>& voxel_centers_world,
                            const CameraHeightBand& band = {}) const;

 private:
  Eigen::Vector3i KeyOf(const Eigen::Vector3d& p) const;
  bool Inside(const Eigen::Vector3i& k) const;
  std::size_t Index(const Eigen::Vector3i& k) const;

  double voxel_m_ = 0.0;
  double floor_top_m_ = 0.0;
  Eigen::Vector3i min_key_ = Eigen::Vector3i::Zero();
  Eigen::Vector3i size_ = Eigen::Vector3i::Zero();
  std::vector<std::uint8_t> state_;  // 0 unreached empty, 1 touched by a triangle, 2 air
  Eigen::Vector3i seed_key_ = Eigen::Vector3i::Zero();
  int z_lo_ = 0;                      // lowest air layer
  std::vector<std::uint8_t> camera_xy_;  // per x-y column: 1 within reach (empty = no limit)
};

}  // namespace objscan::eval
