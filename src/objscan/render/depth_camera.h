#pragma once
// Simulated depth camera: ray casts a world::Scene (Embree, hidden in the .cc) and applies a
// Kinect-style noise model (depth_noise.h). Rendering is deterministic given the Rng and independent of
// threads. With noise off the sensor is ideal: exact depth, no quantisation, no dropouts. Pixels with
// depth 0 also have instance 0 and a zero normal; ground-truth normals face the camera.
#include <memory>

#include "objscan/common/config.h"
#include "objscan/common/rng.h"
#include "objscan/platform/depth_frame.h"
#include "objscan/render/raycaster.h"
#include "objscan/world/scene.h"

namespace objscan::render {

struct SensorOptions {
  int width_px = 640;
  int height_px = 480;
  double fx_px = 525.0;
  double fy_px = 525.0;
  double cx_px = 319.5;
  double cy_px = 239.5;
  double min_range_m = 0.5;
  double max_range_m = 4.0;
  bool noise = true;                          // Kinect-style noise on (default) or off
  double noise_sigma_base_m = 0.0012;         // sigma_z = base + quad * (z - offset)^2 (Nguyen 2012)
  double noise_sigma_quadratic_per_m = 0.0019;
  double noise_sigma_offset_m = 0.4;
  double baseline_m = 0.075;                  // disparity quantisation (projector-camera baseline)
  double disparity_step_px = 0.125;           // 1/8 pixel
  double grazing_dropout_deg = 75.0;          // pixels seen beyond this incidence angle drop out
  double edge_dropout_jump_m = 0.05;          // depth discontinuity (relative: per metre of depth)
  int threads = 0;                            // 0 = hardware concurrency; results do not depend on it

  platform::CameraIntrinsics Intrinsics() const;
  template <class V>
  void Visit(V& v) {
    v("width_px", width_px);
    v("height_px", height_px);
    v("fx_px", fx_px);
    v("fy_px", fy_px);
    v("cx_px", cx_px);
    v("cy_px", cy_px);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("noise", noise);
    v("noise_sigma_base_m", noise_sigma_base_m);
    v("noise_sigma_quadratic_per_m", noise_sigma_quadratic_per_m);
    v("noise_sigma_offset_m", noise_sigma_offset_m);
    v("baseline_m", baseline_m);
    v("disparity_step_px", disparity_step_px);
    v("grazing_dropout_deg", grazing_dropout_deg);
    v("edge_dropout_jump_m", edge_dropout_jump_m);
    v("threads", threads);
  }
  void Validate() const;
};

class DepthCamera {
 public:
  // Commits the scene geometry once. Throws InputError when the scene has no triangles.
  DepthCamera(const world::Scene& scene, const SensorOptions& options);
  ~DepthCamera();
  DepthCamera(const DepthCamera&) = delete;
  DepthCamera& operator=(const DepthCamera&) = delete;

  // Renders one frame from T_world_camera (optical frame: X right, Y down, Z forward).
  // Noise draws from `rng` (may be nullptr when options.noise is false).
  platform::DepthFrame Render(const geometry::Pose3& T_world_camera, Rng* rng) const;

  const SensorOptions& options() const { return options_; }
  // The ray caster holding the committed scene (line-of-sight and pose checks reuse it).
  const Raycaster& raycaster() const;

 private:
  SensorOptions options_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace objscan::render
