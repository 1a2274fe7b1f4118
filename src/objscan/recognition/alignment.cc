#include "objscan/recognition/alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <mutex>

namespace objscan::recognition {

void AlignmentOptions::Validate() const {
  config::Require(yaw_steps >= 1, "recognition.alignment.yaw_steps", "must be at least 1");
  config::Require(initial_points >= 3, "recognition.alignment.initial_points", "must be at least 3");
  config::RequireNonNegative("recognition.alignment.initial_truncation_m", initial_truncation_m);
  config::Require(coarse_points >= 3, "recognition.alignment.coarse_points", "must be at least 3");
  config::Require(coarse_keep >= 1, "recognition.alignment.coarse_keep", "must be at least 1");
  config::Require(coarse_iterations >= 0, "recognition.alignment.coarse_iterations", "must be >= 0");
  config::Require(refine_hypotheses >= 1, "recognition.alignment.refine_hypotheses", "must be at least 1");
  config::Require(refine_iterations >= 0, "recognition.alignment.refine_iterations", "must be >= 0");
  config::Require(refine_points == 0 || refine_points >= 3, "recognition.alignment.refine_points",
                  "must be 0 (all) or at least 3");
  config::RequireInRange("recognition.alignment.trim_fraction", trim_fraction, 0.1, 1.0);
  config::RequirePositive("recognition.alignment.inlier_distance_m", inlier_distance_m);
  config::RequirePositive("recognition.alignment.min_scale", min_scale);
  config::Require(max_scale >= min_scale, "recognition.alignment.max_scale", "must be >= min_scale");
  config::Require(min_scale <= 1.0 && max_scale >= 1.0, "recognition.alignment.min_scale",
                  "the scale range must contain 1");
  config::RequireNonNegative("recognition.alignment.convergence_m", convergence_m);
}

AlignmentTarget::AlignmentTarget(const std::vector<Eigen::Vector3f>& item_points) : tree_(item_points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : item_points) {
    bounds_.Extend(p.cast<double>());
    sum += p.cast<double>();
  }
  if (!item_points.empty()) {
    centroid_ = sum / static_cast<double>(item_points.size());
    EnableNearestGrid(kNearestGridBandM, kNearestGridMaxCells, kNearestGridMinCellM);
  }
}

template <class Grid>
struct AlignmentTarget::LazyGrid {
  std::function<Grid(const std::vector<Eigen::Vector3f>&)> build;
  std::once_flag once;
  Grid grid;
  const Grid* Get(const std::vector<Eigen::Vector3f>& points) {
    std::call_once(once, [&] { grid = build(points); });
    return &grid;
  }
};

void AlignmentTarget::EnableDistanceGrid(float truncation_m, int max_vertices, float min_spacing_m) {
  grid_ = std::make_shared<LazyGrid<DistanceGrid>>();
  grid_->build = [=](const std::vector<Eigen::Vector3f>& points) {
    return DistanceGrid(points, truncation_m, max_vertices, min_spacing_m);
  };
}

const DistanceGrid* AlignmentTarget::distance_grid() const { return grid_ ? grid_->Get(tree_.points()) : nullptr; }

void AlignmentTarget::EnableNearestGrid(float band_m, int max_cells, float min_cell_m) {
  nearest_grid_ = std::make_shared<LazyGrid<NearestGrid>>();
  nearest_grid_->build = [=](const std::vector<Eigen::Vector3f>& points) {
    return NearestGrid(points, band_m, max_cells, min_cell_m);
  };
}

const NearestGrid* AlignmentTarget::nearest_grid() const {
  return nearest_grid_ ? nearest_grid_->Get(tree_.points()) : nullptr;
}

namespace {

// p_item = scale * Rz(yaw) * p_query + t.
struct Similarity4 {
  double yaw = 0.0;
  double scale = 1.0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Eigen::Matrix3d R() const { return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
  Eigen::Affine3d Affine() const {
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    T.linear() = scale * R();
    T.translation() = t;
    return T;
  }
};

// M * p + t in plain float arithmetic: inlined into the correspondence loops.
inline Eigen::Vector3f Transform(const Eigen::Matrix3f& M, const Eigen::Vector3f& t, const Eigen::Vector3f& p) {
  return Eigen::Vector3f(M(0, 0) * p.x() + M(0, 1) * p.y() + M(0, 2) * p.z() + t.x(),
                         M(1, 0) * p.x() + M(1, 1) * p.y() + M(1, 2) * p.z() + t.y(),
                         M(2, 0) * p.x() + M(2, 1) * p.y() + M(2, 2) * p.z() + t.z());
}

struct Hypothesis {
  Similarity4 x;
  double cost = std::numeric_limits<double>::infinity();  // trimmed mean squared distance
};

class Icp {
 public:
  // hold_height: ICP never changes the translation's z (AlignmentConstraints::floor_height_m).
  Icp(const std::vector<Eigen::Vector3f>& query, const AlignmentTarget& target, const AlignmentOptions& options,
      bool hold_height = false)
      : query_(query), target_(target), options_(options), hold_height_(hold_height) {
    moved_.resize(query.size());
    nearest_.resize(query.size());
    hint_.assign(query.size(), -1);
    d2_.resize(query.size());
    order_.resize(query.size());
    range_begin_.resize(query.size());
    range_end_.resize(query.size());
    if (options.grid_correspondences) {
      grid_ = target.nearest_grid();
      if (grid_ != nullptr && grid_->empty()) grid_ = nullptr;
    }
  }

  // The trimmed cost of x on `subset` with every squared distance truncated at truncation_d2.
  double TruncatedCost(const std::vector<int>& subset, const Similarity4& x, float truncation_d2) {
    return Correspond(subset, x, truncation_d2);
  }

  // The same from the target's distance grid (interpolated distances; no correspondences).
  double GridCost(const std::vector<int>& subset, const Similarity4& x, float truncation_d2) {
    const Eigen::Matrix3f M = (x.scale * x.R()).cast<float>();
    const Eigen::Vector3f t = x.t.cast<float>();
    const DistanceGrid& grid = *target_.distance_grid();
    const std::size_t n = subset.size();
    for (std::size_t k = 0; k < n; ++k) moved_[k] = Transform(M, t, query_[subset[k]]);
    grid.Distances(moved_.data(), n, d2_.data());
    for (std::size_t k = 0; k < n; ++k) d2_[k] = std::min(d2_[k] * d2_[k], truncation_d2);
    return TrimmedMean(n);
  }

  // Runs `iterations` trimmed ICP rounds on the points `subset` (indices into query), updating *h.
  void Run(const std::vector<int>& subset, int iterations, Hypothesis* h) {
    for (int it = 0; it <= iterations; ++it) {
      const double cost = Correspond(subset, h->x);
      h->cost = cost;
      if (it == iterations) break;
      if (options_.stop_when_correspondences_repeat && it > 0 && SameAsLastRound(subset.size())) break;
      if (options_.stop_when_correspondences_repeat) RememberRound(subset.size());
      const double moved = Solve(subset, &h->x);
      if (moved < options_.convergence_m) {
        h->cost = Correspond(subset, h->x);
        break;
      }
    }
  }

  // Share of the subset within `distance` of the item under x; *cost gets the trimmed cost and
  // *mean_d2 the untrimmed mean squared distance.
  double InlierFraction(const std::vector<int>& subset, const Similarity4& x, double distance, double* cost,
                        double* mean_d2) {
    *cost = Correspond(subset, x);
    const double d2max = distance * distance;
    int inliers = 0;
    double sum = 0.0;
    for (std::size_t k = 0; k < subset.size(); ++k) {
      inliers += d2_[k] <= d2max ? 1 : 0;
      sum += d2_[k];
    }
    *mean_d2 = subset.empty() ? 0.0 : sum / static_cast<double>(subset.size());
    return subset.empty() ? 0.0 : static_cast<double>(inliers) / subset.size();
  }

 private:
  // Transforms the subset, finds nearest item points, returns the trimmed mean squared distance and
  // leaves the kept correspondences as order_[0, kept_).
  // With a finite truncation_d2, farther points get d2 = truncation_d2 and no correspondence (for
  // scoring only; Solve must not follow such a call).
  double Correspond(const std::vector<int>& subset, const Similarity4& x,
                    float truncation_d2 = std::numeric_limits<float>::infinity()) {
    const Eigen::Matrix3f M = (x.scale * x.R()).cast<float>();
    const Eigen::Vector3f t = x.t.cast<float>();
    const std::size_t n = subset.size();
    const auto& item = target_.tree().points();
    if (grid_ != nullptr) {
      // All cell lookups first, then the scans: independent reads the processor overlaps.
      for (std::size_t k = 0; k < n; ++k) {
        moved_[k] = Transform(M, t, query_[subset[k]]);
        grid_->CellRange(moved_[k], &range_begin_[k], &range_end_[k]);
      }
    } else {
      for (std::size_t k = 0; k < n; ++k) moved_[k] = Transform(M, t, query_[subset[k]]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (grid_ != nullptr && range_begin_[k] < range_end_[k]) {
        // Exact where the grid covers the point: no search needed.
        float d2 = 0.f;
        const int i = grid_->Scan(moved_[k], range_begin_[k], range_end_[k], &d2);
        hint_[subset[k]] = i;
        if (d2 < truncation_d2) {
          nearest_[k] = i;
          d2_[k] = d2;
        } else {
          nearest_[k] = -1;
          d2_[k] = truncation_d2;
        }
        continue;
      }
      // The point's last correspondence (any earlier round or hypothesis) bounds the search: the
      // result is still the exact nearest neighbour, found with far fewer nodes visited.
      int& hint = hint_[subset[k]];
      float bound = truncation_d2;
      int guess = -1;
      if (hint >= 0) {
        const float hint_d2 = (item[hint] - moved_[k]).squaredNorm();
        if (hint_d2 < bound) {
          bound = hint_d2;
          guess = hint;
        }
      }
      nearest_[k] = target_.tree().NearestBounded(moved_[k], bound, guess, &d2_[k]);
      if (nearest_[k] >= 0) {
        hint = nearest_[k];
      } else {
        d2_[k] = truncation_d2;
      }
    }
    return TrimmedMean(n);
  }

  // Whether the last Correspond found the same nearest points and kept the same ones as the round
  // remembered by RememberRound.
  bool SameAsLastRound(std::size_t n) const {
    if (last_kept_ != kept_) return false;
    if (!std::equal(nearest_.begin(), nearest_.begin() + n, last_nearest_.begin())) return false;
    // The kept set (not its order) decides the update.
    for (std::size_t k = 0; k < kept_; ++k) {
      if (!last_in_kept_[order_[k]]) return false;
    }
    return true;
  }
  void RememberRound(std::size_t n) {
    last_nearest_.assign(nearest_.begin(), nearest_.begin() + n);
    last_in_kept_.assign(n, 0);
    for (std::size_t k = 0; k < kept_; ++k) last_in_kept_[order_[k]] = 1;
    last_kept_ = kept_;
  }

  // Trimmed mean of d2_[0, n); leaves the kept indices as order_[0, kept_).
  double TrimmedMean(std::size_t n) {
    kept_ = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(options_.trim_fraction * n)));
    kept_ = std::min(kept_, n);
    if (kept_ == 0) return std::numeric_limits<double>::infinity();
    // Selection on (distance, index) packed in one integer: the bits of a non-negative float order as
    // the float does, so this is the order by distance with ties to the lower index, without the
    // indirection of comparing through indices.
    keys_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t bits;
      std::memcpy(&bits, &d2_[k], sizeof(bits));
      keys_[k] = (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(k);
    }
    std::nth_element(keys_.begin(), keys_.begin() + (kept_ - 1), keys_.end());
    double sum = 0.0;
    for (std::size_t k = 0; k < kept_; ++k) {
      order_[k] = static_cast<int>(keys_[k] & 0xffffffffu);
      sum += d2_[order_[k]];
    }
    return sum / kept_;
  }

  // One least-squares update over the kept correspondences; returns the RMS motion of the points.
  double Solve(const std::vector<int>& /*subset*/, Similarity4* x) {
    if (kept_ < 3) return 0.0;
    const auto& item = target_.tree().points();
    Eigen::Vector3d a_mean = Eigen::Vector3d::Zero(), b_mean = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < kept_; ++k) {
      const int i = order_[k];
      a_mean += moved_[i].cast<double>();
      b_mean += item[nearest_[i]].cast<double>();
    }
    a_mean /= static_cast<double>(kept_);
    b_mean /= static_cast<double>(kept_);
    double sxx = 0.0, sxy = 0.0, saa = 0.0;
    for (std::size_t k = 0; k < kept_; ++k) {
      const int i = order_[k];
      const Eigen::Vector3d a = moved_[i].cast<double>() - a_mean;
      const Eigen::Vector3d b = item[nearest_[i]].cast<double>() - b_mean;
      sxx += a.x() * b.x() + a.y() * b.y();
      sxy += a.x() * b.y() - a.y() * b.x();
      saa += a.squaredNorm();
    }
    const double dyaw = std::atan2(sxy, sxx);
    const Eigen::Matrix3d dR = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    double ds = 1.0;
    if (options_.estimate_scale && saa > 0.0) {
      double sab = 0.0;
      for (std::size_t k = 0; k < kept_; ++k) {
        const int i = order_[k];
        const Eigen::Vector3d a = moved_[i].cast<double>() - a_mean;
        const Eigen::Vector3d b = item[nearest_[i]].cast<double>() - b_mean;
        sab += b.dot(dR * a);
      }
      ds = std::clamp(sab / saa, options_.min_scale / x->scale, options_.max_scale / x->scale);
    }
    Eigen::Vector3d dt = b_mean - ds * dR * a_mean;
    // Held on the floor at height h: t.z = -scale * h. The update keeps that with dt.z = 0 for any ds
    // (new t.z = ds * t.z = -(scale * ds) * h; rotations about Z leave z alone).
    if (hold_height_) dt.z() = 0.0;
    // Motion of the kept points' spread: |ds*dR*a + dt - a| averaged, approximated at the mean and
    // by the rotation/scale change over the spread.
    const double spread = std::sqrt(saa / static_cast<double>(kept_));
    const double motion = (ds * dR * a_mean + dt - a_mean).norm() + spread * (std::abs(dyaw) + std::abs(ds - 1.0));
    // Compose: new = d o old.
    x->yaw += dyaw;
    x->scale *= ds;
    x->t = ds * dR * x->t + dt;
    return motion;
  }

  const std::vector<Eigen::Vector3f>& query_;
  const AlignmentTarget& target_;
  const AlignmentOptions& options_;
  const bool hold_height_;
  std::vector<Eigen::Vector3f> moved_;
  std::vector<int> nearest_;
  std::vector<int> hint_;  // per query point: its last nearest item point, -1 before the first
  std::vector<float> d2_;
  std::vector<int> order_;
  std::vector<std::uint64_t> keys_;
  std::size_t kept_ = 0;
  const NearestGrid* grid_ = nullptr;
  std::vector<std::uint32_t> range_begin_, range_end_;  // per subset point: its grid cell's candidates
  // The previous ICP round's correspondences and kept set (stop_when_correspondences_repeat).
  std::vector<int> last_nearest_;
  std::vector<char> last_in_kept_;
  std::size_t last_kept_ = 0;
};

// Convex hull of the points' xy (Andrew's monotone chain): rotating it gives the rotated query's
// footprint bounds without touching every point for every yaw.
std::vector<Eigen::Vector2d> FootprintHull(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector2d> p(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) p[i] = points[i].head<2>().cast<double>();
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0.0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

std::vector<int> StridedSubset(int n, int count) {
  if (count <= 0 || count > n) count = n;
  std::vector<int> subset;
  subset.reserve(count);
  for (int k = 0; k < count; ++k) subset.push_back(static_cast<int>((static_cast<long>(k) * n) / count));
  return subset;
}

Eigen::Affine3d AlignmentHypothesis::T_item_query() const {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.linear() = scale * Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = t;
  return T;
}

std::vector<AlignmentHypothesis> CoarseAlign(const std::vector<Eigen::Vector3f>& query_points,
                                             const AlignmentTarget& target, const AlignmentOptions& options,
                                             const AlignmentConstraints& constraints) {
  std::vector<AlignmentHypothesis> out;
  if (query_points.empty() || target.empty()) return out;
  const int n = static_cast<int>(query_points.size());
  const std::vector<int> initial = StridedSubset(n, options.initial_points);
  const std::vector<int> coarse = StridedSubset(n, options.coarse_points);

  Icp icp(query_points, target, options, constraints.floor_height_m.has_value());
  const float truncation_d2 = options.initial_truncation_m > 0.0
                                  ? static_cast<float>(options.initial_truncation_m * options.initial_truncation_m)
                                  : std::numeric_limits<float>::infinity();
  const DistanceGrid* grid = options.grid_initial_scoring && options.initial_truncation_m > 0.0
                                 ? target.distance_grid()
                                 : nullptr;
  const bool use_grid =
      grid != nullptr && !grid->empty() && options.initial_truncation_m <= grid->truncation_m() + 1e-6;
  const geometry::Aabb3& tb = target.bounds();
  double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (const auto& p : query_points) {
    z_lo = std::min(z_lo, static_cast<double>(p.z()));
    z_hi = std::max(z_hi, static_cast<double>(p.z()));
  }
  const std::vector<Eigen::Vector2d> hull = FootprintHull(query_points);
  std::vector<Hypothesis> hypotheses;
  for (int k = 0; k < options.yaw_steps; ++k) {
    Similarity4 x;
    x.yaw = 2.0 * M_PI * k / options.yaw_steps;
    const Eigen::Matrix3d R = x.R();
    geometry::Aabb3 qb;  // bounds of the rotated query: its footprint's hull rotated, its z range
    for (const auto& p : hull) qb.Extend(R * Eigen::Vector3d(p.x(), p.y(), z_lo));
    qb.Extend(Eigen::Vector3d(qb.min_m.x(), qb.min_m.y(), z_hi));
    // Translation candidates: footprint centres together, and (for partial views) each footprint side
    // flush with the item's; bottoms together in z, or the item's z = 0 on the floor the query stands on.
    std::vector<Eigen::Vector2d> xy;
    xy.emplace_back(tb.Center().head<2>() - qb.Center().head<2>());
    if (options.side_translation_inits) {
      const double cx = tb.Center().x() - qb.Center().x(), cy = tb.Center().y() - qb.Center().y();
      xy.emplace_back(tb.min_m.x() - qb.min_m.x(), cy);
      xy.emplace_back(tb.max_m.x() - qb.max_m.x(), cy);
      xy.emplace_back(cx, tb.min_m.y() - qb.min_m.y());
      xy.emplace_back(cx, tb.max_m.y() - qb.max_m.y());
    }
    for (const auto& t_xy : xy) {
      Hypothesis h;
      h.x = x;
      const double t_z = constraints.floor_height_m ? -*constraints.floor_height_m : tb.min_m.z() - qb.min_m.z();
      h.x.t = Eigen::Vector3d(t_xy.x(), t_xy.y(), t_z);
      h.cost = use_grid ? icp.GridCost(initial, h.x, truncation_d2) : icp.TruncatedCost(initial, h.x, truncation_d2);
      hypotheses.push_back(h);
    }
  }
  const auto by_cost = [](const Hypothesis& a, const Hypothesis& b) { return a.cost < b.cost; };
  std::stable_sort(hypotheses.begin(), hypotheses.end(), by_cost);
  if (static_cast<int>(hypotheses.size()) > options.coarse_keep) hypotheses.resize(options.coarse_keep);
  for (Hypothesis& h : hypotheses) icp.Run(coarse, options.coarse_iterations, &h);
  std::stable_sort(hypotheses.begin(), hypotheses.end(), by_cost);
  const int n_out = std::min<int>(options.refine_hypotheses, static_cast<int>(hypotheses.size()));
  for (int r = 0; r < n_out; ++r) {
    AlignmentHypothesis a;
    a.yaw_rad = hypotheses[r].x.yaw;
    a.scale = hypotheses[r].x.scale;
    a.t = hypotheses[r].x.t;
    a.cost_m2 = hypotheses[r].cost;
    out.push_back(a);
  }
  return out;
}

AlignmentResult RefineAlignment(const std::vector<Eigen::Vector3f>& query_points, const AlignmentTarget& target,
                                const std::vector<AlignmentHypothesis>& hypotheses, const AlignmentOptions& options,
                                const AlignmentConstraints& constraints) {
  AlignmentResult result;
  if (query_points.empty() || target.empty() || hypotheses.empty()) return result;
  const int n = static_cast<int>(query_points.size());
  const std::vector<int> refine = StridedSubset(n, options.refine_points);
  Icp icp(query_points, target, options, constraints.floor_height_m.has_value());
  Hypothesis best;
  for (const AlignmentHypothesis& a : hypotheses) {
    Hypothesis h;
    h.x.yaw = a.yaw_rad;
    h.x.scale = a.scale;
    h.x.t = a.t;
    icp.Run(refine, options.refine_iterations, &h);
    if (h.cost < best.cost) best = h;
  }
  result.status = AlignmentStatus::kOk;
  result.yaw_rad = std::remainder(best.x.yaw, 2.0 * M_PI);
  best.x.yaw = result.yaw_rad;
  result.scale = best.x.scale;
  result.T_item_query = best.x.Affine();
  double cost_all = 0.0;
  result.inlier_fraction = icp.InlierFraction(StridedSubset(n, 0), best.x, options.inlier_distance_m, &cost_all,
                                              &result.mean_squared_distance_m2);
  result.trimmed_rms_m = std::sqrt(cost_all);
  return result;
}

AlignmentResult AlignToItem(const std::vector<Eigen::Vector3f>& query_points, const AlignmentTarget& target,
                            const AlignmentOptions& options, const AlignmentConstraints& constraints) {
  return RefineAlignment(query_points, target, CoarseAlign(query_points, target, options, constraints), options,
                         constraints);
}

}  // namespace objscan::recognition
