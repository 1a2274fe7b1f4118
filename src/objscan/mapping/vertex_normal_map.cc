#include "objscan/mapping/vertex_normal_map.h"

#include <cmath>

namespace objscan::mapping {

void NormalEstimationOptions::Validate() const {
  config::RequireInRange("smoothing_radius_px", smoothing_radius_px, 0, 15);
  config::RequireInRange("difference_step_px", difference_step_px, 1, 15);
  config::RequirePositive("depth_jump_per_m", depth_jump_per_m);
}

namespace {

// One pass of the guarded box filter along a line of `n` samples spaced `stride` apart.
void GuardedBoxPass(const float* in, float* out, int n, int stride, int radius, float jump_per_m) {
  for (int i = 0; i < n; ++i) {
    const float z = in[i * stride];
    if (z <= 0.f) {
      out[i * stride] = 0.f;
      continue;
    }
    const float tol = jump_per_m * z * z;
    float sum = 0.f;
    int count = 0;
    const int lo = i - radius < 0 ? 0 : i - radius;
    const int hi = i + radius >= n ? n - 1 : i + radius;
    for (int j = lo; j <= hi; ++j) {
      const float zj = in[j * stride];
      if (zj > 0.f && std::fabs(zj - z) < tol) {
        sum += zj;
        ++count;
      }
    }
    out[i * stride] = sum / static_cast<float>(count);
  }
}

}  // namespace

void ComputeVertexNormalMap(const sim::DepthFrame& frame, const NormalEstimationOptions& options,
                            VertexNormalMap* out) {
  const int w = frame.width();
  const int h = frame.height();
  const std::size_t n = static_cast<std::size_t>(w) * h;
  out->width = w;
  out->height = h;
  out->vertex_camera.resize(n);
  out->normal_camera.resize(n);
  out->valid.assign(n, 0);
  const float jump = static_cast<float>(options.depth_jump_per_m);

  // Smoothed depth (horizontal then vertical pass).
  std::vector<float> tmp(n), z_s(n);
  const float* depth = frame.depth_m.data();
  if (options.smoothing_radius_px > 0) {
    for (int v = 0; v < h; ++v) {
      GuardedBoxPass(depth + static_cast<std::size_t>(v) * w, tmp.data() + static_cast<std::size_t>(v) * w, w, 1,
                     options.smoothing_radius_px, jump);
    }
    for (int u = 0; u < w; ++u) {
      GuardedBoxPass(tmp.data() + u, z_s.data() + u, h, w, options.smoothing_radius_px, jump);
    }
  } else {
    z_s.assign(depth, depth + n);
  }

  const sim::CameraIntrinsics& in = frame.intrinsics;
  std::vector<float> ray_x(w), ray_y(h);
  for (int u = 0; u < w; ++u) ray_x[u] = static_cast<float>((u - in.cx_px) / in.fx_px);
  for (int v = 0; v < h; ++v) ray_y[v] = static_cast<float>((v - in.cy_px) / in.fy_px);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const float z = z_s[i];
      out->vertex_camera[i] = Eigen::Vector3f(ray_x[u] * z, ray_y[v] * z, z);
    }
  }

  const int r = options.difference_step_px;
  const float rf = static_cast<float>(r);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      out->normal_camera[i].setZero();
      const float z = z_s[i];
      if (z <= 0.f || depth[i] <= 0.f) continue;
      if (u < r || u + r >= w || v < r || v + r >= h) continue;
      const float tol = jump * z * z * rf;
      const std::size_t il = i - r, ir = i + r, iu = i - static_cast<std::size_t>(r) * w,
                        id = i + static_cast<std::size_t>(r) * w;
      const float zl = z_s[il], zr = z_s[ir], zu = z_s[iu], zd = z_s[id];
      if (zl <= 0.f || zr <= 0.f || zu <= 0.f || zd <= 0.f) continue;
      if (std::fabs(zl - z) > tol || std::fabs(zr - z) > tol || std::fabs(zu - z) > tol ||
          std::fabs(zd - z) > tol) {
        continue;
      }
      const Eigen::Vector3f dx = out->vertex_camera[ir] - out->vertex_camera[il];
      const Eigen::Vector3f dy = out->vertex_camera[id] - out->vertex_camera[iu];
      Eigen::Vector3f nrm = dy.cross(dx);
      const float len = nrm.norm();
      if (!(len > 0.f)) continue;
      nrm /= len;
      if (nrm.dot(out->vertex_camera[i]) > 0.f) nrm = -nrm;
      out->normal_camera[i] = nrm;
      out->valid[i] = 1;
    }
  }
}

}  // namespace objscan::mapping
