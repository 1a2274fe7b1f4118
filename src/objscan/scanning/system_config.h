#pragma once
// The whole effective configuration of objscan: one section per component. The defaults live in the
// options structs (in-class); config/default.yaml mirrors them exactly (a test keeps the two equal,
// scripts/update_default_config.sh regenerates the file).
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/io/scene_spec.h"
#include "objscan/mapping/frontiers.h"
#include "objscan/mapping/occupancy_map.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/navigation/navigator.h"
#include "objscan/planning/exploration.h"
#include "objscan/planning/next_best_object.h"
#include "objscan/planning/next_best_view.h"
#include "objscan/platform/robot_options.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/render/depth_camera.h"
#include "objscan/scanning/report/report_options.h"
#include "objscan/scanning/scanner_options.h"
#include "objscan/segmentation/incremental_segmenter.h"
#include "objscan/segmentation/post_segmenter.h"

namespace objscan::scanning {

// Evaluation settings (the paper's Results section); used only when ground truth is known.
struct EvaluationOptions {
  double coverage_sigma = 0.6;              // sigma of q(v)
  double coverage_theta_t_rad = M_PI / 2;   // theta_t of q(v); d_t = sensor.max_range_m
  double coverage_voxel_size_m = 0.05;      // surface voxels of the ground-truth objects (OctoMap's 5 cm)
  // V_S holds only the surface voxels next to empty space joined to the robot's start (false: every
  // voxel a triangle touches, also under objects, against walls and inside closed furniture).
  bool coverage_exposed_only = true;
  // ... and of those, only voxels whose exposed face a camera at the robot's camera heights
  // (robot.min_camera_height_m to max_camera_height_m) can face: no undersides below the lowest
  // camera, no tops above the highest (eval/exposure.h). false: faces at any height count.
  bool coverage_robot_camera_heights = true;
  // ... and of those, only voxels the depth camera could measure from some height in that band: a
  // line of sight within the sensor's dropout angle of the surface, free for at least
  // sensor.min_range_m (eval/observability.h). Drops faces in slits between an object and a wall or
  // its neighbour. false: keep them (coverage.ply still flags them `observable` 0).
  bool coverage_observable_only = true;
  // ... where the camera must be within robot.max_reach_m of a base position that fits on the free
  // floor (robot.base_radius_m, robot.height_m) joined to the start. false: anywhere in the room.
  bool coverage_robot_reach = true;
  // An incomplete object counts as a recognition at termination when its objectness reaches this
  // (complete objects always count).
  double recognized_min_objectness = 0.5;
  // Measuring the report rules: the run also reports and scores its objects under other report
  // options and writes report_variants.json (eval/report_variants.h): "ablation" or a YAML file of
  // named variants; "" = none.
  std::string report_variants;
  // Threads of the evaluation's ray casting (observability of V_S); 0 = hardware concurrency. The
  // metrics do not depend on it.
  int threads = 0;

  template <class V>
  void Visit(V& v) {
    v("coverage_sigma", coverage_sigma);
    v("coverage_theta_t_rad", coverage_theta_t_rad);
    v("coverage_voxel_size_m", coverage_voxel_size_m);
    v("coverage_exposed_only", coverage_exposed_only);
    v("coverage_robot_camera_heights", coverage_robot_camera_heights);
    v("coverage_observable_only", coverage_observable_only);
    v("coverage_robot_reach", coverage_robot_reach);
    v("recognized_min_objectness", recognized_min_objectness);
    v("report_variants", report_variants);
    v("threads", threads);
  }
  void Validate() const {
    config::RequirePositive("eval.coverage_sigma", coverage_sigma);
    config::RequirePositive("eval.coverage_theta_t_rad", coverage_theta_t_rad);
    config::RequirePositive("eval.coverage_voxel_size_m", coverage_voxel_size_m);
    config::RequireInRange("eval.recognized_min_objectness", recognized_min_objectness, 0.0, 1.0);
    config::Require(threads >= 0, "eval.threads", "must be >= 0 (0 = hardware concurrency)");
  }
};

struct SystemConfig {
  io::SceneLoadOptions scene;
  render::SensorOptions sensor;
  platform::RobotOptions robot;
  navigation::NavigatorOptions navigation;
  mapping::SurfaceMapOptions surface_map;
  mapping::OccupancyMapOptions occupancy;
  mapping::StructureOptions structure;
  mapping::FrontierOptions frontiers;
  segmentation::IncrementalSegmenterOptions presegmentation;
  recognition::RecognitionOptions recognition;
  segmentation::PostSegmenterOptions postsegmentation;
  planning::NextBestObjectOptions nbo;
  planning::NextBestViewOptions nbv;
  planning::ExplorationOptions exploration;
  ScannerOptions scanner;
  ReportOptions report;  // the rules applied to the objects after the loop (report/)
  EvaluationOptions eval;

  template <class V>
  void Visit(V& v) {
    v("scene", scene);
    v("sensor", sensor);
    v("robot", robot);
    v("navigation", navigation);
    v("surface_map", surface_map);
    v("occupancy", occupancy);
    v("structure", structure);
    v("frontiers", frontiers);
    v("presegmentation", presegmentation);
    v("recognition", recognition);
    v("postsegmentation", postsegmentation);
    v("nbo", nbo);
    v("nbv", nbv);
    v("exploration", exploration);
    v("scanner", scanner);
    v("report", report);
    v("eval", eval);
  }
  void Validate() const {
    scene.Validate();
    sensor.Validate();
    robot.Validate();
    navigation.Validate();
    surface_map.Validate();
    occupancy.Validate();
    structure.Validate();
    frontiers.Validate();
    presegmentation.Validate();
    recognition.Validate();
    postsegmentation.Validate();
    nbo.Validate();
    nbv.Validate();
    exploration.Validate();
    scanner.Validate();
    report.Validate();
    eval.Validate();
  }
};

// Defaults, then `config_file` (if not empty), then each `key=value` of `overrides` in order.
// Throws InputError/ConfigError naming the file or key.
SystemConfig LoadSystemConfig(const std::string& config_file, const std::vector<std::string>& overrides);

// YAML and JSON text of the effective configuration.
std::string ToYaml(const SystemConfig& config);
std::string ToJson(const SystemConfig& config, int indent = 2);

// The config/ folder: io::ConfigDir() ($OBJSCAN_CONFIG_DIR, else the source tree's when running from
// the build tree, else the installed share/objscan/config).
std::string ConfigDir();

}  // namespace objscan::scanning
