#pragma once
// The largest dense grids objscan builds, in cells: past them a grid would take gigabytes, so the
// builders refuse (InputError) and `objscan run` checks a scene against them before it starts
// (scanning/scene_limits.h), naming the config key whose resolution sets the grid's size.
#include <cstddef>

namespace objscan::limits {

// 2D grids over the floor (navigation, frontiers, ground-truth occupancy): one byte per cell.
constexpr std::size_t kMaxGrid2dCells = 64'000'000;
// The occupancy map's dense snapshot (occupancy.resolution_m): one byte per cell.
constexpr std::size_t kMaxOccupancySnapshotCells = std::size_t{1} << 28;
// The evaluation's voxels of the room's air (eval.coverage_voxel_size_m): a few bytes per cell.
constexpr std::size_t kMaxEvaluationGridCells = std::size_t{1} << 30;

}  // namespace objscan::limits
