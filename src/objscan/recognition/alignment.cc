#include "objscan/recognition/alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace objscan::recognition {

void AlignmentOptions::Validate() const {
  config::Require(yaw_steps >= 1, "recognition.alignment.yaw_steps", "must be at least 1");
  config::Require(coarse_points >= 3, "recognition.alignment.coarse_points", "must be at least 3");
  config::Require(coarse_keep >= 1, "recognition.alignment.coarse_keep", "must be at least 1");
  config::Require(coarse_iterations >= 0, "recognition.alignment.coarse_iterations", "must be >= 0");
  config::Require(refine_hypotheses >= 1, "recognition.alignment.refine_hypotheses", "must be at least 1");
  config::Require(refine_iterations >= 0, "recognition.alignment.refine_iterations", "must be >= 0");
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
  if (!item_points.empty()) centroid_ = sum / static_cast<double>(item_points.size());
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

struct Hypothesis {
  Similarity4 x;
  double cost = std::numeric_limits<double>::infinity();  // trimmed mean squared distance
};

class Icp {
 public:
  Icp(const std::vector<Eigen::Vector3f>& query, const AlignmentTarget& target, const AlignmentOptions& options)
      : query_(query), target_(target), options_(options) {
    moved_.resize(query.size());
    nearest_.resize(query.size());
    d2_.resize(query.size());
    order_.resize(query.size());
  }

  // Runs `iterations` trimmed ICP rounds on the points `subset` (indices into query), updating *h.
  void Run(const std::vector<int>& subset, int iterations, Hypothesis* h) {
    for (int it = 0; it <= iterations; ++it) {
      const double cost = Correspond(subset, h->x);
      h->cost = cost;
      if (it == iterations) break;
      const double moved = Solve(subset, &h->x);
      if (moved < options_.convergence_m) {
        h->cost = Correspond(subset, h->x);
        break;
      }
    }
  }

  // Share of the subset within `distance` of the item under x (call after Run / Correspond).
  double InlierFraction(const std::vector<int>& subset, const Similarity4& x, double distance) {
    Correspond(subset, x);
    const double d2max = distance * distance;
    int inliers = 0;
    for (std::size_t k = 0; k < subset.size(); ++k) inliers += d2_[k] <= d2max ? 1 : 0;
    return subset.empty() ? 0.0 : static_cast<double>(inliers) / subset.size();
  }

 private:
  // Transforms the subset, finds nearest item points, returns the trimmed mean squared distance and
  // leaves the kept correspondences as order_[0, kept_).
  double Correspond(const std::vector<int>& subset, const Similarity4& x) {
    const Eigen::Matrix3f M = (x.scale * x.R()).cast<float>();
    const Eigen::Vector3f t = x.t.cast<float>();
    const std::size_t n = subset.size();
    for (std::size_t k = 0; k < n; ++k) {
      moved_[k] = M * query_[subset[k]] + t;
      nearest_[k] = target_.tree().Nearest(moved_[k], &d2_[k]);
      order_[k] = static_cast<int>(k);
    }
    kept_ = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(options_.trim_fraction * n)));
    kept_ = std::min(kept_, n);
    std::nth_element(order_.begin(), order_.begin() + (kept_ - 1), order_.begin() + n,
                     [&](int a, int b) { return d2_[a] < d2_[b] || (d2_[a] == d2_[b] && a < b); });
    double sum = 0.0;
    for (std::size_t k = 0; k < kept_; ++k) sum += d2_[order_[k]];
    return kept_ > 0 ? sum / kept_ : std::numeric_limits<double>::infinity();
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
    const Eigen::Vector3d dt = b_mean - ds * dR * a_mean;
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
  std::vector<Eigen::Vector3f> moved_;
  std::vector<int> nearest_;
  std::vector<float> d2_;
  std::vector<int> order_;
  std::size_t kept_ = 0;
};

}  // namespace

AlignmentResult AlignToItem(const std::vector<Eigen::Vector3f>& query_points, const AlignmentTarget& target,
                            const AlignmentOptions& options) {
  AlignmentResult result;
  if (query_points.empty() || target.empty()) return result;
  const int n = static_cast<int>(query_points.size());

  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  std::vector<int> coarse;
  const int n_coarse = std::min(n, options.coarse_points);
  coarse.reserve(n_coarse);
  for (int k = 0; k < n_coarse; ++k) coarse.push_back(static_cast<int>((static_cast<long>(k) * n) / n_coarse));

  Icp icp(query_points, target, options);
  const geometry::Aabb3& tb = target.bounds();
  std::vector<Hypothesis> hypotheses;
  for (int k = 0; k < options.yaw_steps; ++k) {
    Similarity4 x;
    x.yaw = 2.0 * M_PI * k / options.yaw_steps;
    const Eigen::Matrix3d R = x.R();
    geometry::Aabb3 qb;  // bounds of the rotated query
    for (const auto& p : query_points) qb.Extend(R * p.cast<double>());
    // Translation candidates: footprint centres together, and (for partial views) each footprint side
    // flush with the item's; bottoms together in z.
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
      h.x.t = Eigen::Vector3d(t_xy.x(), t_xy.y(), tb.min_m.z() - qb.min_m.z());
      icp.Run(coarse, 0, &h);  // initial cost only
      hypotheses.push_back(h);
    }
  }
  const auto by_cost = [](const Hypothesis& a, const Hypothesis& b) { return a.cost < b.cost; };
  std::stable_sort(hypotheses.begin(), hypotheses.end(), by_cost);
  if (static_cast<int>(hypotheses.size()) > options.coarse_keep) hypotheses.resize(options.coarse_keep);
  for (Hypothesis& h : hypotheses) icp.Run(coarse, options.coarse_iterations, &h);
  std::stable_sort(hypotheses.begin(), hypotheses.end(), by_cost);

  Hypothesis best;
  const int n_refine = std::min<int>(options.refine_hypotheses, static_cast<int>(hypotheses.size()));
  for (int r = 0; r < n_refine; ++r) {
    Hypothesis h = hypotheses[r];
    icp.Run(all, options.refine_iterations, &h);
    if (h.cost < best.cost) best = h;
  }
  result.status = AlignmentStatus::kOk;
  result.yaw_rad = std::remainder(best.x.yaw, 2.0 * M_PI);
  best.x.yaw = result.yaw_rad;
  result.scale = best.x.scale;
  result.T_item_query = best.x.Affine();
  result.trimmed_rms_m = std::sqrt(best.cost);
  result.inlier_fraction = icp.InlierFraction(all, best.x, options.inlier_distance_m);
  return result;
}

}  // namespace objscan::recognition
