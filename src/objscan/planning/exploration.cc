#include "objscan/planning/exploration.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "objscan/common/error.h"

namespace objscan::planning {

void ExplorationOptions::Validate() const {
  config::RequireNonNegative("frontier_size_weight", frontier_size_weight);
  config::RequireNonNegative("travel_weight", travel_weight);
  config::Require(min_frontier_cells >= 1, "min_frontier_cells", "must be at least 1");
  config::RequireNonNegative("visited_radius_m", visited_radius_m);
  config::Require(look_around_yaw_steps >= 1, "look_around_yaw_steps", "must be at least 1");
  config::Require(!look_around_pitches_deg.empty(), "look_around_pitches_deg", "must list at least one pitch");
  for (double p : look_around_pitches_deg) config::RequireInRange("look_around_pitches_deg", p, -89.0, 89.0);
}

const char* ToString(FrontierExclusion exclusion) {
  switch (exclusion) {
    case FrontierExclusion::kNone:
      return "none";
    case FrontierExclusion::kTooSmall:
      return "too_small";
    case FrontierExclusion::kVisited:
      return "visited";
    case FrontierExclusion::kUnreachable:
      return "unreachable";
  }
  return "unknown";
}

const char* ToString(FrontierStatus status) {
  switch (status) {
    case FrontierStatus::kOk:
      return "ok";
    case FrontierStatus::kNoFrontier:
      return "no_frontier";
    case FrontierStatus::kNoReachableFrontier:
      return "no_reachable_frontier";
  }
  return "unknown";
}

const char* ToString(ScanAction action) {
  switch (action) {
    case ScanAction::kScanObject:
      return "scan_object";
    case ScanAction::kExploreFrontier:
      return "explore_frontier";
    case ScanAction::kDone:
      return "done";
    case ScanAction::kStuck:
      return "stuck";
  }
  return "unknown";
}

FrontierChoice ChooseFrontier(const std::vector<FrontierCandidate>& frontiers, const PathLengthFn& path_length,
                              const std::vector<Eigen::Vector3d>& visited_goals_world,
                              const ExplorationOptions& options) {
  FrontierChoice choice;
  choice.scores.resize(frontiers.size());
  bool any_candidate = false;
  double max_size = 0.0, max_path_m = 0.0;
  for (std::size_t i = 0; i < frontiers.size(); ++i) {
    const FrontierCandidate& f = frontiers[i];
    if (!f.centroid_world.allFinite() || f.size_cells < 0) {
      throw InputError("frontier " + std::to_string(i) + ": centroid_world must be finite and size_cells >= 0");
    }
    FrontierScore& s = choice.scores[i];
    if (f.size_cells < options.min_frontier_cells) {
      s.exclusion = FrontierExclusion::kTooSmall;
      continue;
    }
    const bool visited = std::any_of(visited_goals_world.begin(), visited_goals_world.end(), [&](const Eigen::Vector3d& g) {
      return (g - f.centroid_world).head<2>().norm() <= options.visited_radius_m;
    });
    if (visited) {
      s.exclusion = FrontierExclusion::kVisited;
      continue;
    }
    any_candidate = true;
    const std::optional<double> length_m = path_length ? path_length(f.centroid_world) : std::optional<double>();
    if (!length_m || !std::isfinite(*length_m) || *length_m < 0.0) {
      s.exclusion = FrontierExclusion::kUnreachable;
      continue;
    }
    s.path_length_m = *length_m;
    max_size = std::max(max_size, static_cast<double>(f.size_cells));
    max_path_m = std::max(max_path_m, *length_m);
  }
  if (!any_candidate) return choice;  // kNoFrontier
  choice.status = FrontierStatus::kNoReachableFrontier;
  for (std::size_t i = 0; i < frontiers.size(); ++i) {
    FrontierScore& s = choice.scores[i];
    if (s.exclusion != FrontierExclusion::kNone) continue;
    s.size_term = max_size > 0.0 ? frontiers[i].size_cells / max_size : 0.0;
    s.travel_term = std::exp(max_path_m > 0.0 ? -s.path_length_m / max_path_m : 0.0);
    s.score = options.frontier_size_weight * s.size_term + options.travel_weight * s.travel_term;
    if (choice.best_index < 0 || s.score > choice.scores[choice.best_index].score) {
      choice.best_index = static_cast<int>(i);
    }
  }
  if (choice.best_index >= 0) choice.status = FrontierStatus::kOk;
  return choice;
}

std::vector<geometry::Pose3> LookAroundViews(const Eigen::Vector3d& camera_position_world, double start_yaw_rad,
                                             const ExplorationOptions& options) {
  std::vector<geometry::Pose3> views;
  views.reserve(static_cast<std::size_t>(options.look_around_yaw_steps) * options.look_around_pitches_deg.size());
  for (int k = 0; k < options.look_around_yaw_steps; ++k) {
    const double yaw = geometry::WrapAngle(start_yaw_rad + 2.0 * M_PI * k / options.look_around_yaw_steps);
    for (double pitch_deg : options.look_around_pitches_deg) {
      views.push_back(geometry::CameraPoseFromYawPitch(camera_position_world, yaw, geometry::DegToRad(pitch_deg)));
    }
  }
  return views;
}

ScanAction DecideAction(bool has_unfinished_object, FrontierStatus frontier_status) {
  if (has_unfinished_object) return ScanAction::kScanObject;
  switch (frontier_status) {
    case FrontierStatus::kOk:
      return ScanAction::kExploreFrontier;
    case FrontierStatus::kNoFrontier:
      return ScanAction::kDone;
    case FrontierStatus::kNoReachableFrontier:
      return ScanAction::kStuck;
  }
  return ScanAction::kStuck;
}

}  // namespace objscan::planning
