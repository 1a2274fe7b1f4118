#pragma once
// Exploration and termination (Algorithm 1 of the paper plus §6 "Floor and wall"): look around in place
// first; when no unfinished object is left, go to the best floor frontier, trading its size against the
// travel to it; stop when neither objects nor frontiers are left.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/pose.h"

namespace objscan::planning {

struct ExplorationOptions {
  // score = size_weight * size / max size + travel_weight * exp(-path / max path), maxima over the
  // reachable frontiers (the same shape as the NBO's size and distance terms).
  double frontier_size_weight = 1.0;
  double travel_weight = 1.0;
  int min_frontier_cells = 5;     // smaller frontiers are map noise
  double visited_radius_m = 0.5;  // frontiers this close to an earlier frontier goal are not chosen again
  // Initial look-around: this many yaw steps over 360 degrees at each pitch.
  int look_around_yaw_steps = 8;
  std::vector<double> look_around_pitches_deg = {-35.0, 0.0};

  template <class V>
  void Visit(V& v) {
    v("frontier_size_weight", frontier_size_weight);
    v("travel_weight", travel_weight);
    v("min_frontier_cells", min_frontier_cells);
    v("visited_radius_m", visited_radius_m);
    v("look_around_yaw_steps", look_around_yaw_steps);
    v("look_around_pitches_deg", look_around_pitches_deg);
  }
  void Validate() const;
};

// A floor frontier (boundary between known free floor and unknown space).
struct FrontierCandidate {
  Eigen::Vector3d centroid_world = Eigen::Vector3d::Zero();
  int size_cells = 0;
};

// Length of the robot's path to a goal, or nullopt when the goal cannot be reached (the navigator
// answers; it may also move the goal to the nearest reachable free cell as it sees fit).
using PathLengthFn = std::function<std::optional<double>(const Eigen::Vector3d& goal_world)>;

enum class FrontierExclusion { kNone = 0, kTooSmall, kVisited, kUnreachable };
const char* ToString(FrontierExclusion exclusion);

struct FrontierScore {
  FrontierExclusion exclusion = FrontierExclusion::kNone;
  double path_length_m = 0.0;  // 0 unless queried and reachable
  double size_term = 0.0;
  double travel_term = 0.0;
  double score = 0.0;
};

enum class FrontierStatus {
  kOk = 0,
  kNoFrontier,           // nothing left to explore (all too small or visited)
  kNoReachableFrontier,  // frontiers remain but the robot cannot get to any
};
const char* ToString(FrontierStatus status);

struct FrontierChoice {
  FrontierStatus status = FrontierStatus::kNoFrontier;
  int best_index = -1;  // into the input frontiers
  std::vector<FrontierScore> scores;  // one per input frontier
};

// Picks the frontier goal. `path_length` is only asked about frontiers that pass the size and visited
// filters. Ties go to the lower index. Throws InputError on a non-finite centroid or negative size.
FrontierChoice ChooseFrontier(const std::vector<FrontierCandidate>& frontiers, const PathLengthFn& path_length,
                              const std::vector<Eigen::Vector3d>& visited_goals_world,
                              const ExplorationOptions& options);

// The look-around-in-place view set: camera poses at `camera_position_world` turning a full circle from
// `start_yaw_rad` (look_around_yaw_steps yaws, each at every pitch of look_around_pitches_deg).
std::vector<geometry::Pose3> LookAroundViews(const Eigen::Vector3d& camera_position_world, double start_yaw_rad,
                                             const ExplorationOptions& options);

enum class ScanAction {
  kScanObject = 0,   // an unfinished object is left: NBO / NBV
  kExploreFrontier,  // go to the chosen frontier
  kDone,             // no unfinished object and no frontier: terminated "done"
  kStuck,            // no unfinished object, frontiers left but none reachable: the scanner ends "done"
                     // listing them when the robot can still move, "stuck" when it cannot
};
const char* ToString(ScanAction action);

ScanAction DecideAction(bool has_unfinished_object, FrontierStatus frontier_status);

}  // namespace objscan::planning
