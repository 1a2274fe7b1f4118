#pragma once
// `objscan view OUT/`: one self-contained HTML page replaying a finished run folder (run.json,
// scene.ply, models.ply, trajectory.csv): the reconstructed points coloured by category, the placed
// models, the robot's path, every view with its frustum, each step's NBV candidates coloured by
// information gain, and a slider over the steps. three.js (Debian's libjs-three) and the run's data
// are inlined, so the page opens from disk without a network.
#include <string>

#include "objscan/common/error.h"

namespace objscan::eval {

struct RunViewOptions {
  // three.js r111+ as a classic script defining THREE, and its OrbitControls (libjs-three's paths).
  std::string three_js_path = "/usr/share/javascript/three/three.min.js";
  std::string orbit_controls_path = "/usr/share/javascript/three/examples/js/controls/OrbitControls.js";
  // Points of scene.ply put in the page (every k-th beyond it keeps the page small enough to open).
  int max_points = 300000;
  // Triangles of models.ply put in the page (models beyond it are left out, the largest first kept).
  int max_model_triangles = 400000;
  double frustum_depth_m = 0.35;  // drawn length of a view's frustum

  template <class V>
  void Visit(V& v) {
    v("three_js_path", three_js_path);
    v("orbit_controls_path", orbit_controls_path);
    v("max_points", max_points);
    v("max_model_triangles", max_model_triangles);
    v("frustum_depth_m", frustum_depth_m);
  }
  void Validate() const {
    if (max_points < 1) throw ConfigError("max_points: must be >= 1");
    if (max_model_triangles < 0) throw ConfigError("max_model_triangles: must be >= 0");
    if (!(frustum_depth_m > 0.0 && frustum_depth_m < 10.0)) throw ConfigError("frustum_depth_m: must be in (0, 10)");
  }
};

// What the page shows, for callers that report it.
struct RunViewSummary {
  int steps = 0;
  int views = 0;
  int points = 0;        // points put in the page
  int scene_points = 0;  // points of scene.ply (ceiling included)
  int models = 0;
  int candidates = 0;    // NBV candidates over all steps
};

// The page for the run folder `run_dir`. A point appears at the first view whose frustum, within the
// sensor's range, holds it and that it is not hidden from (a depth image at a quarter of the sensor's
// resolution made of the points themselves), a model at the last step its object was the object of
// interest. Throws InputError naming the file on a missing or malformed input.
std::string RunViewHtml(const std::string& run_dir, const RunViewOptions& options, RunViewSummary* summary = nullptr);

}  // namespace objscan::eval
