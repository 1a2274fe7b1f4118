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

  // Interpolated distance to the nearest point, at most truncation_m (which it is outside the grid).
  float Distance(const Eigen::Vector3f& q) const {
    const Eigen::Vector3f g = (q - origin_) * inv_spacing_;
    // Vertices [i, i + 1] in each dimension; the last cell is excluded so i + 1 stays inside.
    if (!(g.x() >= 0.f && g.y() >= 0.f && g.z() >= 0.f && g.x() < static_cast<float>(nx_ - 1) &&
          g.y() < static_cast<float>(ny_ - 1) && g.z() < static_cast<float>(nz_ - 1)))
      return truncation_m_;
    const int ix = static_cast<int>(g.x()), iy = static_cast<int>(g.y()), iz = static_cast<int>(g.z());
    const float fx = g.x() - ix, fy = g.y() - iy, fz = g.z() - iz;
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
  std::vector<std::uint8_t> values_;  // x fastest
};

}  // namespace objscan::recognition
