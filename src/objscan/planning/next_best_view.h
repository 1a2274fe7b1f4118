#pragma once
// Next best view (NBV, §5.2 of the paper): among n_v viewpoints around the object of interest gamma, the
// one with the largest conditional information gain G^j = sum_i p(m_i) G^j(m_i) over the aligned
// candidate models M(gamma) (see information_gain.h for the formulas).
//
// Everything happens on a dense local voxel grid around gamma and its candidate models:
//  - f(x, gamma) and f(x, m_i): indicator of the points, Gaussian-blurred (tdf.h);
//  - Delta_i = { x : f(x, m_i) > tdf_epsilon, f(x, gamma) <= tdf_epsilon, g(x, V_j) = 1 }; tdf_epsilon
//    stands for "!= 0" of the paper because a blurred field is nowhere exactly zero near a shape: below it
//    only the far tail of the kernel (beyond ~2.5 sigma) reaches a voxel;
//  - g(x, V_j): x inside the camera frustum and depth range, and the DDA ray from the camera to x meets
//    no voxel of the current scene surface (occluder points + gamma) or of m_i itself (voxel_traversal.h).
//    Occluders farther away than the grid are the ViewValidator's business (line of sight).
// Per-voxel entropies do not depend on the view, so they are computed once per call; each view then
// only sums precomputed per-voxel gains over its visible voxels.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/geometry/pose.h"
#include "objscan/planning/local_grid.h"
#include "objscan/planning/view_candidates.h"
#include "objscan/planning/voxel_traversal.h"

namespace objscan::planning {

struct NextBestViewOptions {
  ViewCandidateOptions candidates;  // n_v = candidates.num_candidates = 16
  double voxel_size_m = 0.025;
  double blur_sigma_voxels = 1.0;  // 0: unblurred binary TDF
  double tdf_epsilon = 0.01;       // f below this counts as 0 (for both f(x, m_i) and f(x, gamma))
  // Voxels entered within this path length (in voxels) before the target do not occlude it.
  double occlusion_tolerance_voxels = 1.5;
  double grid_padding_m = 0.1;  // grid = bounds of gamma and models + blur radius + this
  int max_grid_voxels = 2000000;  // coarser voxels beyond this (huge segments)
  int threads = 0;  // candidates scored in parallel; 0 = hardware concurrency. Results do not depend on it.

  template <class V>
  void Visit(V& v) {
    v("candidates", candidates);
    v("voxel_size_m", voxel_size_m);
    v("blur_sigma_voxels", blur_sigma_voxels);
    v("tdf_epsilon", tdf_epsilon);
    v("occlusion_tolerance_voxels", occlusion_tolerance_voxels);
    v("grid_padding_m", grid_padding_m);
    v("max_grid_voxels", max_grid_voxels);
    v("threads", threads);
  }
  void Validate() const;
};

// One aligned candidate model m_i of M(gamma).
struct ModelHypothesis {
  int model_id = -1;                                           // database id, for the run record
  double objectness = 0.0;                                     // O(gamma, m_i) >= 0
  const std::vector<Eigen::Vector3f>* points_world = nullptr;  // surface samples, spacing <= voxel size
};

// What a view is worth.
enum class ViewGainMeasure {
  // The paper's conditional information gain (eqs. (7)-(12)).
  kInformation = 0,
  // Beyond the paper, for views that complete the scan of a recognized object: the expected number of
  // voxels of model surface not yet observed (f(x, m_i) above tdf_epsilon, f(x, gamma) not) that the
  // view sees, sum_i p(m_i) |Delta_i visible|. With one model it counts that model's unseen surface.
  kUnobservedSurface,
};

struct NextBestViewInput {
  const std::vector<Eigen::Vector3f>* gamma_points_world = nullptr;  // required, non-empty
  std::vector<ModelHypothesis> models;                               // M(gamma); at most 15
  // Current map surface (any extent; only points inside the local grid matter). May be null.
  const std::vector<Eigen::Vector3f>* occluder_points_world = nullptr;
  CameraFrustum frustum;
  // Ties in gain go to the candidate nearest this position (the current camera) when set.
  bool has_camera_position = false;
  Eigen::Vector3d camera_position_world = Eigen::Vector3d::Zero();
  ViewGainMeasure gain_measure = ViewGainMeasure::kInformation;
  // Beyond the paper (coverage views): when non-empty, as many candidates again, generated the same
  // way around the bounding box of these points (the part of the object still to be seen, e.g. a
  // bathtub's inside) and appended after those around the whole object. They come closer and look
  // more steeply at that part than views framing the whole object can.
  const std::vector<Eigen::Vector3f>* aim_points_world = nullptr;
};

// Gain of one view.
struct ViewGain {
  double gain = 0.0;                         // G^j
  std::vector<double> gain_per_model;        // G^j(m_i), before weighting by p(m_i)
  std::vector<int> visible_voxels_per_model;  // |Delta| for m_i
};

struct ViewCandidate {
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  ViewValidity validity = ViewValidity::kValid;
  ViewGain gain;  // zero for invalid candidates
};

enum class NbvStatus { kOk = 0, kNoValidView };
const char* ToString(NbvStatus status);

struct NextBestViewResult {
  NbvStatus status = NbvStatus::kNoValidView;
  int best_index = -1;  // into candidates; -1 when no candidate is valid
  std::vector<ViewCandidate> candidates;
  Eigen::Vector3d target_world = Eigen::Vector3d::Zero();  // where the candidates look
  double radius_m = 0.0;                                    // bounding sphere used for the distance
  std::vector<double> model_probabilities;                  // p(m_i)
  double prior_entropy_nats = 0.0;                          // H(x)
  LocalGrid grid;                                           // the grid used (voxel size may be coarsened)
  int delta_voxels = 0;  // voxels with a non-zero gain for some model before visibility
};

// Holds scratch buffers between calls; not thread-safe (one per thread).
class NextBestView {
 public:
  explicit NextBestView(const NextBestViewOptions& options);

  // Generates the candidates around gamma, asks `validator` (null: all valid) about each, scores the
  // valid ones and picks the largest gain. Throws InputError on empty gamma, null model points, more
  // than 15 models, negative objectness or non-finite points.
  NextBestViewResult Plan(const NextBestViewInput& input, const ViewValidator* validator);

  // Scores the given camera poses (no validation, no candidate generation).
  std::vector<ViewGain> EvaluateViews(const NextBestViewInput& input,
                                      const std::vector<geometry::Pose3>& T_world_cameras);

  const NextBestViewOptions& options() const { return options_; }

 private:
  // A voxel in Delta of at least one model (before visibility).
  struct DeltaVoxel {
    std::int16_t x, y, z;
    std::uint16_t models;  // bit i + 1 set when the voxel is in Delta_i with a non-zero gain
  };
  // Builds the grid, TDFs, occupancy masks and the per-model gain lists for `input`.
  void Prepare(const NextBestViewInput& input, const geometry::Aabb3& bounds, NextBestViewResult* summary);
  ViewGain Evaluate(const geometry::Pose3& T_world_camera, const CameraFrustum& frustum) const;

  NextBestViewOptions options_;
  LocalGrid grid_;
  std::vector<double> probabilities_;
  std::vector<std::uint16_t> mask_;         // bit 0: scene surface (incl. gamma), bit i + 1: model i
  std::vector<std::uint8_t> free_distance_;  // chessboard distance to the nearest masked voxel
  VoxelOccupancy occupancy_;                 // view of mask_ and free_distance_ for the ray walks
  std::vector<float> gamma_tdf_;
  std::vector<float> model_tdfs_;           // model-major, one grid each
  std::vector<float> scratch_;
  std::vector<DeltaVoxel> delta_;
  std::vector<float> delta_gains_;  // per delta_ entry, one H(x) - H(x | m_i) per model (0 outside Delta_i)
};

}  // namespace objscan::planning
