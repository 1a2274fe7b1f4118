#pragma once
// The pre-segmented components C of the scene surface T (paper §4.1) and their adjacency graph:
// plain data produced by IncrementalSegmenter and read by the later stages (objectness,
// post-segmentation, next best object).
#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "objscan/geometry/aabb.h"

namespace objscan::segmentation {

class IncrementalSegmenter;

// One near-convex component c_i: the non-structural map elements carrying one pre-segment label.
struct Component {
  std::int32_t label = 0;                 // pre-segment label (> 0), stable across updates unless merged
  std::vector<Eigen::Vector3f> points;    // world frame, one per map element
  std::vector<Eigen::Vector3f> normals;   // unit, one per point
  geometry::Aabb3 bounds;
  double area_m2 = 0.0;                   // surface area (elements x voxel face area)
  std::uint64_t revision = 0;             // increases whenever this component's points changed
};

// Components sorted by label plus undirected adjacency (labels whose elements touch).
class ComponentGraph {
 public:
  const std::vector<Component>& components() const { return components_; }
  std::size_t size() const { return components_.size(); }
  bool empty() const { return components_.empty(); }

  // nullptr when no component has this label.
  const Component* Find(std::int32_t label) const;
  // Index of the component with this label in components(), or -1.
  int IndexOf(std::int32_t label) const;
  // Adjacent labels of `label`, ascending.
  const std::vector<std::int32_t>& Neighbors(std::int32_t label) const;
  // Every edge once as (a, b) with a < b, sorted.
  std::vector<std::pair<std::int32_t, std::int32_t>> Edges() const;
  bool Adjacent(std::int32_t a, std::int32_t b) const;

  // Builders (used by the segmenter and by tests that make graphs by hand).
  // Components must be sorted by label; neighbours[i] are the adjacent labels of components[i].
  void Assign(std::vector<Component> components, std::vector<std::vector<std::int32_t>> neighbors);

 private:
  friend class IncrementalSegmenter;  // updates components in place
  std::vector<Component> components_;
  std::vector<std::vector<std::int32_t>> neighbors_;  // parallel to components_, ascending
};

}  // namespace objscan::segmentation
