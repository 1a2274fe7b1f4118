#pragma once
// Scores a scanning run against the simulated world's ground truth with the paper's metrics:
// recognition recall/precision (all objects and those on the floor), Rand Index of the object-level
// segmentation and of the pre-segmentation, pre-segment purity, and object coverage rate and quality.
// Coverage is accumulated from the frames the robot takes (their ground-truth channels), so the
// evaluator observes the run through the scanner's frame observer.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "objscan/eval/metrics.h"
#include "objscan/scanning/run_record.h"
#include "objscan/scanning/scanner.h"
#include "objscan/platform/depth_frame.h"
#include "objscan/world/scene.h"

namespace objscan::eval {

// One ground-truth object of the scene after a run: what the scanner saw of it and whether it was
// recognised (the per-object breakdown of recall and coverage).
struct InstanceOutcome {
  int instance = world::kNoInstance;
  world::Category category = world::Category::kOther;
  bool in_database = false;  // its category is one the database knows (it counts for recall)
  int surface_voxels = 0;    // its voxels in V_S
  int visible_voxels = 0;    // of those, seen within the valid range
  bool matched = false;      // a true positive matched it
};

// One voxel of V_S after the run: where it is, whose it is, whether the robot saw it within range
// (delta_vis) and whether its instance was recognised (delta_detect). Written to coverage.ply.
struct CoverageVoxelOutcome {
  Eigen::Vector3f center_world = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal_world = Eigen::Vector3f::UnitZ();
  int instance = world::kNoInstance;
  world::Category category = world::Category::kOther;
  bool visible = false;
  bool detected = false;  // on a matched instance (delta_detect of coverage_rate)
  bool reported = false;  // on the majority instance of a reported object (coverage_detected_rate)
  bool observable = true;  // a camera could measure it (eval/observability.h)
};

// Recognition in one room of the scene (eval/rooms.h): the ground-truth objects whose centre lies in
// it, and the outputs on them (or, on background, whose model stands in it).
struct RoomMetrics {
  int room = 0;
  double area_m2 = 0.0;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  RecognitionCounts counts;
};

// A ground-truth object, named for people reading run.json.
struct ObjectRef {
  int instance = world::kNoInstance;
  std::string name;
  world::Category category = world::Category::kOther;
};

// A room the robot could not drive into from where it started (a closed door; reachability.h), and
// the ground-truth objects whose centre lies in it.
struct UnreachableRoom {
  int room = 0;
  double area_m2 = 0.0;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  std::vector<ObjectRef> objects;
};

struct RunMetrics {
  double recall = 0.0, precision = 0.0;
  double recall_floor = 0.0, precision_floor = 0.0;
  int ground_truth_objects = 0, ground_truth_floor_objects = 0, output_objects = 0, true_positives = 0;
  double rand_index = 0.0, rand_index_preseg = 0.0, preseg_purity = 0.0;
  double coverage_rate = 0.0, coverage_quality = 0.0;
  // delta_vis alone: the share of V_S seen within range, whether or not its object was recognised.
  double coverage_visible_rate = 0.0;
  // The rate with delta_detect(v) = 1 on every ground-truth object that is the majority instance of
  // a reported object, whatever its label: how much of the objects the robot found it scanned,
  // apart from whether recognition named them right (coverage_rate counts matched objects only).
  double coverage_detected_rate = 0.0;
  std::vector<InstanceOutcome> instances;
  std::vector<CoverageVoxelOutcome> coverage_voxels;  // every voxel of V_S
  double travel_m = 0.0;
  int views = 0, nbo_count = 0;
  int coverage_views = 0;  // views completing reported objects' scans (scanning/coverage_views.h)
  double nbv_per_object = 0.0;
  // Per object category: ground truth count, outputs and true positives (Table 2).
  std::array<RecognitionCounts, world::kNumCategories> per_category{};
  // Coverage after each view (rate, quality), for Fig. 11-style curves.
  std::vector<std::pair<double, double>> coverage_per_view;
  // Rand Index of the segmentation after each analysis: (views seen, rand index), for Fig. 10b.
  std::vector<std::pair<int, double>> rand_index_per_view;
  // Per room, when the scene has two or more rooms holding ground-truth objects (a house); objects
  // in no room (outside the partitioned floor) count in no room.
  std::vector<RoomMetrics> rooms;
  // Rooms the robot could not reach, and recognition over the ground truth and outputs of the rooms
  // it could (objects in no room count as reachable): the totals when every room is reachable.
  std::vector<UnreachableRoom> unreachable_rooms;
  RecognitionCounts reachable;
  // Objects (not structure) of the reachable rooms the robot never saw: no element of its map is
  // theirs and none of their surface was seen within range. A room it could have entered but did
  // not shows here, not in unreachable_rooms.
  std::vector<ObjectRef> never_seen;
};

class RunEvaluator {
 public:
  // `database_categories`: categories the model database knows (the ground-truth set is every
  // non-structural object of those categories).
  RunEvaluator(const world::Scene& scene, const scanning::SystemConfig& config,
               std::vector<world::Category> database_categories);
  ~RunEvaluator();

  // Feeds one frame and where the map fused its pixels (call from the scanner's frame observer).
  void ObserveFrame(const platform::DepthFrame& frame, const mapping::FrameAssociation& association);
  // Scores the segmentation of one analysis (call from the scanner's analysis observer).
  void ObserveAnalysis(const scanning::Scanner& scanner);

  // Each reported object's ground-truth instance (ObjectRecord::gt_instance): the majority instance
  // of its map elements outside the structure (-1 for none). Call before Evaluate.
  void AssignGroundTruthInstances(const scanning::Scanner& scanner, scanning::RunRecord* record) const;

  // Scores the finished run (objects' gt_instance as AssignGroundTruthInstances set them).
  RunMetrics Evaluate(const scanning::Scanner& scanner, const scanning::RunRecord& record) const;

  // Ground-truth object surface voxels (|V_S| of the coverage metrics).
  int num_surface_voxels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace objscan::eval
