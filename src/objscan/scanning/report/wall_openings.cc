#include "objscan/scanning/report/wall_openings.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>

#include "objscan/common/union_find.h"
#include "objscan/mapping/planes.h"

namespace objscan::scanning {

namespace {
constexpr double kLowestQuantile = 0.02;

// The value at fraction f (in [0, 1]) of the sorted, non-empty values (reorders them).
template <class T>
T Quantile(double f, std::vector<T>* values) {
  const auto it = values->begin() + static_cast<std::ptrdiff_t>(f * static_cast<double>(values->size() - 1));
  std::nth_element(values->begin(), it, values->end());
  return *it;
}

void ExtendOnWall(const mapping::WallPlane& wall, const Eigen::Vector3d& p, OpeningExtent* extent) {
  const double along = wall.Along(p);
  extent->along_min_m = std::min(extent->along_min_m, along);
  extent->along_max_m = std::max(extent->along_max_m, along);
  extent->z_min_m = std::min(extent->z_min_m, p.z());
  extent->z_max_m = std::max(extent->z_max_m, p.z());
}
}  // namespace

void WallOpeningOptions::Validate() const {
  config::RequireNonNegative("report.wall_openings.min_depth_m", min_depth_m);
  config::Require(max_depth_m > min_depth_m, "report.wall_openings.max_depth_m", "must be > min_depth_m");
  config::RequireInRange("report.wall_openings.window_min_share", window_min_share, 0.0, 1.0);
  config::RequireInRange("report.wall_openings.window_keep_share", window_keep_share, 0.0, 1.0);
  config::Require(window_keep_share <= window_min_share, "report.wall_openings.window_keep_share",
                  "must be <= window_min_share");
  config::RequireNonNegative("report.wall_openings.min_sill_height_m", min_sill_height_m);
  config::Require(std::isfinite(hanging_window_max_distance_m), "report.wall_openings.hanging_window_max_distance_m",
                  "must be a number (negative = off)");
  config::RequireInRange("report.wall_openings.hanging_window_min_share", hanging_window_min_share, 0.0, 1.0);
  config::RequireNonNegative("report.wall_openings.join_gap_m", join_gap_m);
  config::RequireNonNegative("report.wall_openings.curtain_max_distance_m", curtain_max_distance_m);
  config::RequireInRange("report.wall_openings.curtain_min_share", curtain_min_share, 0.0, 1.0);
  config::RequireNonNegative("report.wall_openings.curtain_min_height_m", curtain_min_height_m);
  config::RequireNonNegative("report.wall_openings.curtain_min_overlap_m", curtain_min_overlap_m);
  config::RequireNonNegative("report.wall_openings.curtain_min_fold_depth_m", curtain_min_fold_depth_m);
  config::Require(curtain_max_fold_depth_m >= curtain_min_fold_depth_m, "report.wall_openings.curtain_max_fold_depth_m",
                  "must be >= curtain_min_fold_depth_m");
  config::RequireNonNegative("report.wall_openings.door_max_depth_m", door_max_depth_m);
}

double MinHorizontalWidth(const std::vector<Eigen::Vector3f>& points_world) {
  if (points_world.empty()) return 0.0;
  constexpr int kSteps = 180;  // directions 1° apart over half a turn
  const double kPi = 3.14159265358979323846;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kSteps; ++k) {
    const double yaw = kPi * k / kSteps;
    const float c = static_cast<float>(std::cos(yaw)), sn = static_cast<float>(std::sin(yaw));
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const Eigen::Vector3f& p : points_world) {
      const float u = c * p.x() + sn * p.y();
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
    best = std::min(best, static_cast<double>(hi - lo));
  }
  return best;
}

bool TooDeepForADoor(const std::vector<Eigen::Vector3f>& points_world, const WallOpeningOptions& options) {
  if (points_world.empty()) return false;
  return MinHorizontalWidth(points_world) > options.door_max_depth_m;
}

WallOpeningResult ClassifyWallOpening(const std::vector<Eigen::Vector3f>& points_world,
                                      const mapping::StructureResult& structure, bool labelled_window,
                                      const WallOpeningOptions& options) {
  WallOpeningResult result;
  if (points_world.empty() || structure.walls.empty()) return result;
  std::size_t in_openings = 0;
  std::vector<float> heights;
  heights.reserve(points_world.size());
  for (const Eigen::Vector3f& p : points_world) {
    heights.push_back(p.z());
    if (structure.InWallOpening(p.cast<double>(), options.min_depth_m, options.max_depth_m)) ++in_openings;
  }
  result.share = static_cast<double>(in_openings) / static_cast<double>(points_world.size());
  // The lowest point but a few: strips of wall or floor left at an object's border do not make it
  // reach the floor.
  const double low = Quantile(kLowestQuantile, &heights);
  const double floor_z = structure.has_floor ? structure.floor_height_m : 0.0;
  const bool off_floor = low - floor_z >= options.min_sill_height_m;
  if (off_floor && result.share >= options.window_min_share) {
    result.verdict = WallOpeningVerdict::kWindow;
  } else if (labelled_window && !off_floor && result.share >= options.window_keep_share &&
             options.doorways_are_not_windows) {
    result.verdict = WallOpeningVerdict::kNotWindow;  // in an opening down to the floor: a doorway
  } else if (labelled_window && result.share < options.window_keep_share) {
    const bool hangs_on_wall = off_floor && options.hanging_window_max_distance_m >= 0.0 &&
                               HangingWall(points_world, structure, options.min_depth_m,
                                           options.hanging_window_max_distance_m, options.hanging_window_min_share) >= 0;
    if (!hangs_on_wall) result.verdict = WallOpeningVerdict::kNotWindow;
  }
  return result;
}

OpeningExtent OpeningBounds(const std::vector<Eigen::Vector3f>& points_world, const mapping::StructureResult& structure,
                            const WallOpeningOptions& options) {
  OpeningExtent extent;
  if (structure.walls.empty()) return extent;
  // The wall whose opening holds each point, -1 for none.
  std::vector<int> wall_of(points_world.size(), -1);
  std::vector<std::size_t> count(structure.walls.size(), 0);
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    wall_of[i] = structure.WallOpeningIndex(points_world[i].cast<double>(), options.min_depth_m, options.max_depth_m);
    if (wall_of[i] >= 0) ++count[static_cast<std::size_t>(wall_of[i])];
  }
  const auto most = std::max_element(count.begin(), count.end());
  if (*most == 0) return extent;
  extent.wall = static_cast<int>(most - count.begin());
  const mapping::WallPlane& wall = structure.walls[static_cast<std::size_t>(extent.wall)];
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    if (wall_of[i] != extent.wall) continue;
    extent.bounds.Extend(points_world[i].cast<double>());
    ExtendOnWall(wall, points_world[i].cast<double>(), &extent);
  }
  return extent;
}

namespace {

// Whether p lies in front of `wall` by at most max_distance_m (behind it by at most min_depth_m),
// within its span.
bool HangsInFront(const mapping::WallPlane& wall, const Eigen::Vector3d& p, double min_depth_m, double max_distance_m) {
  const double d = wall.SignedDistance(p), s = wall.Along(p);
  return d >= -min_depth_m && d <= max_distance_m && s >= wall.span_min_m && s <= wall.span_max_m;
}

}  // namespace

int HangingWall(const std::vector<Eigen::Vector3f>& points_world, const mapping::StructureResult& structure,
                double min_depth_m, double max_distance_m, double min_share) {
  if (points_world.empty()) return -1;
  for (std::size_t w = 0; w < structure.walls.size(); ++w) {
    std::size_t near = 0;
    for (const Eigen::Vector3f& p : points_world) {
      near += HangsInFront(structure.walls[w], p.cast<double>(), min_depth_m, max_distance_m) ? 1 : 0;
    }
    // Walls meet at corners, where an object may hang in front of two; the first that holds it wins.
    if (near > 0 && static_cast<double>(near) >= min_share * static_cast<double>(points_world.size())) {
      return static_cast<int>(w);
    }
  }
  return -1;
}

bool MayBeCurtain(const std::optional<world::Category>& label, double wall_opening_share,
                  const WallOpeningOptions& options) {
  if (!label || *label == world::Category::kDoor || *label == world::Category::kCurtain) return true;
  return *label == world::Category::kWindow && wall_opening_share < options.window_keep_share;
}

bool CurtainLabelGoes(const std::optional<world::Category>& label, const OpeningExtent& hanging,
                      const WallOpeningOptions& options) {
  if (label != world::Category::kCurtain) return false;
  return hanging.wall < 0 || hanging.fold_depth_m > options.curtain_max_fold_depth_m;
}

OpeningExtent HangingExtent(const std::vector<Eigen::Vector3f>& points_world,
                            const mapping::StructureResult& structure, const WallOpeningOptions& options) {
  OpeningExtent extent;
  if (points_world.empty()) return extent;
  const int w = HangingWall(points_world, structure, options.min_depth_m, options.curtain_max_distance_m,
                            options.curtain_min_share);
  if (w >= 0) {
    const mapping::WallPlane& wall = structure.walls[static_cast<std::size_t>(w)];
    const auto hangs = [&](const Eigen::Vector3d& p) {
      return HangsInFront(wall, p, options.min_depth_m, options.curtain_max_distance_m);
    };
    extent.wall = w;
    std::vector<double> distances;
    distances.reserve(points_world.size());
    for (const Eigen::Vector3f& pf : points_world) {
      const Eigen::Vector3d p = pf.cast<double>();
      if (!hangs(p)) continue;
      ExtendOnWall(wall, p, &extent);
      distances.push_back(wall.SignedDistance(p));
    }
    // The spread of the middle half: the depth of the folds of a pleated face (a flat one's is the
    // sensor's noise and its panels').
    extent.fold_depth_m = Quantile(0.75, &distances) - Quantile(0.25, &distances);
  }
  return extent;
}

int CurtainWindow(const OpeningExtent& hanging, const std::vector<OpeningExtent>& windows,
                  const WallOpeningOptions& options) {
  if (hanging.wall < 0) return -1;
  if (hanging.z_max_m - hanging.z_min_m < options.curtain_min_height_m) return -1;
  if (hanging.fold_depth_m < options.curtain_min_fold_depth_m || hanging.fold_depth_m > options.curtain_max_fold_depth_m) {
    return -1;
  }
  for (std::size_t k = 0; k < windows.size(); ++k) {
    const OpeningExtent& w = windows[k];
    if (w.wall != hanging.wall) continue;
    const double along = std::min(w.along_max_m, hanging.along_max_m) - std::max(w.along_min_m, hanging.along_min_m);
    const double height = std::min(w.z_max_m, hanging.z_max_m) - std::max(w.z_min_m, hanging.z_min_m);
    if (along >= options.curtain_min_overlap_m && height > 0.0) return static_cast<int>(k);
  }
  return -1;
}

std::vector<int> JoinWindowPieces(const std::vector<WindowPiece>& pieces, double gap_m) {
  const int n = static_cast<int>(pieces.size());
  UnionFind windows(n);
  for (int a = 0; gap_m >= 0.0 && a < n; ++a) {
    const WindowPiece& pa = pieces[static_cast<std::size_t>(a)];
    if (!pa.window || pa.opening.wall < 0 || pa.opening.bounds.Empty()) continue;
    for (int b = a + 1; b < n; ++b) {
      const WindowPiece& pb = pieces[static_cast<std::size_t>(b)];
      if (!pb.window || pb.opening.wall != pa.opening.wall || pb.opening.bounds.Empty()) continue;
      if (pa.opening.bounds.Touches(pb.opening.bounds, gap_m)) windows.Union(a, b);
    }
  }
  std::vector<int> group(pieces.size());
  for (int i = 0; i < n; ++i) group[static_cast<std::size_t>(i)] = windows.Find(i);
  return HostsOfGroups(group, pieces);
}

std::vector<int> HostsOfGroups(const std::vector<int>& group, const std::vector<WindowPiece>& pieces) {
  const int n = static_cast<int>(pieces.size());
  // Whether a should host b: a complete piece first, then the one with more points, then the lower index.
  const auto hosts = [&pieces](int a, int b) {
    const WindowPiece& pa = pieces[static_cast<std::size_t>(a)];
    const WindowPiece& pb = pieces[static_cast<std::size_t>(b)];
    if (pa.complete != pb.complete) return pa.complete;
    if (pa.num_points != pb.num_points) return pa.num_points > pb.num_points;
    return a < b;
  };
  std::map<int, int> host_of_group;
  for (int i = 0; i < n; ++i) {
    const int g = group[static_cast<std::size_t>(i)];
    if (g < 0) continue;
    const auto [it, first] = host_of_group.emplace(g, i);
    if (!first && hosts(i, it->second)) it->second = i;
  }
  std::vector<int> host(pieces.size());
  for (int i = 0; i < n; ++i) {
    const int g = group[static_cast<std::size_t>(i)];
    host[static_cast<std::size_t>(i)] = g < 0 ? i : host_of_group.at(g);
  }
  return host;
}

}  // namespace objscan::scanning
