#pragma once
// Object instances of a ScanNet scan that has per-vertex labels but no aggregation (instance)
// file. ScanNet meshes are not connected: a chair's seat and its base, a table's top and its legs,
// are separate pieces of one label, so one instance per connected component over-counts objects (a
// room of 5 chairs loads as 14). Pieces of one label are one object when they are
//   - close: some vertex of one lies within join_distance_m of a vertex of the other, or
//   - stacked: their footprints (bounding rectangles seen from above) overlap by at least
//     stack_min_overlap of the smaller one and the vertical gap between them is at most
//     stack_max_gap_m (a seat over its base; wall cabinets 0.5 m above base cabinets stay apart).
// Objects with fewer than min_vertices vertices are label noise and belong to no instance.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace objscan::io {

struct InstanceInferenceOptions {
  double join_distance_m = 0.05;
  double stack_min_overlap = 0.5;
  double stack_max_gap_m = 0.35;
  std::size_t min_vertices = 30;
};

struct InferredInstances {
  std::vector<int> vertex_instance;  // per vertex: the instance index, or -1
  std::vector<int> instance_label;   // per instance: its label; instances ordered by their first vertex
};

// `points_world`: the levelled scan (z up); `labels`: one per vertex, 0 = unlabelled.
InferredInstances InferInstancesFromLabels(const std::vector<Eigen::Vector3f>& points_world,
                                           const std::vector<Eigen::Vector3i>& triangles,
                                           const std::vector<std::int32_t>& labels,
                                           const InstanceInferenceOptions& options = InstanceInferenceOptions());

}  // namespace objscan::io
