#include "objscan/planning/tdf.h"

#include <algorithm>
#include <cmath>

namespace objscan::planning {

int BlurRadiusVoxels(double sigma_voxels) {
  return sigma_voxels > 0.0 ? static_cast<int>(std::ceil(3.0 * sigma_voxels)) : 0;
}

namespace {

std::vector<float> Kernel(double sigma_voxels, int radius) {
  std::vector<float> w(2 * radius + 1);
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) sum += std::exp(-0.5 * k * k / (sigma_voxels * sigma_voxels));
  for (int k = -radius; k <= radius; ++k) {
    w[k + radius] = static_cast<float>(std::exp(-0.5 * k * k / (sigma_voxels * sigma_voxels)) / sum);
  }
  return w;
}

// out[i * stride] = sum_k w[k] in[(i + k - r) * stride] for lines of `length` elements that are `stride`
// apart; `width` contiguous lines are processed together so the inner loop runs over memory in order
// (and vectorises) for every axis.
void BlurLines(const float* in, float* out, int length, std::size_t stride, std::size_t width,
               const std::vector<float>& w, int radius) {
  for (int i = 0; i < length; ++i) {
    float* o = out + i * stride;
    std::fill(o, o + width, 0.0f);
    const int k_lo = std::max(-radius, -i);
    const int k_hi = std::min(radius, length - 1 - i);
    for (int k = k_lo; k <= k_hi; ++k) {
      const float wk = w[k + radius];
      const float* src = in + static_cast<std::ptrdiff_t>(i + k) * static_cast<std::ptrdiff_t>(stride);
      for (std::size_t e = 0; e < width; ++e) o[e] += wk * src[e];
    }
  }
}

}  // namespace

void GaussianBlur3d(const LocalGrid& grid, double sigma_voxels, std::vector<float>* field,
                    std::vector<float>* scratch) {
  const int radius = BlurRadiusVoxels(sigma_voxels);
  if (radius == 0 || grid.NumVoxels() == 0) return;
  const std::vector<float> w = Kernel(sigma_voxels, radius);
  const std::size_t nx = grid.nx, ny = grid.ny, nz = grid.nz;
  scratch->resize(field->size());
  float* a = field->data();
  float* b = scratch->data();
  // X: each row is a line of single elements; blur it directly (the inner loop runs over the taps).
  for (std::size_t row = 0; row < ny * nz; ++row) {
    const float* in = a + row * nx;
    float* out = b + row * nx;
    for (std::size_t x = 0; x < nx; ++x) {
      const int lo = std::max(-radius, -static_cast<int>(x));
      const int hi = std::min(radius, static_cast<int>(nx - 1 - x));
      float s = 0.0f;
      for (int k = lo; k <= hi; ++k) s += w[k + radius] * in[static_cast<int>(x) + k];
      out[x] = s;
    }
  }
  // Y: for each z slab, lines along y of width nx.
  for (std::size_t z = 0; z < nz; ++z) {
    BlurLines(b + z * nx * ny, a + z * nx * ny, static_cast<int>(ny), nx, nx, w, radius);
  }
  // Z: lines along z of width nx * ny.
  BlurLines(a, b, static_cast<int>(nz), nx * ny, nx * ny, w, radius);
  // Sums of non-negative weights <= 1 of values in [0, 1] stay there up to rounding; clamp that away.
  for (std::size_t i = 0; i < field->size(); ++i) a[i] = std::min(1.0f, std::max(0.0f, b[i]));
}

void BuildTdf(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world, double sigma_voxels,
              std::vector<float>* field, std::vector<float>* scratch) {
  field->assign(grid.NumVoxels(), 0.0f);
  RasterizeIndicator(grid, points_world, field);
  GaussianBlur3d(grid, sigma_voxels, field, scratch);
}

}  // namespace objscan::planning
