#pragma once
// Per-pixel camera-frame vertices and normals of a depth frame, shared by fusion (SurfaceMap) and
// frame segmentation so each frame is filtered and differentiated once.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::mapping {

struct NormalEstimationOptions {
  // Depth is smoothed by a separable box filter of this radius that only averages neighbours on the
  // same surface (|dz| below the depth-jump threshold); 0 disables smoothing. Kinect depth is
  // quantised in disparity, so unsmoothed 1-pixel normals are useless beyond ~1 m.
  int smoothing_radius_px = 3;
  // The smoothing only averages neighbours within smoothing_base_m + smoothing_per_m * z^2 of the
  // pixel's depth (~3 sigma of the noise incl. disparity quantisation), so steps of a few
  // centimetres stay steps instead of becoming ramps the segmenter cannot see.
  double smoothing_base_m = 0.006;
  double smoothing_per_m = 0.005;
  // Normals come from central differences over +-this many pixels of the smoothed vertex map.
  int difference_step_px = 2;
  // Neighbours farther apart than k * z^2 (z in metres) are on different surfaces (same k as the
  // frame segmenter's depth-jump test).
  double depth_jump_per_m = 0.02;

  template <class V>
  void Visit(V& v) {
    v("smoothing_radius_px", smoothing_radius_px);
    v("smoothing_base_m", smoothing_base_m);
    v("smoothing_per_m", smoothing_per_m);
    v("difference_step_px", difference_step_px);
    v("depth_jump_per_m", depth_jump_per_m);
  }
  void Validate() const;
};

// Camera-frame maps, row-major like the depth image. Invalid pixels have valid[i] == 0.
// A pixel has a normal (valid == 1) only when its depth and its four difference neighbours are
// valid and continuous; normals point towards the camera.
struct VertexNormalMap {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> vertex_camera;  // smoothed vertex (zero where depth is invalid)
  std::vector<Eigen::Vector3f> normal_camera;  // unit normal (zero where valid == 0)
  std::vector<std::uint8_t> valid;             // 1 = vertex and normal usable
  std::vector<float> smoothed_depth_m;         // the guarded-box-filtered depth (0 = invalid)
  // Scratch buffers reused between frames.
  std::vector<float> scratch_depth_m;
  std::vector<float> scratch_rows;

  std::size_t Index(int u, int v) const { return static_cast<std::size_t>(v) * width + u; }
};

// Computes `out` for `frame` (reuses out's storage).
void ComputeVertexNormalMap(const platform::DepthFrame& frame, const NormalEstimationOptions& options,
                            VertexNormalMap* out);

}  // namespace objscan::mapping
