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

// Compute time per stage of the loop (navigate_sim: the simulated robot's driving time).
struct StageTimes {
  double sense = 0, fuse = 0, segment = 0, recognize = 0, nbo = 0, nbv = 0, navigate_sim = 0;

  StageTimes& operator+=(const StageTimes& o) {
    sense += o.sense, fuse += o.fuse, segment += o.segment, recognize += o.recognize;
    nbo += o.nbo, nbv += o.nbv, navigate_sim += o.navigate_sim;
    return *this;
  }
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
  StageTimes timing_ms;     // per stage, milliseconds
  double wall_ms = 0.0;     // the whole step
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

// One change a report rule (scanning/report/) made to an object, in the order they were made.
struct LabelChange {
  std::string rule;    // the rule's name in report.rules
  std::string action;  // "relabel" (label only), "adopt" (a model's label, model and pose), "take" (the
                       // label goes), "reopen" (a completed object reported unfinished), "join" (an
                       // object became part of this one)
  std::optional<world::Category> from, to;  // the label before and after (nullopt: none)
  std::string model;   // adopt: the model taken; reopen: the model that had completed it
  int joined_id = -1;  // join: the id of the object that joined
};

struct ObjectRecord {
  int id = -1;                                  // smallest pre-segment label of the object
  std::optional<world::Category> category;      // nullopt: unrecognized
  // Share of its points in wall openings (when the wall_openings rule ran and walls are known).
  std::optional<double> wall_opening_share;
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
  std::vector<LabelChange> label_changes;       // what the report rules changed, in order
  int gt_instance = -1;                         // majority ground-truth instance (set by eval only)
  double gt_instance_share = 0.0;               // share of that instance's reconstructed surface held here
};

struct TrajectorySample {
  double time_s = 0.0;  // simulated time
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;  // base
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  bool view = false;   // a frame was taken here
  int step = 0;
};

// Seconds per stage over the run, and the whole run's compute time.
struct TimingTotals : StageTimes {
  double total = 0;
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

// What the robot could not get to when the run ended, as its own map shows it (no ground truth): the
// floor frontiers no path reaches (a closed door, a gap narrower than the robot, cells in the
// inflated margin of the navigation map) and the objects left unfinished for want of a reachable
// view. A run that leaves these ends `done`; `stuck` means the robot could not move at all.
struct UnreachableFrontierRecord {
  double x_m = 0.0, y_m = 0.0;  // centroid
  int cells = 0;
  double area_m2 = 0.0;
};
struct UnreachableRecord {
  std::vector<UnreachableFrontierRecord> frontiers;
  double frontier_area_m2 = 0.0;
  std::vector<int> objects;  // ids of reported objects left unfinished: no view of them was reachable
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
  // The area explored (navigation grid cells seen free or occupied) and the step budget it gave
  // (ScannerOptions::steps_per_explored_m2), as of the last step.
  double explored_area_m2 = 0.0;
  int step_budget = 0;
  UnreachableRecord unreachable;
  double NbvPerObject() const { return nbo_count > 0 ? static_cast<double>(nbv_views) / nbo_count : 0.0; }
};

}  // namespace objscan::scanning
