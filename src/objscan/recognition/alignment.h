#pragma once
// Aligning a (possibly partial) query point set to a database item. Gravity is known (both are Z up),
// so the search is over yaw (a fixed number of angles) and translation, then trimmed ICP with
// 4 degrees of freedom (yaw + translation) and optionally a uniform scale. Correspondences go from
// the query to the item, so a partial query is matched against the part of the item it covers.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/recognition/distance_grid.h"
#include "objscan/recognition/kd_tree.h"
#include "objscan/recognition/nearest_grid.h"

namespace objscan::recognition {

struct AlignmentOptions {
  int yaw_steps = 24;                 // initial yaw hypotheses, evenly spaced over 360 deg
  bool side_translation_inits = true; // besides centring, align each side of the footprints (partial views)
  int initial_points = 24;             // query points scoring each initial (yaw, translation) hypothesis
  // Initial hypotheses are scored with distances truncated here (0 = exact): a far point then costs
  // a few kd-tree nodes instead of a long search, and one stray part cannot dominate the score.
  double initial_truncation_m = 0.15;
  // Score the initial hypotheses by the target's distance grid (when it has one reaching at least
  // initial_truncation_m) instead of kd-tree searches: interpolated, so approximate, and far cheaper.
  bool grid_initial_scoring = true;
  int coarse_points = 48;             // query points used in the coarse ICP rounds
  int coarse_keep = 4;                 // hypotheses (by initial cost) that get coarse ICP rounds
  int coarse_iterations = 3;          // ICP rounds per kept hypothesis
  int refine_hypotheses = 2;          // best hypotheses refined with all query points
  int refine_iterations = 15;
  int refine_points = 150;            // query points used in refinement (0 = all)
  double trim_fraction = 0.85;        // share of best correspondences kept in each ICP round
  double inlier_distance_m = 0.03;    // a query point within this of the item counts as explained
  bool estimate_scale = false;        // uniform scale in [min_scale, max_scale]
  double min_scale = 0.8;
  double max_scale = 1.25;
  double convergence_m = 1e-5;        // stop refining when the update moves points less than this
  // ICP correspondences from the target's nearest grid (a cell lookup and a short exact scan; built
  // on first use) where it covers the point, else the kd-tree: the same nearest points, faster.
  // false = kd-tree searches only.
  bool grid_correspondences = true;
  // End an ICP run as soon as a round finds the same correspondences (and keeps the same ones) as
  // the round before: the next update would then be the identity.
  bool stop_when_correspondences_repeat = true;

  template <class V>
  void Visit(V& v) {
    v("yaw_steps", yaw_steps);
    v("side_translation_inits", side_translation_inits);
    v("initial_points", initial_points);
    v("initial_truncation_m", initial_truncation_m);
    v("grid_initial_scoring", grid_initial_scoring);
    v("coarse_points", coarse_points);
    v("coarse_keep", coarse_keep);
    v("coarse_iterations", coarse_iterations);
    v("refine_hypotheses", refine_hypotheses);
    v("refine_iterations", refine_iterations);
    v("refine_points", refine_points);
    v("trim_fraction", trim_fraction);
    v("inlier_distance_m", inlier_distance_m);
    v("estimate_scale", estimate_scale);
    v("min_scale", min_scale);
    v("max_scale", max_scale);
    v("convergence_m", convergence_m);
    v("grid_correspondences", grid_correspondences);
    v("stop_when_correspondences_repeat", stop_when_correspondences_repeat);
  }
  void Validate() const;
};

// The item side of an alignment, prepared once per item (kd-tree over its points).
class AlignmentTarget {
 public:
  AlignmentTarget() = default;
  explicit AlignmentTarget(const std::vector<Eigen::Vector3f>& item_points);
  const KdTree3& tree() const { return tree_; }
  const geometry::Aabb3& bounds() const { return bounds_; }
  const Eigen::Vector3d& centroid() const { return centroid_; }
  bool empty() const { return tree_.empty(); }
  // Optional truncated distance field of the item points (see DistanceGrid) for scoring the initial
  // hypotheses, built on its first use (thread-safe): a database with thousands of entries then
  // loads as fast as before and builds only the grids its queries reach.
  void EnableDistanceGrid(float truncation_m, int max_vertices, float min_spacing_m);
  // nullptr when not enabled.
  const DistanceGrid* distance_grid() const;
  // The nearest grid for ICP correspondences (see NearestGrid), likewise built on first use; enabled
  // with the defaults below by the constructor, re-parametrised (before any use) here.
  static constexpr float kNearestGridBandM = 0.15f;
  static constexpr int kNearestGridMaxCells = 8192;
  static constexpr float kNearestGridMinCellM = 0.02f;
  void EnableNearestGrid(float band_m, int max_cells, float min_cell_m);
  // Correspondences from the kd-tree only (for targets met too rarely to repay building the grid).
  void DisableNearestGrid() { nearest_grid_.reset(); }
  // nullptr when not enabled.
  const NearestGrid* nearest_grid() const;

 private:
  // A grid over the item points, built from them on first use (thread-safe); shared by copies and
  // immutable once built.
  template <class Grid>
  struct LazyGrid;
  KdTree3 tree_;
  std::shared_ptr<LazyGrid<DistanceGrid>> grid_;
  std::shared_ptr<LazyGrid<NearestGrid>> nearest_grid_;
  geometry::Aabb3 bounds_;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
};

enum class AlignmentStatus {
  kOk,
  kEmptyInput,  // the query or the item has no points
};

struct AlignmentResult {
  AlignmentStatus status = AlignmentStatus::kEmptyInput;
  // Maps query points into the item frame: p_item = T_item_query * p_query (rotation about Z,
  // translation, and the uniform scale when estimated).
  Eigen::Affine3d T_item_query = Eigen::Affine3d::Identity();
  double yaw_rad = 0.0;
  double scale = 1.0;
  double trimmed_rms_m = 0.0;     // RMS distance of the kept correspondences
  double inlier_fraction = 0.0;   // share of query points within inlier_distance_m of the item
  // Mean over all query points of the squared distance to the nearest item point (untrimmed): the
  // similarity term d(c, m) of the objectness, measured on the way.
  double mean_squared_distance_m2 = 0.0;
  bool ok() const { return status == AlignmentStatus::kOk; }
};

// One pose hypothesis: p_item = scale * Rz(yaw_rad) * p_query + t.
struct AlignmentHypothesis {
  double yaw_rad = 0.0;
  double scale = 1.0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double cost_m2 = 0.0;  // trimmed mean squared distance over the points that scored it
  Eigen::Affine3d T_item_query() const;
};

// What is known of the query's pose besides its points.
struct AlignmentConstraints {
  // The query stands on a floor at this height (query frame): the item's z = 0, where a database
  // model stands, is held there, so the search and ICP turn and move the item across the floor but
  // never lift it (a chair raised to fit a table top, a cabinet floating on a counter). Unset: the
  // item's bottom starts at the query's bottom and ICP moves it freely in z.
  std::optional<double> floor_height_m;
};

// The whole alignment: CoarseAlign, then RefineAlignment of its hypotheses.
AlignmentResult AlignToItem(const std::vector<Eigen::Vector3f>& query_points, const AlignmentTarget& target,
                            const AlignmentOptions& options, const AlignmentConstraints& constraints = {});

// The coarse stage alone (yaw x translation search on initial_points, coarse ICP on coarse_points):
// the refine_hypotheses best hypotheses, best first; empty when the query or the item is empty. Cheap
// enough to run on a whole shortlist and refine only the promising entries.
std::vector<AlignmentHypothesis> CoarseAlign(const std::vector<Eigen::Vector3f>& query_points,
                                             const AlignmentTarget& target, const AlignmentOptions& options,
                                             const AlignmentConstraints& constraints = {});

// Refines hypotheses (e.g. from CoarseAlign) with refine_points query points and keeps the best;
// trimmed_rms_m and inlier_fraction are measured over all query points.
// With constraints.floor_height_m, the hypotheses must hold it already (as CoarseAlign's do).
AlignmentResult RefineAlignment(const std::vector<Eigen::Vector3f>& query_points, const AlignmentTarget& target,
                                const std::vector<AlignmentHypothesis>& hypotheses, const AlignmentOptions& options,
                                const AlignmentConstraints& constraints = {});

// Evenly strided indices of `count` of n points (all when count <= 0 or count >= n).
std::vector<int> StridedSubset(int n, int count);

}  // namespace objscan::recognition
