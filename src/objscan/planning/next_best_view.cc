#include "objscan/planning/next_best_view.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include "objscan/common/error.h"
#include "objscan/geometry/aabb.h"
#include "objscan/planning/information_gain.h"
#include "objscan/planning/tdf.h"
#include "objscan/planning/voxel_traversal.h"

namespace objscan::planning {

namespace {

constexpr int kMaxModels = 15;            // one bit each beside the scene bit in a uint16 mask
constexpr std::uint16_t kSceneBit = 1;
// Per-voxel gains this small are rounding noise of candidates that agree at the voxel.
constexpr double kNegligibleGainNats = 1e-10;

void ExtendChecked(const std::vector<Eigen::Vector3f>& points, const std::string& what, geometry::Aabb3* box) {
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) throw InputError(what + ": non-finite point");
    box->Extend(p.cast<double>());
  }
}

geometry::Aabb3 CheckedBounds(const NextBestViewInput& input) {
  if (input.gamma_points_world == nullptr || input.gamma_points_world->empty()) {
    throw InputError("nbv input: gamma_points_world is empty");
  }
  if (static_cast<int>(input.models.size()) > kMaxModels) {
    throw InputError("nbv input: models holds " + std::to_string(input.models.size()) + " candidates, at most " +
                     std::to_string(kMaxModels) + " are supported");
  }
  geometry::Aabb3 box;
  ExtendChecked(*input.gamma_points_world, "nbv input: gamma_points_world", &box);
  for (std::size_t i = 0; i < input.models.size(); ++i) {
    const std::string what = "nbv input: models[" + std::to_string(i) + "].points_world";
    if (input.models[i].points_world == nullptr) throw InputError(what + " is null");
    ExtendChecked(*input.models[i].points_world, what, &box);
  }
  return box;
}

}  // namespace

void NextBestViewOptions::Validate() const {
  candidates.Validate();
  config::RequirePositive("voxel_size_m", voxel_size_m);
  config::RequireInRange("blur_sigma_voxels", blur_sigma_voxels, 0.0, 10.0);
  config::Require(tdf_epsilon > 0.0 && tdf_epsilon < 1.0, "tdf_epsilon", "must be in (0, 1)");
  config::RequireNonNegative("occlusion_tolerance_voxels", occlusion_tolerance_voxels);
  config::RequireNonNegative("grid_padding_m", grid_padding_m);
  config::Require(max_grid_voxels >= 1000, "max_grid_voxels", "must be at least 1000");
  config::Require(threads >= 0, "threads", "must be >= 0 (0 = hardware concurrency)");
}

const char* ToString(NbvStatus status) {
  switch (status) {
    case NbvStatus::kOk:
      return "ok";
    case NbvStatus::kNoValidView:
      return "no_valid_view";
  }
  return "unknown";
}

NextBestView::NextBestView(const NextBestViewOptions& options) : options_(options) { options_.Validate(); }

void NextBestView::Prepare(const NextBestViewInput& input, const geometry::Aabb3& bounds,
                           NextBestViewResult* summary) {
  const int n = static_cast<int>(input.models.size());
  std::vector<double> objectness(n);
  for (int i = 0; i < n; ++i) objectness[i] = input.models[i].objectness;
  probabilities_ = CandidateProbabilities(objectness);
  const double prior_entropy = Entropy(probabilities_.data(), n);

  const bool count_surface = input.gain_measure == ViewGainMeasure::kUnobservedSurface;
  const double padding_m = BlurRadiusVoxels(options_.blur_sigma_voxels) * options_.voxel_size_m + options_.grid_padding_m;
  grid_ = LocalGrid::Covering(bounds, options_.voxel_size_m, padding_m,
                              static_cast<std::size_t>(options_.max_grid_voxels));
  const std::size_t num_voxels = grid_.NumVoxels();

  // Indicators and occupancy bits in one pass over each point set, then the blur (the TDFs).
  mask_.assign(num_voxels, 0);
  if (input.occluder_points_world != nullptr) {
    RasterizeIndicatorAndMask(grid_, *input.occluder_points_world, nullptr, kSceneBit, &mask_);
  }
  gamma_tdf_.assign(num_voxels, 0.0f);
  RasterizeIndicatorAndMask(grid_, *input.gamma_points_world, &gamma_tdf_, kSceneBit, &mask_);
  GaussianBlur3d(grid_, options_.blur_sigma_voxels, &gamma_tdf_, &scratch_);
  model_tdfs_.resize(static_cast<std::size_t>(n) * num_voxels);
  std::vector<float> field;
  for (int i = 0; i < n; ++i) {
    field.assign(num_voxels, 0.0f);
    RasterizeIndicatorAndMask(grid_, *input.models[i].points_world, &field,
                              static_cast<std::uint16_t>(1u << (i + 1)), &mask_);
    GaussianBlur3d(grid_, options_.blur_sigma_voxels, &field, &scratch_);
    std::copy(field.begin(), field.end(), model_tdfs_.begin() + static_cast<std::ptrdiff_t>(i * num_voxels));
  }

  ChebyshevFreeDistance(grid_.nx, grid_.ny, grid_.nz, mask_.data(), &free_distance_);
  occupancy_ = VoxelOccupancy::Of(grid_.nx, grid_.ny, grid_.nz, mask_.data(), free_distance_.data());

  // Per-voxel entropies once; every voxel of some Delta_i keeps the gains H(x) - H(x | m_i) of all models.
  delta_.clear();
  delta_gains_.clear();
  const float eps = static_cast<float>(options_.tdf_epsilon);
  std::vector<float> f(n);
  std::vector<float> gains(n);
  std::size_t v = 0;
  for (int z = 0; z < grid_.nz; ++z) {
    for (int y = 0; y < grid_.ny; ++y) {
      for (int x = 0; x < grid_.nx; ++x, ++v) {
        if (gamma_tdf_[v] > eps) continue;
        bool any = false;
        for (int k = 0; k < n; ++k) {
          f[k] = model_tdfs_[k * num_voxels + v];
          any = any || f[k] > eps;
        }
        if (!any) continue;
        double h0 = 0.0, h1 = 0.0;
        if (!count_surface) OutcomeEntropies(probabilities_.data(), f.data(), n, prior_entropy, &h0, &h1);
        std::uint16_t models = 0;
        for (int k = 0; k < n; ++k) {
          gains[k] = 0.0f;
          if (f[k] <= eps) continue;
          const double gain = count_surface ? 1.0 : prior_entropy - ConditionalEntropy(f[k], h0, h1);
          if (std::abs(gain) <= kNegligibleGainNats) continue;
          gains[k] = static_cast<float>(gain);
          models |= static_cast<std::uint16_t>(1u << (k + 1));
        }
        if (models == 0) continue;
        delta_.push_back(DeltaVoxel{static_cast<std::int16_t>(x), static_cast<std::int16_t>(y),
                                    static_cast<std::int16_t>(z), models});
        delta_gains_.insert(delta_gains_.end(), gains.begin(), gains.end());
      }
    }
  }

  if (summary != nullptr) {
    summary->target_world = bounds.Center();
    summary->radius_m = 0.5 * bounds.Diagonal();
    summary->model_probabilities = probabilities_;
    summary->prior_entropy_nats = prior_entropy;
    summary->grid = grid_;
    summary->delta_voxels = static_cast<int>(delta_.size());
  }
}

ViewGain NextBestView::Evaluate(const geometry::Pose3& T_world_camera, const CameraFrustum& frustum) const {
  const int n = static_cast<int>(probabilities_.size());
  ViewGain out;
  out.gain_per_model.assign(n, 0.0);
  out.visible_voxels_per_model.assign(n, 0);
  const Eigen::Matrix3d R_camera_world = T_world_camera.linear().transpose();
  const Eigen::Vector3d eye_world = T_world_camera.translation();
  const Eigen::Vector3d eye_grid = grid_.ToGrid(eye_world);
  for (std::size_t e = 0; e < delta_.size(); ++e) {
    const DeltaVoxel& d = delta_[e];
    const Eigen::Vector3d p_camera = R_camera_world * (grid_.CenterOf(d.x, d.y, d.z) - eye_world);
    if (!frustum.Contains(p_camera)) continue;
    // One walk serves every model: the scene surface hides the voxel from all of them, a model's own
    // voxels only from that model.
    const std::uint16_t blocked =
        BlockingBits(occupancy_, eye_grid, d.x, d.y, d.z, options_.occlusion_tolerance_voxels, kSceneBit, d.models);
    if (blocked & kSceneBit) continue;
    const std::uint16_t visible = d.models & static_cast<std::uint16_t>(~blocked);
    if (visible == 0) continue;
    const float* gains = &delta_gains_[e * n];
    for (int i = 0; i < n; ++i) {
      if (visible & (1u << (i + 1))) {
        out.gain_per_model[i] += gains[i];
        ++out.visible_voxels_per_model[i];
      }
    }
  }
  for (int i = 0; i < n; ++i) out.gain += probabilities_[i] * out.gain_per_model[i];
  return out;
}

std::vector<ViewGain> NextBestView::EvaluateViews(const NextBestViewInput& input,
                                                  const std::vector<geometry::Pose3>& T_world_cameras) {
  Prepare(input, CheckedBounds(input), nullptr);
  std::vector<ViewGain> gains;
  gains.reserve(T_world_cameras.size());
  for (const geometry::Pose3& T : T_world_cameras) gains.push_back(Evaluate(T, input.frustum));
  return gains;
}

NextBestViewResult NextBestView::Plan(const NextBestViewInput& input, const ViewValidator* validator) {
  NextBestViewResult result;
  const geometry::Aabb3 bounds = CheckedBounds(input);
  result.target_world = bounds.Center();
  result.radius_m = 0.5 * bounds.Diagonal();
  std::vector<geometry::Pose3> poses =
      GenerateViewCandidates(result.target_world, result.radius_m, input.frustum, options_.candidates);
  // Where each candidate looks (its line of sight is checked to there).
  std::vector<Eigen::Vector3d> looks_at(poses.size(), result.target_world);
  if (input.aim_points_world != nullptr && !input.aim_points_world->empty()) {
    geometry::Aabb3 aim;
    ExtendChecked(*input.aim_points_world, "nbv input: aim_points_world", &aim);
    const std::vector<geometry::Pose3> aimed =
        GenerateViewCandidates(aim.Center(), 0.5 * aim.Diagonal(), input.frustum, options_.candidates);
    poses.insert(poses.end(), aimed.begin(), aimed.end());
    looks_at.resize(poses.size(), aim.Center());
  }
  result.candidates.resize(poses.size());
  bool any_valid = false;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    ViewCandidate& c = result.candidates[j];
    c.T_world_camera = poses[j];
    c.validity = validator != nullptr ? validator->Check(poses[j], looks_at[j]) : ViewValidity::kValid;
    c.gain.gain_per_model.assign(input.models.size(), 0.0);
    c.gain.visible_voxels_per_model.assign(input.models.size(), 0);
    any_valid = any_valid || c.validity == ViewValidity::kValid;
  }
  if (!any_valid) return result;  // kNoValidView

  Prepare(input, bounds, &result);
  // Candidates are independent and Evaluate only reads the prepared grids: score them in parallel.
  std::vector<int> valid;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    if (result.candidates[j].validity == ViewValidity::kValid) valid.push_back(static_cast<int>(j));
  }
  const int hardware = static_cast<int>(std::thread::hardware_concurrency());
  const int workers = std::max(1, std::min(static_cast<int>(valid.size()),
                                           options_.threads > 0 ? options_.threads : std::max(1, hardware)));
  auto score = [&](int worker) {
    for (std::size_t v = worker; v < valid.size(); v += workers) {
      ViewCandidate& c = result.candidates[valid[v]];
      c.gain = Evaluate(c.T_world_camera, input.frustum);
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(score, w);
  score(0);
  for (std::thread& t : pool) t.join();

  const double tie_tolerance = 1e-12;
  double best_distance_m = 0.0;
  for (int j : valid) {
    const ViewCandidate& c = result.candidates[j];
    const double distance_m =
        input.has_camera_position ? (c.T_world_camera.translation() - input.camera_position_world).norm() : 0.0;
    if (result.best_index < 0) {
      result.best_index = j;
      best_distance_m = distance_m;
      continue;
    }
    const double best_gain = result.candidates[result.best_index].gain.gain;
    const double scale = std::max(1.0, std::abs(best_gain));
    if (c.gain.gain > best_gain + tie_tolerance * scale ||
        (c.gain.gain >= best_gain - tie_tolerance * scale && distance_m < best_distance_m)) {
      result.best_index = j;
      best_distance_m = distance_m;
    }
  }
  result.status = NbvStatus::kOk;
  return result;
}

}  // namespace objscan::planning
