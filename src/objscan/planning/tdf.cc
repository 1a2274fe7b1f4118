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

// One pass along y (row_step = nx) or z (row_step = nx * ny) over rows of nx contiguous voxels:
// out_row(y, z) = sum_k w_k in_row at (y, z) shifted by k along the pass axis. Rows flagged empty in
// `in_nonzero` are skipped (the fields are thin surfaces, so most rows are empty); `out_nonzero`
// receives which output rows can be non-zero. `out` must be zero on entry.
void BlurRows(const float* in, float* out, int nx, int ny, int nz, bool along_z, const std::vector<float>& w,
              int radius, const std::vector<char>& in_nonzero, std::vector<char>* out_nonzero) {
  const int length = along_z ? nz : ny;
  out_nonzero->assign(in_nonzero.size(), 0);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      const int i = along_z ? z : y;
      const int k_lo = std::max(-radius, -i);
      const int k_hi = std::min(radius, length - 1 - i);
      float* o = out + static_cast<std::size_t>(nx) * (y + static_cast<std::size_t>(ny) * z);
      char any = 0;
      for (int k = k_lo; k <= k_hi; ++k) {
        const int sy = along_z ? y : y + k;
        const int sz = along_z ? z + k : z;
        const std::size_t row = sy + static_cast<std::size_t>(ny) * sz;
        if (!in_nonzero[row]) continue;
        any = 1;
        const float wk = w[k + radius];
        const float* src = in + static_cast<std::size_t>(nx) * row;
        for (int x = 0; x < nx; ++x) o[x] += wk * src[x];
      }
      (*out_nonzero)[y + static_cast<std::size_t>(ny) * z] = any;
    }
  }
}

}  // namespace

void GaussianBlur3d(const LocalGrid& grid, double sigma_voxels, std::vector<float>* field,
                    std::vector<float>* scratch) {
  const int radius = BlurRadiusVoxels(sigma_voxels);
  if (radius == 0 || grid.NumVoxels() == 0) return;
  const std::vector<float> w = Kernel(sigma_voxels, radius);
  const int nx = grid.nx, ny = grid.ny, nz = grid.nz;
  const std::size_t rows = static_cast<std::size_t>(ny) * nz;
  scratch->assign(field->size(), 0.0f);
  float* a = field->data();
  float* b = scratch->data();
  // X: within each non-empty row.
  std::vector<char> nonzero(rows, 0), next;
  for (std::size_t row = 0; row < rows; ++row) {
    const float* in = a + row * nx;
    if (std::none_of(in, in + nx, [](float v) { return v != 0.0f; })) continue;
    nonzero[row] = 1;
    float* out = b + row * nx;
    for (int x = 0; x < nx; ++x) {
      const int lo = std::max(-radius, -x);
      const int hi = std::min(radius, nx - 1 - x);
      float s = 0.0f;
      for (int k = lo; k <= hi; ++k) s += w[k + radius] * in[x + k];
      out[x] = s;
    }
  }
  // Y then Z, ping-ponging between the two buffers.
  std::fill(a, a + field->size(), 0.0f);
  BlurRows(b, a, nx, ny, nz, /*along_z=*/false, w, radius, nonzero, &next);
  std::fill(b, b + field->size(), 0.0f);
  BlurRows(a, b, nx, ny, nz, /*along_z=*/true, w, radius, next, &nonzero);
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
