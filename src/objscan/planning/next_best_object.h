#pragma once
// Next best object (NBO, §5.1 of the paper, eq. NBO): the object of interest gamma is the post-segmented
// object r maximising O(r) + S(r), S(r) = w_z S_z(r) + w_e S_e(r) + w_d S_d(r).
// Inputs are plain per-object summaries, so the segmentation and recognition stages stay out of here.
#include <Eigen/Core>
#include <vector>

#include "objscan/common/config.h"

namespace objscan::planning {

struct NextBestObjectOptions {
  // Weights of the terms; 0 switches a term off (ablations no-objectness / no-distance / ...).
  double objectness_weight = 1.0;   // factor on O(r) (the paper adds O(r) unweighted)
  double distance_weight = 1.5;     // w_z
  double orientation_weight = 1.0;  // w_e
  double size_weight = 1.0;         // w_d
  // An object that has had this many views without becoming complete is given up (marked incomplete).
  int max_views_per_object = 5;
  // Keep the current object of interest until it is complete or out of views (the paper's behaviour);
  // false re-runs the argmax every step.
  bool keep_current_object = true;

  template <class V>
  void Visit(V& v) {
    v("objectness_weight", objectness_weight);
    v("distance_weight", distance_weight);
    v("orientation_weight", orientation_weight);
    v("size_weight", size_weight);
    v("max_views_per_object", max_views_per_object);
    v("keep_current_object", keep_current_object);
  }
  void Validate() const;
};

// One post-segmented object r as NBO sees it.
struct NboObject {
  int id = -1;
  double objectness = 0.0;                            // O(r) = max over M(r) of O(r, m)
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();  // C(r)
  double area_m2 = 0.0;                               // Area(r)
  bool complete = false;                              // already replaced by a model: out of the race
  int views_spent = 0;                                // NBV views taken while r was the object of interest
};

// Where the robot stands and looks: P and V of the paper.
struct RobotView {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d view_direction_world = Eigen::Vector3d::UnitX();  // need not be normalised
};

enum class NboExclusion {
  kNone = 0,        // in the race
  kComplete,        // complete objects are out of the race
  kViewBudgetSpent  // had max_views_per_object views: the caller should mark it incomplete
};
const char* ToString(NboExclusion exclusion);

// Per-object score breakdown (for run.json). Terms are the unweighted S_z, S_e, S_d and O(r);
// `score` is the weighted sum. Excluded objects keep score 0.
struct NboScore {
  int id = -1;
  NboExclusion exclusion = NboExclusion::kNone;
  double objectness = 0.0;
  double distance_term = 0.0;     // S_z = exp(-|C(r) - P| / max |C - P|)
  double orientation_term = 0.0;  // S_e = cos angle(C(r) - P, V)
  double size_term = 0.0;         // S_d = Area(r) / max Area
  double score = 0.0;
};

enum class NboStatus { kOk = 0, kNoCandidate };
const char* ToString(NboStatus status);

struct NboResult {
  NboStatus status = NboStatus::kNoCandidate;
  int chosen_id = -1;         // gamma; -1 when status is kNoCandidate
  bool kept_current = false;  // the previous object of interest was kept
  std::vector<NboScore> scores;  // one per input object, same order
  // Ids that ran out of views this call (including a current object of interest that did).
  std::vector<int> budget_spent_ids;
};

// Chooses gamma among `objects`. `current_ooi_id` is the previous object of interest (-1: none); it is
// kept while it is in the race and options.keep_current_object is set. The maxima of the distance and
// area normalisations are taken over the objects in the race (complete objects are removed from the
// scene surface in the paper, so they are not part of R). Ties go to the smaller id.
// Throws InputError on a non-finite field or a negative area / view count.
NboResult SelectNextBestObject(const std::vector<NboObject>& objects, const RobotView& robot, int current_ooi_id,
                               const NextBestObjectOptions& options);

}  // namespace objscan::planning
