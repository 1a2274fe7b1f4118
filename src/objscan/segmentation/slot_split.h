#pragma once
// Beyond the paper: cutting the pre-segmentation at narrow slots between pieces of furniture
// standing side by side. Kitchen base cabinets stand 2.5 cm apart: far views cannot resolve the
// gap, so frame segments span the counter run, the incremental segmenter merges it, and a union of
// two base cabinets fits a sideboard model better than either fits a cabinet, so the grouping
// joins them too. A slot shows in the map as two sheets of side faces turned to each other a few
// centimetres apart: one facing +a at the end of the left piece, one facing -a at the start of the
// right one. (A panel between two bowls or shelf bays shows the opposite order, faces turned away
// from each other, and is no slot; door and drawer gaps of a few millimetres are below min_gap_m.)
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"

namespace objscan::segmentation {

struct SlotSplitOptions {
  bool enabled = false;
  // Distance between the two facing sheets (the slot's width, as the map resolves it).
  double min_gap_m = 0.015;
  double max_gap_m = 0.06;
  // Each sheet: at least this much side-face area (elements x element area) within 2 bins.
  double min_sheet_area_m2 = 0.015;
  // Each side of a cut: at least this much surface.
  double min_part_area_m2 = 0.1;
  // The two sheets face each other over most of their extent: the overlap of their height ranges
  // (and of their ranges across) is at least this share of the smaller one's. A chair's seat and
  // backrest a few centimetres apart show a low sheet (the seat's back edge) before a tall one.
  double min_sheet_overlap = 0.6;
  // A side-face element's normal is within this cosine of the axis.
  double sheet_min_cos = 0.9;
  double bin_m = 0.01;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("min_gap_m", min_gap_m);
    v("max_gap_m", max_gap_m);
    v("min_sheet_area_m2", min_sheet_area_m2);
    v("min_part_area_m2", min_part_area_m2);
    v("min_sheet_overlap", min_sheet_overlap);
    v("sheet_min_cos", sheet_min_cos);
    v("bin_m", bin_m);
  }
  void Validate() const;
};

// A vertical cut plane through a slot: points p with p.dot(axis) < offset_m lie before it.
// `across` is the horizontal axis in the plane; the sheets' elements span [across_min_m,
// across_max_m] along it and [z_min_m, z_max_m] in height (between their 5% and 95% quantiles).
struct Slot {
  Eigen::Vector3f axis = Eigen::Vector3f::UnitX();
  Eigen::Vector3f across = Eigen::Vector3f::UnitY();
  double offset_m = 0.0;
  double across_min_m = 0.0, across_max_m = 0.0;
  double z_min_m = 0.0, z_max_m = 0.0;
  bool Before(const Eigen::Vector3f& p) const { return p.dot(axis) < offset_m; }
};

// The slots in a set of surface elements (points and normals parallel, world frame, Z up), along
// the two horizontal axes of their dominant side-face orientation, ordered by axis then offset;
// each leaves at least min_part_area_m2 on both sides. `element_area_m2`: the surface one element
// stands for. None when disabled.
std::vector<Slot> FindSlots(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                            double element_area_m2, const SlotSplitOptions& options);

}  // namespace objscan::segmentation
