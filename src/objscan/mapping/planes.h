#pragma once
// Floor and walls of the fused surface (paper §5.1, "Floor and wall"): the floor is the dominant
// horizontal plane near z = 0, walls are large vertical planes that bound the observed surface
// (almost nothing lies behind them). Their elements are tagged structural in the SurfaceMap and so
// stay out of the components C. Beyond the paper (whose rooms are open at the top), a ceiling is
// structure too, not an object: its lowest level is the lowest height well above the floor where
// downward-facing elements cover ceiling_min_area_m2; every element from that level up that does
// not face up (upper ceiling levels, the sides of bulkheads and beams) is tagged ceiling.
#include <Eigen/Core>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/mapping/surface_map.h"

namespace objscan::mapping {

struct StructureOptions {
  double floor_search_height_m = 0.3;   // the floor is looked for within +-this of z = 0
  double floor_max_tilt_deg = 20.0;     // element normals within this of +Z count as floor
  double floor_min_area_m2 = 0.3;
  double plane_tolerance_m = 0.03;      // element-to-plane distance that tags an element
  double wall_max_tilt_deg = 15.0;      // element normals within this of horizontal
  double wall_angle_bin_deg = 3.0;      // Hough bins over (normal azimuth, offset)
  double wall_offset_bin_m = 0.04;
  double wall_min_area_m2 = 0.8;
  double wall_min_height_m = 1.0;       // vertical extent of the wall's elements
  // A wall has at most this share of all elements more than wall_behind_min_depth_m behind it.
  double wall_max_behind_fraction = 0.03;
  // Shallower than this behind a plane are what fills its openings (a window pane recessed a few cm,
  // a frame) and noise, which do not count against a wall; 0.06 (2 x plane_tolerance_m) = the old
  // rule, which rejected walls with a big recessed window. Of two parallel planes closer than this
  // (and farther apart than 2 x plane_tolerance_m), one larger and as long, only that one is a wall.
  double wall_behind_min_depth_m = 0.12;
  int wall_max_count = 12;
  // The ceiling is looked for this far above the floor and more, and needs this much area. Furniture
  // tops face up; the large downward faces this high are ceilings and the building's beams and
  // lintels at ceiling height (the AWS house without its ceiling has 1.8 m2 of them at 2.5 m):
  // structure either way.
  double ceiling_min_height_m = 2.0;
  double ceiling_min_area_m2 = 1.0;
  // A plane in front of a parallel wall whose top this much lower than the wall's is furniture
  // against it (0 = only when the wall behind overlaps it along the wall).
  double furniture_top_margin_m = 0.2;

  template <class V>
  void Visit(V& v) {
    v("floor_search_height_m", floor_search_height_m);
    v("floor_max_tilt_deg", floor_max_tilt_deg);
    v("floor_min_area_m2", floor_min_area_m2);
    v("plane_tolerance_m", plane_tolerance_m);
    v("wall_max_tilt_deg", wall_max_tilt_deg);
    v("wall_angle_bin_deg", wall_angle_bin_deg);
    v("wall_offset_bin_m", wall_offset_bin_m);
    v("wall_min_area_m2", wall_min_area_m2);
    v("wall_min_height_m", wall_min_height_m);
    v("wall_max_behind_fraction", wall_max_behind_fraction);
    v("wall_behind_min_depth_m", wall_behind_min_depth_m);
    v("wall_max_count", wall_max_count);
    v("ceiling_min_height_m", ceiling_min_height_m);
    v("ceiling_min_area_m2", ceiling_min_area_m2);
    v("furniture_top_margin_m", furniture_top_margin_m);
  }
  void Validate() const;
};

// A vertical wall plane n . x = offset with n horizontal, pointing into the room.
struct WallPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double offset_m = 0.0;
  double area_m2 = 0.0;
  double z_min_m = 0.0, z_max_m = 0.0;
  // Extent along the wall direction t = (-n.y, n.x, 0): [span_min_m, span_max_m] of t . x.
  double span_min_m = 0.0, span_max_m = 0.0;
  double SignedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset_m; }
  // Position of p along the wall direction t = (-n.y, n.x, 0) (compare with the span).
  double Along(const Eigen::Vector3d& p) const { return -normal.y() * p.x() + normal.x() * p.y(); }
  // Whether p lies within the wall's span and height, each widened by margin_m (at any distance from
  // its plane).
  bool Spans(const Eigen::Vector3d& p, double margin_m = 0.0) const {
    const double s = Along(p);
    return s >= span_min_m - margin_m && s <= span_max_m + margin_m && p.z() >= z_min_m - margin_m &&
           p.z() <= z_max_m + margin_m;
  }
  // The point of the plane at z = 0 whose position along the wall is along_m (Along's inverse).
  Eigen::Vector3d PointAt(double along_m) const {
    return offset_m * normal + along_m * Eigen::Vector3d(-normal.y(), normal.x(), 0.0);
  }
};

struct StructureResult {
  bool has_floor = false;
  double floor_height_m = 0.0;
  double floor_area_m2 = 0.0;
  std::vector<WallPlane> walls;
  bool has_ceiling = false;
  double ceiling_height_m = 0.0;  // the lowest ceiling level
  std::size_t num_floor_elements = 0;
  std::size_t num_wall_elements = 0;
  std::size_t num_ceiling_elements = 0;

  // True when p is on the room side of every wall whose span covers it (margin in metres).
  bool InsideWalls(const Eigen::Vector3d& p, double margin_m) const;
  // True when p lies within distance_m of the floor or of a wall plane (within its span widened by
  // distance_m).
  bool OnStructure(const Eigen::Vector3d& p, double distance_m) const;
  // True when p lies within distance_m of a wall plane (within its span widened by distance_m).
  bool NearWall(const Eigen::Vector3d& p, double distance_m) const;
  // True when p, on a surface with unit normal n, lies inside a wall's thickness: behind the wall
  // plane by less than depth_m, within its span, on a face across the wall (|n . wall normal| <
  // max_cos). Such faces are the reveals of door and window openings, which belong to the wall.
  bool InWallReveal(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double depth_m, double max_cos) const;
  // True when p lies in an opening of a wall: behind its plane by more than min_depth_m and at most
  // max_depth_m, within its span and height. Nothing but what fills a door or window opening (a
  // recessed pane, a frame) is seen there: the space behind a wall is outside the room.
  bool InWallOpening(const Eigen::Vector3d& p, double min_depth_m, double max_depth_m) const {
    return WallOpeningIndex(p, min_depth_m, max_depth_m) >= 0;
  }
  // The first wall (index into walls) in whose opening p lies, as InWallOpening; -1 for none.
  int WallOpeningIndex(const Eigen::Vector3d& p, double min_depth_m, double max_depth_m) const;
  // True when at least `fraction` of the points lie within band_m of one structure plane (the floor,
  // or a wall within its span and height widened by band_m) on faces parallel to it
  // (|n . plane normal| >= cos 30 deg), and at least min_side_share of those lie on each side of the plane. That is the
  // noise tail of the floor's or a wall's surface, beyond the tolerance that tagged the plane: it
  // straddles the plane, where the surface of anything standing on the floor or in front of a wall
  // (and of a door or a window in an opening behind it) lies on one side.
  bool IsPlaneNoise(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                    double band_m, double min_side_share, double fraction) const;
};

class StructureDetector {
 public:
  explicit StructureDetector(const StructureOptions& options = StructureOptions());
  // Detects floor and walls over all elements and rewrites every element's structural tag.
  StructureResult Update(SurfaceMap* map) const;
  // Rewrites every element's structural tag from already detected planes (much cheaper than Update:
  // no plane search) and refreshes result's element counts.
  void TagElements(SurfaceMap* map, StructureResult* result) const;
  const StructureOptions& options() const { return options_; }

 private:
  StructureOptions options_;
};

}  // namespace objscan::mapping
