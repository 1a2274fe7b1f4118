#pragma once
// What the robot has observed of the space around a recognition hypothesis. A model placed where the
// sensor saw through (known free space), under the floor or behind a wall is wrong however well it
// fits the points it was aligned to: a refrigerator fitted to the face of a window puts its body in
// the air in front of the window or outside the room. The recognizer asks for the share of a placed
// model's keypoints that lie where no surface can be.
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace objscan::recognition {

class SpaceEvidence {
 public:
  virtual ~SpaceEvidence() = default;
  // The share (in [0, 1]) of `model_points_world` that lie where no surface can be, for a model
  // aligned to a query whose keypoints' centroid is `query_center_world` (so that a query itself
  // beyond a wall, e.g. seen through a door, is not judged by that wall). 0 for no points.
  virtual double ImpossibleFraction(const std::vector<Eigen::Vector3f>& model_points_world,
                                    const Eigen::Vector3f& query_center_world) const = 0;
  // The squared distance from p, on model surface with outward unit normal n, to the nearest surface
  // of observed structure that can hide it (the floor; a wall plane, within its span and height,
  // when the face turns to it); +inf when there is none. Model surface there is not seen apart from
  // the structure (RecognitionOptions::structure_completeness).
  // The height of the detected floor, when there is one.
  virtual std::optional<double> FloorHeight() const { return std::nullopt; }
  virtual double SquaredDistanceToStructure(const Eigen::Vector3f& /*p_world*/,
                                            const Eigen::Vector3f& /*n_world*/) const {
    return std::numeric_limits<double>::infinity();
  }
};

}  // namespace objscan::recognition
