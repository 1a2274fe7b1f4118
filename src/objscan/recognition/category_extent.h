#pragma once
// Beyond the paper: how big the objects of each category are, from the database's full models, and
// whether a reconstructed object could be one of them. The paper's objectness is normalised by the
// query's own diagonal, so a 30 cm piece of a dresser can fit a bed model's corner as well as a whole
// bed fits a bed; once scanning ends, a "bed" that small (or a "cabinet" spanning a whole wall) is
// not one. Extents are yaw-invariant: the height and the diagonal of the smallest horizontal
// bounding rectangle.
#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/world/category.h"

namespace objscan::recognition {

class ModelDatabase;

struct ObjectExtent {
  double height_m = 0.0;              // vertical size of the points' bounding box
  double footprint_diagonal_m = 0.0;  // diagonal of the smallest bounding rectangle over yaw
};

// The extent of a point set (Z up); zeros when empty. The rectangle is searched over yaw in steps
// of 90° / yaw_steps, so its diagonal overestimates the smallest one's by at most a factor
// sqrt(1 + sin(90° / yaw_steps)) (1.05 for 16 steps). With trim_fraction > 0, each range (height,
// and each side of the rectangle) runs between the trim_fraction and 1 - trim_fraction quantiles
// of the points instead of their extremes, so that a few stray points (noisy wall returns that
// joined an object) do not set its size.
ObjectExtent MeasureExtent(const std::vector<Eigen::Vector3f>& points, int yaw_steps = 16,
                           double trim_fraction = 0.0);

struct ExtentRange {
  ObjectExtent min;  // component-wise over the category's models
  ObjectExtent max;
  int num_models = 0;
};

// Per-category extents of the database's full models.
class CategoryExtents {
 public:
  CategoryExtents() = default;
  static CategoryExtents FromDatabase(const ModelDatabase& database);
  void Add(world::Category category, const ObjectExtent& extent);
  // Null when the database has no model of the category.
  const ExtentRange* Find(world::Category category) const;

 private:
  std::array<ExtentRange, world::kNumObjectCategories> ranges_{};
};

struct SizePlausibilityOptions {
  // An object is a plausible member of a category when its height and footprint diagonal both lie in
  // [min_ratio * smallest model's, max_ratio * largest model's]. Below: a fragment; above: several
  // objects (or a wall) taken for one.
  double min_ratio = 0.5;
  double max_ratio = 1.4;
  // A reconstructed object's extent leaves out this share of its points at each end of each range
  // (MeasureExtent's trim_fraction); 0 = its extreme points. Database models are measured whole.
  double extent_trim_fraction = 0.005;
  // Before that, the scanner leaves out of a reconstructed object's extent its points within this
  // distance of a detected wall plane, unless that leaves less than half of them (a door, a window,
  // a curtain lies along a wall). Noisy far returns of a wall (the depth noise is 2-3 cm at 3-4 m)
  // escape the wall tags and join the furniture before it; they would make it as long as the wall.
  // 0 = off.
  double wall_margin_m = 0.08;
  // An object whose label a check took (this one, or a window label outside wall openings) takes the
  // best-fitting other category among its full-model matches that its size fits, when that match's
  // objectness reaches relabel_min_objectness (report rule relabel); without one it is reported
  // unrecognized. The threshold keeps guesses out: most such labels are right above ~0.92.
  double relabel_min_objectness = 0.92;
  // Before the check, pieces too small for their label join an adjacent object whose category the
  // union fits (scanning/report/size_regrouping.h; report rule regroup_by_size).
  double adjacency_m = 0.05;  // pieces with points this close are adjacent for the regrouping
  // Beyond that, a piece standing under another with at most this gap between the lower one's top
  // and the upper one's bottom is adjacent to it (size_regrouping.h, ObjectsStandingUnder: a table
  // top and its legs, apart by the unseen underside).
  double support_gap_m = 0.15;
  // After the regrouping, of two labelled pieces one standing under the other (by support_gap_m),
  // the smaller joins the larger when the union fits the larger's label (size_regrouping.h,
  // JoinStackedPieces: a lamp's shade taken for a radio over its stem; report rule join_stacked).

  template <class V>
  void Visit(V& v) {
    v("min_ratio", min_ratio);
    v("max_ratio", max_ratio);
    v("extent_trim_fraction", extent_trim_fraction);
    v("wall_margin_m", wall_margin_m);
    v("relabel_min_objectness", relabel_min_objectness);
    v("adjacency_m", adjacency_m);
    v("support_gap_m", support_gap_m);
  }
  void Validate() const;
};

// A reconstructed object's extent as the size check measures it: MeasureExtent with the default
// yaw steps and options.extent_trim_fraction.
ObjectExtent MeasureObjectExtent(const std::vector<Eigen::Vector3f>& points, const SizePlausibilityOptions& options);

// True when `extent` fits `range` under `options` (always true when range is null).
bool IsPlausibleExtent(const ObjectExtent& extent, const ExtentRange* range, const SizePlausibilityOptions& options);

}  // namespace objscan::recognition
