#include "objscan/planning/next_best_object.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_set>

#include "objscan/common/error.h"

namespace objscan::planning {

void NextBestObjectOptions::Validate() const {
  config::RequireNonNegative("objectness_weight", objectness_weight);
  config::RequireNonNegative("distance_weight", distance_weight);
  config::RequireNonNegative("orientation_weight", orientation_weight);
  config::RequireNonNegative("size_weight", size_weight);
  config::Require(max_views_per_object >= 1, "max_views_per_object", "must be at least 1");
}

const char* ToString(NboExclusion exclusion) {
  switch (exclusion) {
    case NboExclusion::kNone:
      return "none";
    case NboExclusion::kComplete:
      return "complete";
    case NboExclusion::kViewBudgetSpent:
      return "view_budget_spent";
  }
  return "unknown";
}

const char* ToString(NboStatus status) {
  switch (status) {
    case NboStatus::kOk:
      return "ok";
    case NboStatus::kNoCandidate:
      return "no_candidate";
  }
  return "unknown";
}

namespace {

void CheckObject(const NboObject& o) {
  const std::string which = "nbo object " + std::to_string(o.id);
  if (!std::isfinite(o.objectness)) throw InputError(which + ": objectness is not finite");
  if (!o.center_world.allFinite()) throw InputError(which + ": center_world is not finite");
  if (!std::isfinite(o.area_m2) || o.area_m2 < 0.0) throw InputError(which + ": area_m2 must be finite and >= 0");
  if (o.views_spent < 0) throw InputError(which + ": views_spent must be >= 0");
}

}  // namespace

NboResult SelectNextBestObject(const std::vector<NboObject>& objects, const RobotView& robot, int current_ooi_id,
                               const NextBestObjectOptions& options) {
  if (!robot.position_world.allFinite() || !robot.view_direction_world.allFinite()) {
    throw InputError("nbo robot view: position_world / view_direction_world is not finite");
  }
  NboResult result;
  result.scores.resize(objects.size());
  std::unordered_set<int> seen_ids;
  double max_distance_m = 0.0;
  double max_area_m2 = 0.0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const NboObject& o = objects[i];
    CheckObject(o);
    if (!seen_ids.insert(o.id).second) throw InputError("nbo objects: duplicate id " + std::to_string(o.id));
    NboScore& s = result.scores[i];
    s.id = o.id;
    if (o.complete) {
      s.exclusion = NboExclusion::kComplete;
    } else if (o.views_spent >= options.max_views_per_object) {
      s.exclusion = NboExclusion::kViewBudgetSpent;
      result.budget_spent_ids.push_back(o.id);
    }
    if (s.exclusion != NboExclusion::kNone) continue;
    max_distance_m = std::max(max_distance_m, (o.center_world - robot.position_world).norm());
    max_area_m2 = std::max(max_area_m2, o.area_m2);
  }

  const double view_norm = robot.view_direction_world.norm();
  int best = -1;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    NboScore& s = result.scores[i];
    if (s.exclusion != NboExclusion::kNone) continue;
    const NboObject& o = objects[i];
    const Eigen::Vector3d to_object = o.center_world - robot.position_world;
    const double distance_m = to_object.norm();
    s.objectness = o.objectness;
    // All objects at P: every ratio is 0/0; they are equally near.
    s.distance_term = std::exp(max_distance_m > 0.0 ? -distance_m / max_distance_m : 0.0);
    // An object centred exactly at P has no direction: neutral orientation.
    s.orientation_term = (distance_m > 0.0 && view_norm > 0.0) ? to_object.dot(robot.view_direction_world) /
                                                                     (distance_m * view_norm)
                                                               : 0.0;
    s.size_term = max_area_m2 > 0.0 ? o.area_m2 / max_area_m2 : 0.0;
    s.score = options.objectness_weight * s.objectness + options.distance_weight * s.distance_term +
              options.orientation_weight * s.orientation_term + options.size_weight * s.size_term;
    if (best < 0) {
      best = static_cast<int>(i);
      continue;
    }
    const NboScore& b = result.scores[best];
    if (s.score > b.score || (s.score == b.score && s.id < b.id)) best = static_cast<int>(i);
  }

  if (best < 0) return result;  // kNoCandidate
  result.status = NboStatus::kOk;
  result.chosen_id = result.scores[best].id;
  if (options.keep_current_object && current_ooi_id >= 0) {
    for (const NboScore& s : result.scores) {
      if (s.id == current_ooi_id && s.exclusion == NboExclusion::kNone) {
        result.chosen_id = current_ooi_id;
        result.kept_current = true;
        break;
      }
    }
  }
  return result;
}

}  // namespace objscan::planning
