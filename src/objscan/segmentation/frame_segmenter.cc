#include "objscan/segmentation/frame_segmenter.h"

#include <cmath>
#include <string>

#include "objscan/common/error.h"

namespace objscan::segmentation {

void FrameSegmenterOptions::Validate() const {
  config::RequirePositive("depth_jump_per_m", depth_jump_per_m);
  config::RequireInRange("concavity_threshold", concavity_threshold, 0.0, 2.0);
  config::RequireNonNegative("concave_min_offset_m", concave_min_offset_m);
  config::RequirePositive("step_base_m", step_base_m);
  config::RequireNonNegative("step_quadratic_per_m", step_quadratic_per_m);
  config::RequireInRange("neighbor_step_px", neighbor_step_px, 1, 16);
  config::RequireInRange("min_segment_px", min_segment_px, 1, 1 << 24);
}

void SegmentFrame(const platform::DepthFrame& frame, const mapping::VertexNormalMap& vnm,
                  const FrameSegmenterOptions& options, const std::vector<std::uint8_t>* pixel_class,
                  FrameSegmentation* out) {
  const int w = frame.width(), h = frame.height();
  const std::size_t n = static_cast<std::size_t>(w) * h;
  out->width = w;
  out->height = h;
  out->segment.assign(n, -1);
  out->segment_size_px.clear();
  const float k = static_cast<float>(options.depth_jump_per_m);
  const float tau = static_cast<float>(options.concavity_threshold);
  const float min_offset = static_cast<float>(options.concave_min_offset_m);
  const float step_base = static_cast<float>(options.step_base_m);
  const float step_quad = static_cast<float>(options.step_quadratic_per_m);
  const int r = options.neighbor_step_px;
  const float* depth = frame.depth_m.data();
  if (pixel_class != nullptr && pixel_class->size() != n) {
    throw InputError("SegmentFrame: pixel_class has " + std::to_string(pixel_class->size()) + " values for " +
                     std::to_string(n) + " pixels");
  }
  const std::uint8_t* cls = pixel_class != nullptr ? pixel_class->data() : nullptr;

  // Edge map: 1 where a pixel may not join a segment.
  std::vector<std::uint8_t> edge(n, 1);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      if (!vnm.valid[i]) continue;
      const float z = depth[i];
      const float tol = k * z * z;
      bool is_edge = false;
      // Depth jumps (and holes) to the 4 direct neighbours.
      const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
      for (int d = 0; d < 4 && !is_edge; ++d) {
        const int uu = u + du[d], vv = v + dv[d];
        if (uu < 0 || vv < 0 || uu >= w || vv >= h) continue;
        const float zj = depth[static_cast<std::size_t>(vv) * w + uu];
        if (zj <= 0.f || std::fabs(zj - z) > tol) is_edge = true;
      }
      // Concave folds and steps to the 4 neighbours r pixels away.
      const Eigen::Vector3f& vi = vnm.vertex_camera[i];
      const Eigen::Vector3f& ni = vnm.normal_camera[i];
      const float step = step_base + step_quad * z * z;
      for (int d = 0; d < 4 && !is_edge; ++d) {
        const int uu = u + r * du[d], vv = v + r * dv[d];
        if (uu < 0 || vv < 0 || uu >= w || vv >= h) continue;
        const std::size_t j = static_cast<std::size_t>(vv) * w + uu;
        if (!vnm.valid[j]) continue;
        const float offset = (vnm.vertex_camera[j] - vi).dot(ni);
        if (offset > step || (offset > min_offset && 1.f - ni.dot(vnm.normal_camera[j]) > tau)) is_edge = true;
      }
      edge[i] = is_edge ? 1 : 0;
    }
  }

  // 4-connected components of non-edge pixels (flood fill with an explicit stack).
  std::vector<std::int32_t> stack;
  std::vector<std::int32_t> members;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (edge[seed] || out->segment[seed] != -1) continue;
    const std::int32_t id = static_cast<std::int32_t>(out->segment_size_px.size());
    members.clear();
    stack.assign(1, static_cast<std::int32_t>(seed));
    out->segment[seed] = id;
    while (!stack.empty()) {
      const std::int32_t p = stack.back();
      stack.pop_back();
      members.push_back(p);
      const int u = p % w, v = p / w;
      const std::int32_t nb[4] = {u + 1 < w ? p + 1 : -1, u > 0 ? p - 1 : -1, v + 1 < h ? p + w : -1,
                                  v > 0 ? p - w : -1};
      for (std::int32_t q : nb) {
        if (q >= 0 && !edge[q] && out->segment[q] == -1 && (cls == nullptr || cls[q] == cls[p])) {
          out->segment[q] = id;
          stack.push_back(q);
        }
      }
    }
    if (static_cast<int>(members.size()) < options.min_segment_px) {
      for (std::int32_t p : members) out->segment[p] = -2;  // dropped; reset below
      continue;
    }
    out->segment_size_px.push_back(static_cast<std::int32_t>(members.size()));
  }
  for (std::int32_t& s : out->segment) {
    if (s == -2) s = -1;
  }
}

}  // namespace objscan::segmentation
