#pragma once
// Spatially sensitive bag of words (paper §4.2): word histograms per spatial cell of the item's upright
// frame, so that two shapes with the same local parts in different places differ. Gravity is known and
// the floor is at z = 0 (database models stand on it, live objects mostly do), so there are three
// levels, like a spatial pyramid:
//   - global: all keypoints (a partial view whose box is cut still matches on its words);
//   - relative: height bands of the points' axis-aligned box x rings of horizontal distance from the
//     box's vertical axis (yaw does not matter);
//   - absolute: height bands above the floor in metres x the keypoint normal's class (facing up, down
//     or sideways): a seat at 0.45 m, a table top at 0.75 m and a bed at 0.5 m differ here even when
//     their local shape words do not, and a partial view keeps its heights.
// Beside the words, two "size words" describe the whole point set: its height (log-spaced bins) and
// the height of its lowest point (a window or a wall cabinet does not reach the floor); both
// survive a view from one side, unlike the footprint. Each is soft-assigned to its two nearest bins.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/recognition/vocabulary.h"

namespace objscan::recognition {

struct SpatialBowOptions {
  int height_bands = 3;
  int radial_rings = 2;
  double spatial_weight = 1.0;   // weight of the relative level against the global level
  std::vector<double> absolute_height_edges_m = {0.15, 0.35, 0.55, 0.8, 1.1, 1.5};
  double absolute_weight = 1.0;  // weight of the absolute level (0 = off)
  double up_normal_min_z = 0.7;  // |n.z| above this: facing up / down
  double size_weight = 0.2;      // weight of the size words (0 = off)
  double height_bin_ratio = 1.15;  // consecutive height bins differ by this factor (from 5 cm)
  double floor_gap_bin_m = 0.15;   // bin width of the lowest point's height

  template <class V>
  void Visit(V& v) {
    v("height_bands", height_bands);
    v("radial_rings", radial_rings);
    v("spatial_weight", spatial_weight);
    v("absolute_height_edges_m", absolute_height_edges_m);
    v("absolute_weight", absolute_weight);
    v("up_normal_min_z", up_normal_min_z);
    v("size_weight", size_weight);
    v("height_bin_ratio", height_bin_ratio);
    v("floor_gap_bin_m", floor_gap_bin_m);
  }
  void Validate() const;
  static constexpr int kMaxBandsOrRings = 100;  // height bands, radial rings, absolute height edges
  int NumRelativeCells() const { return height_bands * radial_rings; }
  int NumAbsoluteCells() const { return 3 * (static_cast<int>(absolute_height_edges_m.size()) + 1); }
  int NumCells() const { return 1 + NumRelativeCells() + NumAbsoluteCells(); }
  static constexpr int kHeightBins = 32;
  static constexpr int kFloorGapBins = 16;
  // Word bins (num_words x NumCells()) followed by the size bins.
  std::uint32_t NumBins(int num_words) const {
    return static_cast<std::uint32_t>(num_words * NumCells() + kHeightBins + kFloorGapBins);
  }
};

struct HistogramBin {
  std::uint32_t bin = 0;  // cell * num_words + word
  float value = 0.f;
};
// Non-zero bins in increasing bin order.
using SparseHistogram = std::vector<HistogramBin>;

// Relative cell (1 .. NumRelativeCells()) of a point in the frame given by `bounds`.
int SpatialCell(const Eigen::Vector3f& p, const geometry::Aabb3& bounds, const SpatialBowOptions& options);
// Absolute cell (1 + NumRelativeCells() .. NumCells() - 1) of a point and its unit normal.
int AbsoluteCell(const Eigen::Vector3f& p, const Eigen::Vector3f& normal, const SpatialBowOptions& options);

// Histogram of the keypoints' soft word assignments; each level is L1-normalised and scaled by its
// weight. `descriptors` is keypoints.size() x vocabulary.dimension(); `keypoint_normals` one unit
// normal per keypoint (outward).
SparseHistogram ComputeSpatialBow(const Vocabulary& vocabulary, const std::vector<Eigen::Vector3f>& keypoints,
                                  const std::vector<Eigen::Vector3f>& keypoint_normals,
                                  const std::vector<float>& descriptors, const geometry::Aabb3& bounds,
                                  const SpatialBowOptions& options);

}  // namespace objscan::recognition
