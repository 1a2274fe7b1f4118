#pragma once
// The paper's evaluation metrics (§6.2), as functions over plain data so they can be checked on tiny
// hand-made inputs and fed from any map representation:
//  - object recognition: recall and precision, for all objects and for objects standing on the floor,
//    and per object category (Tables 1 and 2);
//  - object-level segmentation: the Rand Index over reconstructed non-structural points (Fig. 10);
//  - object coverage rate and quality over ground-truth surface voxels (Figs. 11 and 13).
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "objscan/world/category.h"
#include "objscan/world/scene.h"

namespace objscan::eval {

// ---------------------------------------------------------------------------------------------------
// Object recognition

// One ground-truth object of the scene.
struct GroundTruthInstance {
  int instance_id = world::kNoInstance;
  world::Category category = world::Category::kOther;
  bool on_floor = false;  // standing on the floor (the paper's "ground objects")
};

// One recognized output object.
struct OutputObject {
  world::Category category = world::Category::kOther;
  // The ground-truth instance holding most of the object's points (see MajorityInstance);
  // world::kNoInstance (or any id not in the ground truth) when that is unlabelled background.
  int majority_instance = world::kNoInstance;
  // The share of that instance's reconstructed surface the object holds, in [0, 1]; negative when
  // unknown (runs written before it was recorded). Error analysis only: the metrics ignore it.
  double instance_share = -1.0;
};

// The most frequent value of `point_instances` (ties: the smallest id); world::kNoInstance values
// (background) take part in the vote like any id. world::kNoInstance for an empty list.
int MajorityInstance(const std::vector<int>& point_instances);

// Each object's ground-truth instance and how much of that instance it holds.
struct ObjectInstanceShare {
  int instance = world::kNoInstance;  // the instance (id > 0) holding most of its points; none: kNoInstance
  double share = 0.0;                 // its points on that instance / all points of that instance
};
// `point_object[i]` is point i's object in [0, num_objects) or -1 for a point in no object (it still
// counts in its instance's total); `point_instance[i]` its ground-truth instance (<= 0: background,
// which never becomes an object's instance). Ties keep the smaller instance id. Throws InputError when
// the sizes differ or an object index is out of range.
std::vector<ObjectInstanceShare> ObjectInstanceShares(const std::vector<int>& point_object,
                                                      const std::vector<int>& point_instance, int num_objects);

struct RecognitionCounts {
  int ground_truth = 0;    // |ground-truth set|
  int outputs = 0;         // |output objects|
  int true_positives = 0;
  // 0 when the denominator is 0 (check the counts before averaging).
  double Recall() const { return ground_truth > 0 ? static_cast<double>(true_positives) / ground_truth : 0.0; }
  double Precision() const { return outputs > 0 ? static_cast<double>(true_positives) / outputs : 0.0; }
};

struct RecognitionResult {
  RecognitionCounts all;
  // Ground truth: the set's objects on the floor; outputs: those whose majority instance is on the floor.
  RecognitionCounts floor;
  // Ground truth and true positives by the instance's category, outputs by the output's category.
  std::array<RecognitionCounts, world::kNumCategories> per_category{};
  std::vector<bool> output_is_true_positive;  // parallel to the outputs
  std::vector<int> matched_instances;         // ground-truth instance ids matched, ascending
};

// Whether the recognition metrics score objects of this category: not structure, and not `other`.
// An object recognised as `other` (a plant, a towel, a box: a database model of no benchmark category)
// is the honest answer "none of the categories", so it is no output, and ground-truth objects of
// category `other` are in no ground-truth set, whatever the database holds.
bool IsScoredCategory(world::Category category);

// Matches outputs to ground truth in the given order: an output is a true positive when its category
// equals that of its majority instance, that instance is in the ground-truth set (every instance of a
// scored category that `database_categories` holds) and no earlier output matched it (a duplicate
// detection is a false positive). Outputs must be of scored categories (std::invalid_argument
// otherwise). Throws InputError on duplicate instance ids.
RecognitionResult MatchRecognitions(const std::vector<GroundTruthInstance>& ground_truth,
                                    const std::vector<OutputObject>& outputs,
                                    const std::vector<world::Category>& database_categories);

// ---------------------------------------------------------------------------------------------------
// Segmentation: Rand Index

// The Rand Index itself is segmentation::RandIndex (segmentation_quality.h): RI(S1, S2) = share of
// the C(n, 2) point pairs on which S1 and S2 agree, from the contingency table.

// Rand Index of a reconstruction's segmentation (segment id per point) against ground truth (instance
// id per point) over the points whose instance is a non-structural ground-truth object; points of
// floors, walls and unlisted instances (e.g. world::kNoInstance) are left out. Throws InputError when
// the sizes differ.
double NonStructuralRandIndex(const std::vector<std::int32_t>& point_segment,
                              const std::vector<std::int32_t>& point_instance,
                              const std::vector<GroundTruthInstance>& ground_truth);

// ---------------------------------------------------------------------------------------------------
// Coverage rate and quality

struct CoverageOptions {
  double sigma = 0.6;                  // the paper's sigma
  double theta_t_rad = M_PI / 2.0;     // angle scale theta_t
  double min_range_m = 0.5;            // d_min: valid scanning range [d_min, d_max]
  double max_range_m = 4.0;            // d_max, also the distance scale d_t

  template <class V>
  void Visit(V& v) {
    v("sigma", sigma);
    v("theta_t_rad", theta_t_rad);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
  }
  void Validate() const;
};

// One surface voxel of a ground-truth object (the set V_S).
struct SurfaceVoxel {
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();  // unit; its sign does not matter
  int instance = world::kNoInstance;                         // owning ground-truth instance
  bool observable = true;  // a camera could measure it (eval/observability.h); not tested = true
};

// q(v) = exp(-theta^2 / (sigma^2 theta_t)) * exp(-(d - d_min)^2 / (sigma^2 d_t)) for one camera:
// theta is the angle between the voxel's normal line and the line of sight (0 head-on, pi/2 grazing),
// d the camera-voxel distance, d_t = d_max. 0 outside [d_min, d_max].
double ViewQuality(const SurfaceVoxel& voxel, const Eigen::Vector3d& camera_position_world,
                   const CoverageOptions& options);

struct CoverageResult {
  double rate = 0.0;      // R_cover = |{v : detected(v) and visible(v)}| / |V_S|
  double quality = 0.0;   // Q_cover = sum of q(v) over those voxels / |V_S|
  int num_voxels = 0;     // |V_S|
  int num_visible = 0;    // voxels seen within range by some camera
  int num_covered = 0;    // visible and on a detected instance
};

// Surface voxels of one ground-truth instance, and how many of them were seen within range.
struct InstanceCoverage {
  int instance = world::kNoInstance;
  int num_voxels = 0;
  int num_visible = 0;
};

// Accumulates views one at a time, so coverage curves over the number of views (Fig. 11) cost one
// pass. Each voxel keeps the best q over the cameras that saw it within range.
class CoverageAccumulator {
 public:
  CoverageAccumulator(std::vector<SurfaceVoxel> voxels, CoverageOptions options);

  // A camera at `camera_position_world` saw the voxels with these indices (occlusion already decided
  // by the caller, e.g. by ray casting). Throws InputError on an index out of range.
  void AddView(const Eigen::Vector3d& camera_position_world, const std::vector<int>& seen_voxels);

  // Coverage with delta_detect(v) = 1 for voxels of the given instances (the matched ones).
  CoverageResult Result(const std::vector<int>& detected_instances) const;
  // Per instance, ascending by id: its surface voxels and those seen within range.
  std::vector<InstanceCoverage> PerInstance() const;

  const std::vector<SurfaceVoxel>& voxels() const { return voxels_; }
  // Best q per voxel; -1 for voxels not (yet) seen within range.
  const std::vector<double>& best_quality() const { return best_quality_; }

 private:
  std::vector<SurfaceVoxel> voxels_;
  CoverageOptions options_;
  std::vector<double> best_quality_;
};

// All views at once: seen_voxels_per_camera[c] lists the voxel indices camera c saw.
CoverageResult ComputeCoverage(const std::vector<SurfaceVoxel>& voxels,
                               const std::vector<Eigen::Vector3d>& camera_positions_world,
                               const std::vector<std::vector<int>>& seen_voxels_per_camera,
                               const std::vector<int>& detected_instances, const CoverageOptions& options = {});

}  // namespace objscan::eval
