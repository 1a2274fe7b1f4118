#pragma once
// Step 1 of the incremental segmentation (Tateno et al. 2015): one depth frame cut into segments
// along depth jumps and concave folds. Convex folds (box edges seen from outside) do not cut, so
// segments are near-convex surface patches such as a chair's seat, back or legs.
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/mapping/vertex_normal_map.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::segmentation {

struct FrameSegmenterOptions {
  // Neighbouring pixels are on different surfaces when |dz| > k * z^2 (z in metres).
  double depth_jump_per_m = 0.02;
  // Concave fold between pixel i and a neighbour j: (v_j - v_i) . n_i > concave_min_offset_m and
  // 1 - n_i . n_j > concavity_threshold (0.06 ~ 20 degrees between the normals).
  double concavity_threshold = 0.06;
  double concave_min_offset_m = 0.0;
  // Step: a neighbour standing out of pixel i's tangent plane towards the camera side,
  // (v_j - v_i) . n_i > step_base_m + step_quadratic_per_m * z^2, is on another surface whatever
  // the normals say (a drawer front 5 cm proud of its neighbour, seen from 3 m, is only a few
  // pixels of side face: too few for the normals to turn). Convex edges never trigger it.
  double step_base_m = 0.01;
  double step_quadratic_per_m = 0.003;
  int neighbor_step_px = 2;   // the concavity test compares pixels this far apart
  int min_segment_px = 150;   // smaller segments are dropped (their pixels stay unlabelled)

  template <class V>
  void Visit(V& v) {
    v("depth_jump_per_m", depth_jump_per_m);
    v("concavity_threshold", concavity_threshold);
    v("concave_min_offset_m", concave_min_offset_m);
    v("step_base_m", step_base_m);
    v("step_quadratic_per_m", step_quadratic_per_m);
    v("neighbor_step_px", neighbor_step_px);
    v("min_segment_px", min_segment_px);
  }
  void Validate() const;
};

struct FrameSegmentation {
  int width = 0;
  int height = 0;
  std::vector<std::int32_t> segment;  // per pixel: segment index in [0, num_segments) or -1
  std::vector<std::int32_t> segment_size_px;
  int num_segments() const { return static_cast<int>(segment_size_px.size()); }
};

// Segments `frame` given its vertex/normal map (from mapping::ComputeVertexNormalMap). `out`'s
// storage is reused. Segment indices follow the first pixel of each segment in row-major order.
// When `pixel_class` is given (one value per pixel, e.g. 0 = object, 1 = floor, 2 = wall),
// neighbours of different classes are never in one segment.
void SegmentFrame(const platform::DepthFrame& frame, const mapping::VertexNormalMap& vertex_normals,
                  const FrameSegmenterOptions& options, const std::vector<std::uint8_t>* pixel_class,
                  FrameSegmentation* out);
inline void SegmentFrame(const platform::DepthFrame& frame, const mapping::VertexNormalMap& vertex_normals,
                         const FrameSegmenterOptions& options, FrameSegmentation* out) {
  SegmentFrame(frame, vertex_normals, options, nullptr, out);
}

}  // namespace objscan::segmentation
