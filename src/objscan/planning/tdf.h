#pragma once
// Truncated distance function of a shape on a local grid (eq. TDF of the paper): f(x, X) = 1 on voxels
// holding points of X, 0 elsewhere, then Gaussian-blurred "to reduce the effect of data noise".
// The blur kernel sums to one, so f stays in [0, 1]; for a surface whose position is uncertain by
// sigma it is the probability that a voxel holds the surface.
#include <Eigen/Core>
#include <vector>

#include "objscan/planning/local_grid.h"

namespace objscan::planning {

// Half width of the truncated kernel in voxels: ceil(3 sigma) (0 when sigma is 0).
int BlurRadiusVoxels(double sigma_voxels);

// Separable Gaussian blur of `field` in place; values outside the grid count as 0. sigma 0: no-op.
// `scratch` is resized as needed (pass the same one to avoid reallocations).
void GaussianBlur3d(const LocalGrid& grid, double sigma_voxels, std::vector<float>* field,
                    std::vector<float>* scratch);

// f(., X) for the point set X on `grid`: indicator then blur. `field` is resized to the grid.
void BuildTdf(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world, double sigma_voxels,
              std::vector<float>* field, std::vector<float>* scratch);

}  // namespace objscan::planning
