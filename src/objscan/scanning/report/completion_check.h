#pragma once
// Beyond the paper: a completed object must hold what was seen of it. The robot completes an object
// when a model scores O > 0.96 (§5.1) on what it has seen then, usually a front: a wardrobe's doors
// fit a door model that well. Its components keep growing as the robot scans on (their labels are
// done, the surface is not), and by the end of the run a wardrobe's sides stand 0.6 m outside the
// door model. At the end of a run, a completed object with too much of its seen surface outside its
// model's box is reported as unfinished, recognized again as a whole.
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/geometry/pose.h"

namespace objscan::scanning {

struct CompletionCheckOptions {
  // A completed object whose seen points lie outside its model's bounding box (grown by margin_m)
  // in a share above this is reported unfinished (report rule reopen_outgrown).
  double max_outside_share = 0.3;
  double margin_m = 0.05;

  template <class V>
  void Visit(V& v) {
    v("max_outside_share", max_outside_share);
    v("margin_m", margin_m);
  }
  void Validate() const {
    config::RequireInRange("report.completion_check.max_outside_share", max_outside_share, 0.0, 1.0);
    config::RequireNonNegative("report.completion_check.margin_m", margin_m);
  }
};

// The share of `points_world` outside the axis-aligned box of `model_points` (model frame), grown by
// margin_m on every side, with the model placed at T_world_model. 0 for no points; 1 for a model
// without points.
double ShareOutsideModelBox(const std::vector<Eigen::Vector3f>& points_world,
                            const std::vector<Eigen::Vector3f>& model_points, const geometry::Pose3& T_world_model,
                            double margin_m);

}  // namespace objscan::scanning
