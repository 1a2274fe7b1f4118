#pragma once
// Beyond the paper: views that complete the scan of the objects the robot reported. The paper's loop
// leaves an object once a model explains it (O > 0.96) or its view budget is spent, usually with its
// front and top seen; its sides, the undersides of tables and chairs and the far ends of long objects
// stay unseen, and the object-wise coverage rate (§6) counts them. When nothing else is left (no
// unfinished object, no reachable frontier), the robot visits each object with a model once more and
// takes the view that shows most of that model's surface not yet observed (NBV candidates around the
// object, planning::ViewGainMeasure::kUnobservedSurface), when it shows enough of it.
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"

namespace objscan::scanning {

struct CoverageViewOptions {
  bool enabled = true;            // false: the paper's loop (done when no object and no frontier is left)
  // Coverage views planned per object, at most (a plan whose best view shows too little counts).
  int max_views_per_object = 2;
  // A view must show at least this many unseen voxels of the model's blurred surface (NBV grid voxels,
  // 2.5 cm by default; the blurred shell is 3-4 voxels thick, so 400 is roughly 0.06 m2 of surface).
  int min_unseen_voxels = 400;
  // Only objects whose model explains them this well are visited (the model predicts where the
  // unseen surface is).
  double min_objectness = 0.85;
  // Model surface this close above the floor is left out: nothing sees under an object standing on it.
  double floor_clearance_m = 0.03;
  // Candidate elevations, as nbv.candidates.ring_elevations_deg; a ring below the object's centre
  // shows the undersides of tables and chairs.
  std::vector<double> ring_elevations_deg = {-20.0, 10.0, 40.0};
  // Candidates around the object, spread over the rings in turn (as nbv.candidates.num_candidates).
  int num_candidates = 16;
  // Beyond framing the whole object: as many candidates again around the part of its model not yet
  // seen (UnseenModelPoints, away from the walls), which come closer and look more steeply into it
  // (the inside of a bathtub, a sink's basin, the far end of a long sofa). false = only the former.
  bool aim_at_unseen = false;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("max_views_per_object", max_views_per_object);
    v("min_unseen_voxels", min_unseen_voxels);
    v("min_objectness", min_objectness);
    v("floor_clearance_m", floor_clearance_m);
    v("ring_elevations_deg", ring_elevations_deg);
    v("num_candidates", num_candidates);
    v("aim_at_unseen", aim_at_unseen);
  }
  void Validate() const;
};

// The model points worth scanning: those at least clearance_m above the floor (all when has_floor is
// false, measured from z = 0 then).
std::vector<Eigen::Vector3f> ModelSurfaceAboveFloor(const std::vector<Eigen::Vector3f>& model_points_world,
                                                    bool has_floor, double floor_height_m, double clearance_m);

// The model points with no seen point near them: none in the same or a neighbouring cell of a grid of
// cell size seen_radius_m (so every seen point within seen_radius_m counts, and none beyond
// 2 sqrt(3) seen_radius_m). Order kept.
std::vector<Eigen::Vector3f> UnseenModelPoints(const std::vector<Eigen::Vector3f>& model_points_world,
                                               const std::vector<Eigen::Vector3f>& seen_points_world,
                                               double seen_radius_m);

}  // namespace objscan::scanning
