#pragma once
// Beyond the paper: fragments explained by a neighbour's model. The graph cut keeps a small piece
// apart from a large object when joining them does not raise the object's objectness (a recognized
// bed with a strip of its frame seen through a gap, a table with a leg split off by occlusion); the
// piece then counts as an object of its own, usually mis-labelled. When the large object's aligned
// database model covers the piece (most of its points lie on that model's surface), the piece is
// part of it.
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/geometry/pose.h"

namespace objscan::scanning {

struct FragmentAbsorptionOptions {
  double min_host_objectness = 0.8;     // only an object recognized at least this well lends its model
  double distance_m = 0.05;             // a point lies on the model's surface within this distance
  double min_explained_fraction = 0.7;  // share of a fragment's points that must lie on it
  double max_size_ratio = 0.5;          // a fragment has at most this share of the host's points

  template <class V>
  void Visit(V& v) {
    v("min_host_objectness", min_host_objectness);
    v("distance_m", distance_m);
    v("min_explained_fraction", min_explained_fraction);
    v("max_size_ratio", max_size_ratio);
  }
  void Validate() const {
    config::RequireInRange("report.fragments.min_host_objectness", min_host_objectness, 0.0, 1.0);
    config::RequirePositive("report.fragments.distance_m", distance_m);
    config::RequireInRange("report.fragments.min_explained_fraction", min_explained_fraction, 0.0, 1.0);
    config::RequireNonNegative("report.fragments.max_size_ratio", max_size_ratio);
  }
};

struct FragmentCandidate {
  std::vector<Eigen::Vector3f> points_world;   // the object's map points (may be empty for a host)
  std::size_t num_points = 0;                  // its size (for the size ratio); points_world.size() if 0
  double objectness = 0.0;
  // Its best full model's surface points in the model frame and the model's pose; empty = no model.
  std::vector<Eigen::Vector3f> model_points;
  geometry::Pose3 T_world_model = geometry::Pose3::Identity();
  bool may_be_absorbed = true;                 // false for objects already replaced by their model
};

// For every object, the index of the object it belongs to (itself when it stays apart). Hosts are
// taken largest first; an absorbed object hosts nothing. Deterministic.
std::vector<int> AbsorbExplainedFragments(const std::vector<FragmentCandidate>& objects,
                                          const FragmentAbsorptionOptions& options);

}  // namespace objscan::scanning
