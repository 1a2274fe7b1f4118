#pragma once
// What one scanning run did, as plain data: steps with their actions, poses, travel and per-stage
// timing, the objects found, and the trajectory. Serialised to run.json / trajectory.csv by
// run_writer; metrics are added by eval when ground truth is known.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "objscan/geometry/pose.h"
#include "objscan/world/category.h"

namespace objscan::scanning {

enum class Termination { kRunning, kDone, kMaxSteps, kStuck };
const char* TerminationName(Termination t);

struct NbvCandidateRecord {
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  std::string validity;  // planning::ViewValidity name
  double gain = 0.0;
};

struct StepRecord {
  int index = 0;
  std::string action;       // "nbo" (new object of interest), "nbv" (same one), "frontier" (exploration)
  bool look_around = false; // views taken turning in place (start and frontier arrivals)
  bool coverage_view = false;  // an "nbv" view completing the scan of a reported object (coverage_views.h)
  int ooi = -1;             // object of interest id, -1 when exploring
  int views = 0;            // frames taken in this step
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();  // last camera pose of the step
  double travel_m = 0.0;    // base travel of this step
  std::map<std::string, double> timing_ms;  // sense, fuse, segment, recognize, nbo, nbv, navigate_sim(s*1000)
  std::vector<NbvCandidateRecord> nbv_candidates;
  int num_components = 0;
  int num_objects = 0;
  // Recognition queries of this step's post-segmentation (cache misses): components, adjacent pairs,
  // groups (objects and split candidates).
  int component_queries = 0, pair_queries = 0, group_queries = 0;
  // Why objects of interest were given up or goals skipped in this step (for people reading run.json).
  std::vector<std::string> notes;
};

// Another category recognition considered for an object: its best full model of that category.
struct ObjectAlternative {
  world::Category category = world::Category::kOther;
  std::string model;
  double objectness = 0.0;
};

struct ObjectRecord {
  int id = -1;                                  // smallest pre-segment label of the object
  std::optional<world::Category> category;      // nullopt: unrecognized
  // Whether the best full model's category replaced the graph-cut label, and that label
  // (scanner.model_label_min_objectness; nullopt: "none").
  bool model_labelled = false;
  std::optional<world::Category> graph_cut_category;
  // The label it had before the size check found no model of that category its size (nullopt: kept).
  std::optional<world::Category> size_rejected_category;
  // The label it had before it was found too small to report (scanner.min_reported_elements).
  std::optional<world::Category> small_rejected_category;
  // Share of its points in wall openings (when walls are known), and the label recognition gave it
  // when that share made it a window or took its window label, or when it was too deep for the door
  // it was labelled (scanner.wall_openings).
  std::optional<double> wall_opening_share;
  std::optional<world::Category> wall_opening_replaced_category;
  bool wall_opening_relabelled = false;
  // The model that completed it, when it is reported unfinished all the same: its seen surface
  // outgrew that model (scanner.completion_check), or the model is a door and what was seen of it is
  // too deep for one (scanner.wall_openings.door_max_depth_m); "" otherwise.
  std::string completion_rejected_model;
  std::string model;                            // best database model name ("" when none)
  int model_index = -1;                         // into the database's models
  double objectness = 0.0;
  bool complete = false;                        // replaced by its model
  bool given_up = false;                        // ran out of views or of valid views
  geometry::Pose3 T_world_model = geometry::Pose3::Identity();
  int points = 0;                               // map elements of the object
  // Size of what was seen of it (bounding-box height, smallest footprint rectangle's diagonal).
  double height_m = 0.0;
  double footprint_diagonal_m = 0.0;
  // The full models of M(r) at the end of the run, best first (empty for completed objects).
  std::vector<ObjectAlternative> alternatives;
  std::vector<std::int32_t> labels;             // its pre-segment labels
  int gt_instance = -1;                         // majority ground-truth instance (evaluation only)
};

struct TrajectorySample {
  double time_s = 0.0;  // simulated time
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;  // base
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  bool view = false;   // a frame was taken here
  int step = 0;
};

struct TimingTotals {
  double total = 0, sense = 0, fuse = 0, segment = 0, recognize = 0, nbo = 0, nbv = 0, navigate_sim = 0;
};

// What the robot took for the room's structure at the end of the run (mapping/planes.h).
struct WallRecord {
  double normal_x = 1.0, normal_y = 0.0;  // horizontal unit normal, into the room
  double offset_m = 0.0;                  // the plane n . x = offset_m
  double span_min_m = 0.0, span_max_m = 0.0;  // extent along (-n.y, n.x)
  double z_min_m = 0.0, z_max_m = 0.0;
  double area_m2 = 0.0;
};
struct StructureRecord {
  std::optional<double> floor_height_m;  // nullopt: no floor found
  std::vector<WallRecord> walls;
};

struct RunRecord {
  std::string scene;
  std::uint64_t seed = 0;
  Termination terminated = Termination::kRunning;
  std::vector<StepRecord> steps;
  std::vector<ObjectRecord> objects;
  std::vector<TrajectorySample> trajectory;
  StructureRecord structure;
  TimingTotals timing_s;
  double travel_m = 0.0;
  int views = 0;
  int nbo_count = 0;
  int nbv_views = 0;
  int coverage_views = 0;  // views completing reported objects' scans (not in nbv_views or nbo_count)
  double NbvPerObject() const { return nbo_count > 0 ? static_cast<double>(nbv_views) / nbo_count : 0.0; }
};

}  // namespace objscan::scanning
