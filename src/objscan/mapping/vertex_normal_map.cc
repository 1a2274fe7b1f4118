#include "objscan/mapping/vertex_normal_map.h"

#include <cmath>

namespace objscan::mapping {

void NormalEstimationOptions::Validate() const {
  config::RequireInRange("smoothing_radius_px", smoothing_radius_px, 0, 15);
  config::RequireNonNegative("smoothing_base_m", smoothing_base_m);
  config::RequireNonNegative("smoothing_per_m", smoothing_per_m);
  config::RequireInRange("difference_step_px", difference_step_px, 1, 15);
  config::RequirePositive("depth_jump_per_m", depth_jump_per_m);
}

namespace {

// The guarded box filter along rows: out[i] is the mean of the valid samples within `radius`
// columns of i whose depth is within tolerance of in[i] (0 where in[i] is invalid). Branch-free
// inner loops so the compiler vectorises them.
void GuardedBoxRows(const float* in, float* out, int w, int h, int radius, float tol_base, float tol_per_m) {
  for (int v = 0; v < h; ++v) {
    const float* row = in + static_cast<std::size_t>(v) * w;
    float* out_row = out + static_cast<std::size_t>(v) * w;
    for (int u = 0; u < w; ++u) {
      const float z = row[u];
      const float tol = tol_base + tol_per_m * z * z;
      const int lo = u - radius < 0 ? 0 : u - radius;
      const int hi = u + radius >= w ? w - 1 : u + radius;
      float sum = 0.f, count = 0.f;
      for (int j = lo; j <= hi; ++j) {
        const float zj = row[j];
        const bool take = zj > 0.f && std::fabs(zj - z) < tol;
        sum += take ? zj : 0.f;
        count += take ? 1.f : 0.f;
      }
      out_row[u] = z > 0.f ? sum / count : 0.f;
    }
  }
}

// The same along columns, processed a row at a time so every access is contiguous.
void GuardedBoxColumns(const float* in, float* out, int w, int h, int radius, float tol_base, float tol_per_m,
                       std::vector<float>* scratch) {
  scratch->resize(3 * static_cast<std::size_t>(w));
  float* sum = scratch->data();
  float* count = sum + w;
  float* tol = count + w;
  for (int v = 0; v < h; ++v) {
    const float* centre = in + static_cast<std::size_t>(v) * w;
    for (int u = 0; u < w; ++u) {
      sum[u] = 0.f;
      count[u] = 0.f;
      tol[u] = tol_base + tol_per_m * centre[u] * centre[u];
    }
    const int lo = v - radius < 0 ? 0 : v - radius;
    const int hi = v + radius >= h ? h - 1 : v + radius;
    for (int j = lo; j <= hi; ++j) {
      const float* row = in + static_cast<std::size_t>(j) * w;
      for (int u = 0; u < w; ++u) {
        const float zj = row[u];
        const bool take = zj > 0.f && std::fabs(zj - centre[u]) < tol[u];
        sum[u] += take ? zj : 0.f;
        count[u] += take ? 1.f : 0.f;
      }
    }
    float* out_row = out + static_cast<std::size_t>(v) * w;
    for (int u = 0; u < w; ++u) out_row[u] = centre[u] > 0.f ? sum[u] / count[u] : 0.f;
  }
}

}  // namespace

void ComputeVertexNormalMap(const platform::DepthFrame& frame, const NormalEstimationOptions& options,
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
  const float smooth_base = static_cast<float>(options.smoothing_base_m);
  const float smooth_per_m = static_cast<float>(options.smoothing_per_m);

  // Smoothed depth (horizontal then vertical pass).
  std::vector<float>& tmp = out->scratch_depth_m;
  std::vector<float>& z_s = out->smoothed_depth_m;
  tmp.resize(n);
  z_s.resize(n);
  const float* depth = frame.depth_m.data();
  if (options.smoothing_radius_px > 0) {
    GuardedBoxRows(depth, tmp.data(), w, h, options.smoothing_radius_px, smooth_base, smooth_per_m);
    GuardedBoxColumns(tmp.data(), z_s.data(), w, h, options.smoothing_radius_px, smooth_base, smooth_per_m,
                      &out->scratch_rows);
  } else {
    z_s.assign(depth, depth + n);
  }

  const platform::CameraIntrinsics& in = frame.intrinsics;
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
