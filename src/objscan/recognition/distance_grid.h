#pragma once
// A small truncated distance field over a point set: the distance to the nearest point, sampled at
// the vertices of a regular grid over the points' bounds (grown by the truncation distance), one
// byte per vertex, trilinearly interpolated. A lookup costs eight byte reads instead of a kd-tree
// search, for scoring many alignment hypotheses where an error of a fraction of the spacing is
// harmless (distances between two keypoint samplings are that noisy anyway).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace objscan::recognition {

class DistanceGrid {
 public:
  DistanceGrid() = default;
  // At most max_vertices vertices (the spacing grows to fit), spacing at least min_spacing_m.
  DistanceGrid(const std::vector<Eigen::Vector3f>& points, float truncation_m, int max_vertices,
               float min_spacing_m);

  bool empty() const { return values_.empty(); }
  float truncation_m() const { return truncation_m_; }
  float spacing_m() const { return spacing_m_; }
  std::size_t num_vertices() const { return values_.size(); }

  // Distance() of q[0, n) into distance[0, n): one call for a batch, the lookups inlined in its loop.
  void Distances(const Eigen::Vector3f* q, std::size_t n, float* distance) const;

  // Interpolated distance to the nearest point, at most truncation_m (which it is outside the grid).
  float Distance(const Eigen::Vector3f& q) const {
    // Plain float arithmetic (no Eigen temporaries) keeps this small enough to inline into loops.
    const float gx = (q.x() - origin_.x()) * inv_spacing_, gy = (q.y() - origin_.y()) * inv_spacing_,
                gz = (q.z() - origin_.z()) * inv_spacing_;
    // Vertices [i, i + 1] in each dimension; the last cell is excluded so i + 1 stays inside.
    if (!(gx >= 0.f && gy >= 0.f && gz >= 0.f && gx < max_cell_x_ && gy < max_cell_y_ && gz < max_cell_z_))
      return truncation_m_;
    const int ix = static_cast<int>(gx), iy = static_cast<int>(gy), iz = static_cast<int>(gz);
    const float fx = gx - ix, fy = gy - iy, fz = gz - iz;
    const std::uint8_t* v = values_.data() + (static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix;
    const std::size_t sy = nx_, sz = static_cast<std::size_t>(nx_) * ny_;
    const float c00 = v[0] + fx * (v[1] - v[0]);
    const float c10 = v[sy] + fx * (v[sy + 1] - v[sy]);
    const float c01 = v[sz] + fx * (v[sz + 1] - v[sz]);
    const float c11 = v[sz + sy] + fx * (v[sz + sy + 1] - v[sz + sy]);
    const float c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
    return (c0 + fz * (c1 - c0)) * step_m_;
  }

 private:
  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();  // vertex (0, 0, 0)
  float spacing_m_ = 0.f, inv_spacing_ = 0.f;
  float truncation_m_ = 0.f;
  float step_m_ = 0.f;  // metres per quantisation step: truncation_m / 255
  int nx_ = 0, ny_ = 0, nz_ = 0;
  float max_cell_x_ = 0.f, max_cell_y_ = 0.f, max_cell_z_ = 0.f;  // n - 1 per axis
  std::vector<std::uint8_t> values_;  // x fastest
};

}  // namespace objscan::recognition
