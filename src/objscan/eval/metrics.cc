#include "objscan/eval/metrics.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/segmentation/segmentation_quality.h"

namespace objscan::eval {

int MajorityInstance(const std::vector<int>& point_instances) {
  if (point_instances.empty()) return world::kNoInstance;
  std::vector<int> sorted = point_instances;
  std::sort(sorted.begin(), sorted.end());
  int best = sorted.front();
  std::size_t best_count = 0;
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i;
    while (j < sorted.size() && sorted[j] == sorted[i]) ++j;
    if (j - i > best_count) {  // strict: ties keep the smaller id, seen first
      best_count = j - i;
      best = sorted[i];
    }
    i = j;
  }
  return best;
}

std::vector<ObjectInstanceShare> ObjectInstanceShares(const std::vector<int>& point_object,
                                                      const std::vector<int>& point_instance, int num_objects) {
  if (point_object.size() != point_instance.size()) {
    throw InputError("ObjectInstanceShares: " + std::to_string(point_object.size()) + " object ids for " +
                     std::to_string(point_instance.size()) + " instance ids");
  }
  std::vector<std::map<int, int>> votes(static_cast<std::size_t>(std::max(0, num_objects)));
  std::map<int, int> instance_points;
  for (std::size_t i = 0; i < point_object.size(); ++i) {
    const int instance = point_instance[i];
    if (instance > 0) ++instance_points[instance];
    const int object = point_object[i];
    if (object < 0) continue;
    if (object >= num_objects) {
      throw InputError("ObjectInstanceShares: object index " + std::to_string(object) + " of " +
                       std::to_string(num_objects) + " objects");
    }
    if (instance > 0) ++votes[static_cast<std::size_t>(object)][instance];
  }
  std::vector<ObjectInstanceShare> shares(votes.size());
  for (std::size_t o = 0; o < votes.size(); ++o) {
    int best = 0;
    for (const auto& [instance, n] : votes[o]) {  // ascending ids: a tie keeps the smaller
      if (n > best) {
        best = n;
        shares[o].instance = instance;
        shares[o].share = static_cast<double>(n) / instance_points[instance];
      }
    }
  }
  return shares;
}

bool IsScoredCategory(world::Category category) {
  return !world::IsStructural(category) && category != world::Category::kOther;
}

RecognitionResult MatchRecognitions(const std::vector<GroundTruthInstance>& ground_truth,
                                    const std::vector<OutputObject>& outputs,
                                    const std::vector<world::Category>& database_categories) {
  std::array<bool, world::kNumCategories> known{};
  for (world::Category c : database_categories) known[static_cast<std::size_t>(world::CategoryId(c))] = true;

  std::unordered_map<int, const GroundTruthInstance*> instance_by_id;
  RecognitionResult result;
  for (const GroundTruthInstance& g : ground_truth) {
    if (!instance_by_id.emplace(g.instance_id, &g).second) {
      throw InputError("MatchRecognitions: duplicate ground-truth instance id " + std::to_string(g.instance_id));
    }
  }
  auto in_set = [&](const GroundTruthInstance& g) {
    return IsScoredCategory(g.category) && known[static_cast<std::size_t>(world::CategoryId(g.category))];
  };
  for (const GroundTruthInstance& g : ground_truth) {
    if (!in_set(g)) continue;
    ++result.all.ground_truth;
    if (g.on_floor) ++result.floor.ground_truth;
    ++result.per_category[static_cast<std::size_t>(world::CategoryId(g.category))].ground_truth;
  }

  std::unordered_set<int> matched;
  result.output_is_true_positive.assign(outputs.size(), false);
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const OutputObject& out = outputs[o];
    if (!IsScoredCategory(out.category)) {
      throw std::invalid_argument(std::string("MatchRecognitions: an output of category ") +
                                  world::CategoryName(out.category) + " (not a scored category)");
    }
    ++result.all.outputs;
    ++result.per_category[static_cast<std::size_t>(world::CategoryId(out.category))].outputs;
    auto it = instance_by_id.find(out.majority_instance);
    const GroundTruthInstance* g = it == instance_by_id.end() ? nullptr : it->second;
    const bool on_floor = g != nullptr && g->on_floor;
    if (on_floor) ++result.floor.outputs;
    if (g == nullptr || !in_set(*g) || g->category != out.category || matched.count(g->instance_id)) continue;
    matched.insert(g->instance_id);
    result.output_is_true_positive[o] = true;
    ++result.all.true_positives;
    if (on_floor) ++result.floor.true_positives;
    ++result.per_category[static_cast<std::size_t>(world::CategoryId(g->category))].true_positives;
  }
  result.matched_instances.assign(matched.begin(), matched.end());
  std::sort(result.matched_instances.begin(), result.matched_instances.end());
  return result;
}

double NonStructuralRandIndex(const std::vector<std::int32_t>& point_segment,
                              const std::vector<std::int32_t>& point_instance,
                              const std::vector<GroundTruthInstance>& ground_truth) {
  if (point_segment.size() != point_instance.size()) {
    throw InputError("NonStructuralRandIndex: " + std::to_string(point_segment.size()) + " segment ids for " +
                     std::to_string(point_instance.size()) + " points");
  }
  std::unordered_set<int> object_instances;
  for (const GroundTruthInstance& g : ground_truth) {
    if (!world::IsStructural(g.category)) object_instances.insert(g.instance_id);
  }
  std::vector<std::int32_t> kept_segment;
  std::vector<std::int32_t> kept_instance;
  for (std::size_t i = 0; i < point_segment.size(); ++i) {
    if (!object_instances.count(point_instance[i])) continue;
    kept_segment.push_back(point_segment[i]);
    kept_instance.push_back(point_instance[i]);
  }
  return segmentation::RandIndex(kept_segment, kept_instance);
}

void CoverageOptions::Validate() const {
  config::RequirePositive("sigma", sigma);
  config::RequirePositive("theta_t_rad", theta_t_rad);
  config::RequireNonNegative("min_range_m", min_range_m);
  config::RequirePositive("max_range_m", max_range_m);
  config::Require(min_range_m < max_range_m, "min_range_m", "must be below max_range_m");
}

namespace {

bool InRange(double distance_m, const CoverageOptions& options) {
  return distance_m >= options.min_range_m && distance_m <= options.max_range_m;
}

}  // namespace

double ViewQuality(const SurfaceVoxel& voxel, const Eigen::Vector3d& camera_position_world,
                   const CoverageOptions& options) {
  const Eigen::Vector3d to_camera = camera_position_world - voxel.center_world;
  const double d = to_camera.norm();
  if (!InRange(d, options) || d <= 0.0) return 0.0;
  const double n_norm = voxel.normal_world.norm();
  // Angle between the normal line and the line of sight, in [0, pi/2]: normals of voxels need not be
  // oriented, and a voxel seen at all is seen from its front.
  const double cos_theta =
      n_norm > 0.0 ? std::min(1.0, std::abs(voxel.normal_world.dot(to_camera)) / (n_norm * d)) : 1.0;
  const double theta = std::acos(cos_theta);
  const double s2 = options.sigma * options.sigma;
  const double d_t = options.max_range_m;
  return std::exp(-theta * theta / (s2 * options.theta_t_rad)) *
         std::exp(-(d - options.min_range_m) * (d - options.min_range_m) / (s2 * d_t));
}

CoverageAccumulator::CoverageAccumulator(std::vector<SurfaceVoxel> voxels, CoverageOptions options)
    : voxels_(std::move(voxels)), options_(options), best_quality_(voxels_.size(), -1.0) {
  options_.Validate();
}

void CoverageAccumulator::AddView(const Eigen::Vector3d& camera_position_world, const std::vector<int>& seen_voxels) {
  for (int v : seen_voxels) {
    if (v < 0 || static_cast<std::size_t>(v) >= voxels_.size()) {
      throw InputError("CoverageAccumulator: voxel index " + std::to_string(v) + " out of range");
    }
    const SurfaceVoxel& voxel = voxels_[static_cast<std::size_t>(v)];
    const double d = (camera_position_world - voxel.center_world).norm();
    if (!InRange(d, options_)) continue;
    best_quality_[static_cast<std::size_t>(v)] =
        std::max(best_quality_[static_cast<std::size_t>(v)], ViewQuality(voxel, camera_position_world, options_));
  }
}

CoverageResult CoverageAccumulator::Result(const std::vector<int>& detected_instances) const {
  const std::unordered_set<int> detected(detected_instances.begin(), detected_instances.end());
  CoverageResult r;
  r.num_voxels = static_cast<int>(voxels_.size());
  double quality_sum = 0.0;
  for (std::size_t v = 0; v < voxels_.size(); ++v) {
    if (best_quality_[v] < 0.0) continue;
    ++r.num_visible;
    if (!detected.count(voxels_[v].instance)) continue;
    ++r.num_covered;
    quality_sum += best_quality_[v];
  }
  if (r.num_voxels > 0) {
    r.rate = static_cast<double>(r.num_covered) / r.num_voxels;
    r.quality = quality_sum / r.num_voxels;
  }
  return r;
}

std::vector<InstanceCoverage> CoverageAccumulator::PerInstance() const {
  std::map<int, InstanceCoverage> by_instance;
  for (std::size_t v = 0; v < voxels_.size(); ++v) {
    InstanceCoverage& c = by_instance[voxels_[v].instance];
    c.instance = voxels_[v].instance;
    ++c.num_voxels;
    if (best_quality_[v] >= 0.0) ++c.num_visible;
  }
  std::vector<InstanceCoverage> out;
  out.reserve(by_instance.size());
  for (const auto& [id, c] : by_instance) out.push_back(c);
  return out;
}

CoverageResult ComputeCoverage(const std::vector<SurfaceVoxel>& voxels,
                               const std::vector<Eigen::Vector3d>& camera_positions_world,
                               const std::vector<std::vector<int>>& seen_voxels_per_camera,
                               const std::vector<int>& detected_instances, const CoverageOptions& options) {
  if (camera_positions_world.size() != seen_voxels_per_camera.size()) {
    throw InputError("ComputeCoverage: " + std::to_string(camera_positions_world.size()) + " cameras but " +
                     std::to_string(seen_voxels_per_camera.size()) + " seen-voxel lists");
  }
  CoverageAccumulator accumulator(voxels, options);
  for (std::size_t c = 0; c < camera_positions_world.size(); ++c) {
    accumulator.AddView(camera_positions_world[c], seen_voxels_per_camera[c]);
  }
  return accumulator.Result(detected_instances);
}

}  // namespace objscan::eval
