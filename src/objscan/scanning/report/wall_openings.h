#pragma once
// Beyond the paper: windows from where they are. A window fills an opening in a wall, so its pane
// and frame lie behind the wall's plane, where nothing else in a room can be seen; seen from inside
// it is a flat framed rectangle that retrieval confuses with the fronts of dressers, shelves and
// refrigerators. At the end of a run, an object most of whose points lie in wall openings is
// reported as a window (the window model that fits it best, with its pose), and an object labelled
// window with almost none there loses that label. And curtains from where they hang: a tall thing
// with a folded face hanging just in front of a wall, over a window in it, is a curtain, however
// well a door or window model fits its face (a curtain panel is a door-sized slab, and the
// database's pleats fall elsewhere than the scanned ones, so a flat model fits it as well). And
// doors by their depth: a door model fits any flat face, but a door leaf is thin.
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/world/category.h"

namespace objscan::mapping {
struct StructureResult;
}  // namespace objscan::mapping

namespace objscan::scanning {

struct WallOpeningOptions {
  double min_depth_m = 0.02;    // behind a wall plane by more than this ...
  double max_depth_m = 0.3;     // ... and at most this (the wall's thickness and a deep reveal)
  double window_min_share = 0.5;  // share of an object's points in openings that makes it a window
  double window_keep_share = 0.1; // a window label needs at least this share
  double min_sill_height_m = 0.2; // a window's lowest point is this far above the floor (doors reach it)
  // A window label goes from an object with window_keep_share of its points in wall openings that
  // reaches the floor (its lowest points within min_sill_height_m of it): an opening down to the
  // floor is a doorway, and what recognition fits a window model to there is a door's frame, its
  // reveals or the room beyond. false = the sill only decides which objects are made windows.
  bool doorways_are_not_windows = true;
  // A window label also stays on an object off the floor (min_sill_height_m) of whose points at
  // least hanging_window_min_share lie in front of one wall, within hanging_window_max_distance_m:
  // a window mounted on the wall's face with no opening behind it, as in the SUNCG rooms of the OASC
  // benchmark. Negative distance = only windows in openings keep the label.
  double hanging_window_max_distance_m = 0.3;
  double hanging_window_min_share = 0.9;
  // Objects labelled window whose points in wall openings come this close (their boxes) are pieces of
  // one window (frame, sashes and panes are pre-segmented apart, and each piece fits a window model);
  // they are reported as one (report rule join_window_pieces).
  double join_gap_m = 0.1;
  // An object labelled door, or left unlabelled, is a curtain when at least curtain_min_share of its
  // points lie within curtain_max_distance_m in front of one wall (and not behind it), it is at
  // least curtain_min_height_m tall, its face is folded (the middle half of its points spread over
  // curtain_min_fold_depth_m to curtain_max_fold_depth_m of distance from the wall: a door leaf
  // opened over a window is flat, ~1 cm with its panels; more than the maximum is a thing with
  // depth, such as shelves' boards and back), and it covers a window in that wall by
  // curtain_min_overlap_m along the wall (and overlaps it in height) (report rule
  // curtains_over_windows).
  double curtain_max_distance_m = 0.3;
  double curtain_min_share = 0.9;
  double curtain_min_height_m = 0.8;
  double curtain_min_overlap_m = 0.1;
  double curtain_min_fold_depth_m = 0.026;
  double curtain_max_fold_depth_m = 0.1;
  // Objects labelled curtain that hang over the same window (by the rule above) are the panels of
  // one curtain and are reported as one, hosted like window pieces (HostsOfGroups). false = each
  // panel is an object.
  bool join_curtain_panels = true;
  // Doors by their depth: a door leaf is a slab a few centimetres thick (with its handles and what of
  // the wall beside it joins it, under 0.35 m), and what the robot sees of it lies in such a slab; a
  // door label on an object whose seen surface is wider than door_max_depth_m in every horizontal
  // direction goes (a flat door model fits any flat face, such as a cabinet's front, and the sides
  // and top seen later make it 0.4-0.6 m deep), and a completed door that deep is reported
  // unfinished (report rules reopen_outgrown and door_depth).
  double door_max_depth_m = 0.4;

  template <class V>
  void Visit(V& v) {
    v("min_depth_m", min_depth_m);
    v("max_depth_m", max_depth_m);
    v("window_min_share", window_min_share);
    v("window_keep_share", window_keep_share);
    v("min_sill_height_m", min_sill_height_m);
    v("doorways_are_not_windows", doorways_are_not_windows);
    v("hanging_window_max_distance_m", hanging_window_max_distance_m);
    v("hanging_window_min_share", hanging_window_min_share);
    v("join_gap_m", join_gap_m);
    v("curtain_max_distance_m", curtain_max_distance_m);
    v("curtain_min_share", curtain_min_share);
    v("curtain_min_height_m", curtain_min_height_m);
    v("curtain_min_overlap_m", curtain_min_overlap_m);
    v("curtain_min_fold_depth_m", curtain_min_fold_depth_m);
    v("curtain_max_fold_depth_m", curtain_max_fold_depth_m);
    v("join_curtain_panels", join_curtain_panels);
    v("door_max_depth_m", door_max_depth_m);
  }
  void Validate() const;
};

enum class WallOpeningVerdict {
  kNoChange,   // leave the label as recognition gave it
  kWindow,     // in a wall opening: a window (whatever its label; its size is the opening's)
  kNotWindow,  // a window label on something neither in an opening nor hanging on a wall
};

struct WallOpeningResult {
  double share = 0.0;  // share of the points in wall openings
  WallOpeningVerdict verdict = WallOpeningVerdict::kNoChange;
};

// The verdict for an object with these points whose current label is (or is not) window.
WallOpeningResult ClassifyWallOpening(const std::vector<Eigen::Vector3f>& points_world,
                                      const mapping::StructureResult& structure, bool labelled_window,
                                      const WallOpeningOptions& options);

// Where an object lies in wall openings: the wall whose opening holds most of its points (-1 when
// none does or options are off) and the box of the points in that wall's opening.
struct OpeningExtent {
  int wall = -1;  // index into StructureResult::walls
  geometry::Aabb3 bounds;
  // The same points' extent along that wall (mapping::WallPlane::Along) and in height.
  double along_min_m = std::numeric_limits<double>::infinity();
  double along_max_m = -std::numeric_limits<double>::infinity();
  double z_min_m = std::numeric_limits<double>::infinity();
  double z_max_m = -std::numeric_limits<double>::infinity();
  // HangingExtent only: the interquartile range of the hanging points' distances from the wall
  // plane, the depth of a pleated face's folds.
  double fold_depth_m = 0.0;
};
OpeningExtent OpeningBounds(const std::vector<Eigen::Vector3f>& points_world, const mapping::StructureResult& structure,
                            const WallOpeningOptions& options);

// One reported object's part in JoinWindowPieces.
struct WindowPiece {
  OpeningExtent opening;    // where it lies in wall openings (OpeningBounds)
  bool window = false;      // labelled window (only windows join)
  bool complete = false;    // replaced by its model: it hosts whatever joins it
  std::size_t num_points = 0;
};

// Windows in the opening of one wall whose boxes there lie within gap_m of each other (transitively)
// form one window. Returns, per piece, the piece it joins: the complete one if any, else the one with
// most points (lowest index on ties); itself for pieces that stay (all of them when gap_m < 0).
std::vector<int> JoinWindowPieces(const std::vector<WindowPiece>& pieces, double gap_m);

// Per piece, the piece it joins when the pieces of each group (`group`, parallel to `pieces`; ids
// >= 0, any values) are one object: the complete one if any, else the one with most points (lowest
// index on ties); itself for pieces of group -1. Only `complete` and `num_points` are read.
std::vector<int> HostsOfGroups(const std::vector<int>& group, const std::vector<WindowPiece>& pieces);

// The first wall (index into StructureResult::walls; -1 for none) in front of which, by at most
// max_distance_m (behind it by at most min_depth_m) and within its span, at least min_share of the
// points lie.
int HangingWall(const std::vector<Eigen::Vector3f>& points_world, const mapping::StructureResult& structure,
                double min_depth_m, double max_distance_m, double min_share);

// Whether an object not in a wall opening, with this label and share of points in openings, may be
// found to be a curtain over a window: unlabelled, a door or a curtain, or a window label kept only
// because the object hangs on a wall (share below window_keep_share). A curtain hanging on its rail
// over a window is such an object too.
bool MayBeCurtain(const std::optional<world::Category>& label, double wall_opening_share,
                  const WallOpeningOptions& options);

// Where an object hangs in front of a wall: the wall (-1 for none) in front of which, by at most
// curtain_max_distance_m and within its span, at least curtain_min_share of the points lie, and the
// extent of those points along it and in height (the fields of OpeningExtent, bounds left empty).
OpeningExtent HangingExtent(const std::vector<Eigen::Vector3f>& points_world,
                            const mapping::StructureResult& structure, const WallOpeningOptions& options);

// Under curtain_must_hang, whether an object labelled `label` whose points hang as `hanging`
// (HangingExtent) loses its label: only a curtain label on a thing that does not hang on a wall does.
bool CurtainLabelGoes(const std::optional<world::Category>& label, const OpeningExtent& hanging,
                      const WallOpeningOptions& options);

// The window an object hanging as `hanging` (HangingExtent) is a curtain over: the index of the
// first of `windows` (their OpeningBounds) it overlaps along the wall by curtain_min_overlap_m and in
// height, on the same wall, when it is tall enough and folded; -1 for none, and when curtains are off.
int CurtainWindow(const OpeningExtent& hanging, const std::vector<OpeningExtent>& windows,
                  const WallOpeningOptions& options);

// The smallest horizontal width of a point set: over directions in the floor plane (1° apart), the
// least extent of the points along one (0 for no points).
double MinHorizontalWidth(const std::vector<Eigen::Vector3f>& points_world);

// Whether an object with these points is too deep to be a door (door_max_depth_m); false when the
// check is off.
bool TooDeepForADoor(const std::vector<Eigen::Vector3f>& points_world, const WallOpeningOptions& options);

}  // namespace objscan::scanning
