#pragma once
// Test shapes against a wall: hand-made point sets for the wall-opening and report-rule tests.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "objscan/mapping/planes.h"
#include "objscan/mapping/testing/one_wall.h"

namespace objscan::scanning::testing {

// A room whose wall x = 0 faces +x, 4 m long and 2.5 m high, over a floor at z = 0.
inline mapping::StructureResult OneWallRoom() {
  mapping::StructureResult s = mapping::testing::OneWall();
  s.has_floor = true;
  s.floor_height_m = 0.0;
  return s;
}

// A vertical rectangle of points at x = `x`, y in [y0, y1], z in [z0, z1], 2 cm apart.
inline std::vector<Eigen::Vector3f> Pane(double x, double y0, double y1, double z0, double z1) {
  std::vector<Eigen::Vector3f> points;
  for (double y = y0; y <= y1 + 1e-9; y += 0.02) {
    for (double z = z0; z <= z1 + 1e-9; z += 0.02) points.emplace_back(x, y, z);
  }
  return points;
}

inline void Append(const std::vector<Eigen::Vector3f>& more, std::vector<Eigen::Vector3f>* points) {
  points->insert(points->end(), more.begin(), more.end());
}

// A pleated curtain panel hanging in front of the wall: folds 8 cm deep around x0, 10 cm wide.
inline std::vector<Eigen::Vector3f> Pleats(double x0, double y0, double y1, double z0, double z1) {
  std::vector<Eigen::Vector3f> points;
  for (double y = y0; y <= y1 + 1e-9; y += 0.01) {
    const double phase = std::fmod(y - y0 + 1e-9, 0.1) / 0.1;
    const double x = x0 - 0.04 + 0.08 * (phase < 0.5 ? 2.0 * phase : 2.0 - 2.0 * phase);
    for (double z = z0; z <= z1 + 1e-9; z += 0.02) points.emplace_back(x, y, z);
  }
  return points;
}

}  // namespace objscan::scanning::testing
