#pragma once
// The current scene surface T (paper §4.1): posed depth frames fused into voxel-hashed surface
// elements (one surfel per voxel, voxblox-style flat arrays plus an open-addressing hash index).
// The index is two-level: an open-addressing hash of 8x8x8-voxel blocks, each a dense array of
// element indices, so the neighbouring voxels association probes mostly share one cached block.
// Each element keeps a running weighted mean position and normal, a confidence (fusion weight), a
// pre-segment label with its voting confidence and a structural tag (floor / wall). The map never
// reads the frames' ground-truth channel (evaluation does, eval/ground_truth_votes.h).
//
// Association keeps a surface seen many times as one layer: a point joins the element of its own
// voxel or, failing that, an element a few voxels along its normal with an agreeing normal; only
// then does it start a new element.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/geometry/point_cloud.h"
#include "objscan/geometry/voxel_key.h"
#include "objscan/mapping/vertex_normal_map.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::mapping {

struct SurfaceMapOptions {
  double voxel_size_m = 0.01;
  // Search distance along the normal for an existing element: base + quadratic * z^2 (z = depth
  // in metres), rounded up to whole voxels; covers ~3 sigma of Kinect noise.
  double association_base_m = 0.01;
  double association_quadratic_per_m = 0.004;
  // A point only joins an element whose normal is within this angle of its own.
  double association_max_normal_angle_deg = 50.0;
  // Pixels seen more obliquely than this are not fused (their depth is unreliable).
  double max_incidence_deg = 80.0;
  // Each fused pixel weighs cos(incidence) / max(z, 1 m)^2.
  int pixel_stride = 1;  // fuse every n-th pixel in u and v
  NormalEstimationOptions normals;

  template <class V>
  void Visit(V& v) {
    v("voxel_size_m", voxel_size_m);
    v("association_base_m", association_base_m);
    v("association_quadratic_per_m", association_quadratic_per_m);
    v("association_max_normal_angle_deg", association_max_normal_angle_deg);
    v("max_incidence_deg", max_incidence_deg);
    v("pixel_stride", pixel_stride);
    v("normals", normals);
  }
  void Validate() const;
};

// Structural tag of an element (set by StructureDetector; kept out of the components C).
enum class Structure : std::uint8_t { kNone = 0, kFloor = 1, kWall = 2, kCeiling = 3 };

// What Integrate() did with each pixel of a frame: the element it was fused into (-1 when the
// pixel was not fused), and the frame's vertex/normal map, for the segmenter.
struct FrameAssociation {
  VertexNormalMap vertex_normals;
  std::vector<std::int32_t> pixel_element;  // row-major like the depth image
  std::size_t num_fused = 0;
  std::size_t num_created = 0;
};

class SurfaceMap {
 public:
  explicit SurfaceMap(const SurfaceMapOptions& options = SurfaceMapOptions());

  // Fuses one posed frame. When `association` is given it receives the per-pixel element indices
  // (valid until the next Integrate/Remove).
  void Integrate(const platform::DepthFrame& frame, FrameAssociation* association = nullptr);

  std::size_t size() const { return keys_.size(); }
  double voxel_size_m() const { return options_.voxel_size_m; }
  const SurfaceMapOptions& options() const { return options_; }

  // Element accessors (index in [0, size())).
  const Eigen::Vector3f& position(std::size_t i) const { return position_[i]; }
  const std::vector<Eigen::Vector3f>& positions() const { return position_; }  // every element's, by index
  Eigen::Vector3f normal(std::size_t i) const { return normal_sum_[i].normalized(); }
  float weight(std::size_t i) const { return weight_[i]; }
  std::int32_t label(std::size_t i) const { return label_[i]; }
  float label_confidence(std::size_t i) const { return label_confidence_[i]; }
  Structure structure(std::size_t i) const { return static_cast<Structure>(structure_[i]); }
  const geometry::VoxelKey& key(std::size_t i) const { return keys_[i]; }
  // Element index of a voxel, or -1.
  std::int32_t Find(const geometry::VoxelKey& key) const;

  // Pre-segment labels (written by the segmenter). Label 0 = unlabelled.
  void SetLabel(std::size_t i, std::int32_t label, float confidence);
  // Confidence-weighted vote: the same label gains `weight`, another label loses it and takes over
  // when the confidence falls below zero.
  void VoteLabel(std::size_t i, std::int32_t label, float weight);
  // Replaces every label in `from` (sorted) by `to` (after a merge).
  void RelabelAll(const std::vector<std::int32_t>& from, std::int32_t to);
  void SetStructure(std::size_t i, Structure s);

  // Queries.
  // Points and normals of the non-structural elements carrying `label` / any of `labels`.
  geometry::PointCloud Cloud(std::int32_t label) const;
  geometry::PointCloud Cloud(const std::vector<std::int32_t>& labels) const;
  // Every element (positions, normals, labels), e.g. for export.
  geometry::PointCloud AllPoints() const;
  // Distinct labels (> 0) present on non-structural elements, ascending.
  std::vector<std::int32_t> Labels() const;
  // Labels whose elements changed (votes, relabels, fusion, structure, removal) since the last call;
  // ascending. Clears the set.
  std::vector<std::int32_t> TakeDirtyLabels();
  // Removes every element carrying one of `labels` (T <- T \ gamma). Element indices change.
  // Returns the number of elements removed.
  std::size_t Remove(const std::vector<std::int32_t>& labels);
  geometry::Aabb3 Bounds() const;

 private:
  std::int32_t Insert(const geometry::VoxelKey& key);  // new element, returns its index
  // Drops and rebuilds the block index from keys_.
  void RebuildIndex();
  // Block index: the first entry of the block holding `key` in block_elements_, or -1.
  std::int32_t FindBlock(const geometry::VoxelKey& block_key) const;
  std::int32_t FindOrAddBlock(const geometry::VoxelKey& block_key);
  void GrowBlockTable();
  void MarkDirty(std::int32_t label) {
    if (label <= 0) return;
    if (static_cast<std::size_t>(label) >= dirty_flag_.size()) dirty_flag_.resize(2 * label + 16, 0);
    if (!dirty_flag_[label]) {
      dirty_flag_[label] = 1;
      dirty_labels_.push_back(label);
    }
  }

  SurfaceMapOptions options_;
  float inv_voxel_size_;

  // Element arrays (structure of arrays).
  std::vector<geometry::VoxelKey> keys_;
  std::vector<Eigen::Vector3f> position_;
  std::vector<Eigen::Vector3f> normal_sum_;  // weighted sum; normalise on read
  std::vector<float> weight_;
  std::vector<std::int32_t> label_;
  std::vector<float> label_confidence_;
  std::vector<std::uint8_t> structure_;

  // Block hash (linear probing, power-of-two capacity, at most half full): block key -> offset of
  // its 64 entries in block_elements_ (element index or -1 per voxel).
  struct Slot {
    geometry::VoxelKey key;
    std::int32_t offset = -1;
  };
  std::vector<Slot> slots_;
  std::size_t slot_mask_ = 0;
  std::size_t num_blocks_ = 0;
  std::vector<std::int32_t> block_elements_;

  std::vector<std::uint8_t> dirty_flag_;  // by label
  std::vector<std::int32_t> dirty_labels_;
  VertexNormalMap scratch_vertex_normals_;
  std::vector<float> ray_x_;  // per image column: (u - cx) / fx
};

}  // namespace objscan::mapping
