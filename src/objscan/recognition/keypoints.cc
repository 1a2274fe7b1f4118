#include "objscan/recognition/keypoints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_set>

#include "objscan/geometry/voxel_key.h"
#include "objscan/recognition/kd_tree.h"

namespace objscan::recognition {

void KeypointOptions::Validate() const {
  config::Require(num_keypoints >= 1, "recognition.keypoints.num_keypoints", "must be at least 1");
  config::Require(lloyd_iterations >= 0, "recognition.keypoints.lloyd_iterations", "must be >= 0");
  config::RequireNonNegative("recognition.keypoints.density_voxel_m", density_voxel_m);
  config::Require(max_relaxation_points >= num_keypoints, "recognition.keypoints.max_relaxation_points",
                  "must be >= num_keypoints");
}

std::vector<int> VoxelThin(const std::vector<Eigen::Vector3f>& points, double voxel_m) {
  std::vector<int> kept;
  kept.reserve(points.size());
  if (voxel_m <= 0.0) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  const float inv = static_cast<float>(1.0 / voxel_m);
  std::unordered_set<geometry::VoxelKey, geometry::VoxelKeyHash> seen;
  seen.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    if (seen.insert(geometry::KeyOf(points[i], inv)).second) kept.push_back(static_cast<int>(i));
  }
  return kept;
}

namespace {

constexpr int kNotFound = -2;
constexpr int kMaxShells = 6;

// Points in a dense grid of cells (empty when that would be too sparse), for nearest-point searches
// shell by shell around the query's cell.
class ShellGrid {
 public:
  ShellGrid(const std::vector<Eigen::Vector3f>& points, float cell_m) : points_(points), cell_m_(cell_m) {
    const int n = static_cast<int>(points.size());
    if (n == 0) return;
    const float inv = 1.f / cell_m;
    std::vector<geometry::VoxelKey> keys(n);
    lo_ = hi_ = geometry::KeyOf(points[0], inv);
    for (int i = 0; i < n; ++i) {
      keys[i] = geometry::KeyOf(points[i], inv);
      lo_ = {std::min(lo_.x, keys[i].x), std::min(lo_.y, keys[i].y), std::min(lo_.z, keys[i].z)};
      hi_ = {std::max(hi_.x, keys[i].x), std::max(hi_.y, keys[i].y), std::max(hi_.z, keys[i].z)};
    }
    nx_ = hi_.x - lo_.x + 1;
    ny_ = hi_.y - lo_.y + 1;
    nz_ = hi_.z - lo_.z + 1;
    const long cells = static_cast<long>(nx_) * ny_ * nz_;
    if (cells > 8L * n + 65536) return;  // too sparse: every search falls back
    start_.assign(cells + 1, 0);
    for (const auto& k : keys) ++start_[Linear(k.x, k.y, k.z) + 1];
    for (long c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    sorted_.resize(n);
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int i = 0; i < n; ++i) sorted_[fill[Linear(keys[i].x, keys[i].y, keys[i].z)]++] = i;
  }

  // The nearest point with !used[i]; kNotFound when none is certain within max_shells shells.
  int NearestUnused(const Eigen::Vector3f& q, const std::vector<char>& used, int max_shells) const {
    if (start_.empty()) return kNotFound;
    const geometry::VoxelKey c = geometry::KeyOf(q, 1.f / cell_m_);
    int best = -1;
    float best_d2 = std::numeric_limits<float>::infinity();
    for (int r = 0; r <= max_shells; ++r) {
      for (int x = c.x - r; x <= c.x + r; ++x) {
        if (x < lo_.x || x > hi_.x) continue;
        for (int y = c.y - r; y <= c.y + r; ++y) {
          if (y < lo_.y || y > hi_.y) continue;
          const bool x_or_y_on_shell = x == c.x - r || x == c.x + r || y == c.y - r || y == c.y + r;
          for (int z = c.z - r; z <= c.z + r; z += (x_or_y_on_shell || r == 0) ? 1 : 2 * r) {
            if (z < lo_.z || z > hi_.z) continue;
            const int cell = Linear(x, y, z);
            for (int s = start_[cell]; s < start_[cell + 1]; ++s) {
              const int i = sorted_[s];
              if (used[i]) continue;
              const float d2 = (points_[i] - q).squaredNorm();
              if (d2 < best_d2) {
                best_d2 = d2;
                best = i;
              }
            }
          }
        }
      }
      // Every point outside shells 0..r is at least r cells away from q.
      const float reach = r * cell_m_;
      if (best >= 0 && best_d2 < reach * reach) return best;
    }
    return kNotFound;
  }

 private:
  int Linear(int x, int y, int z) const { return ((x - lo_.x) * ny_ + (y - lo_.y)) * nz_ + (z - lo_.z); }

  const std::vector<Eigen::Vector3f>& points_;
  float cell_m_;
  geometry::VoxelKey lo_, hi_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<int> start_;
  std::vector<int> sorted_;
};

}  // namespace

std::vector<int> FarthestPointOrder(const std::vector<Eigen::Vector3f>& points, int count, int start) {
  const int n = static_cast<int>(points.size());
  std::vector<int> order;
  if (n == 0 || count <= 0) return order;
  order.reserve(static_cast<std::size_t>(count));
  // Coordinates as separate arrays so the distance update and the maximum vectorise; the first index
  // holding the maximum is the one a sequential scan picks.
  Eigen::ArrayXf xs(n), ys(n), zs(n);
  for (int i = 0; i < n; ++i) {
    xs[i] = points[i].x();
    ys[i] = points[i].y();
    zs[i] = points[i].z();
  }
  Eigen::ArrayXf d2 = Eigen::ArrayXf::Constant(n, std::numeric_limits<float>::infinity());
  int next = start;
  for (int k = 0; k < count; ++k) {
    order.push_back(next);
    const Eigen::Vector3f& p = points[next];
    // x^2 + (y^2 + z^2): the association of Vector3f::squaredNorm, so the choices match it bit for bit.
    d2 = d2.min((xs - p.x()).square() + ((ys - p.y()).square() + (zs - p.z()).square()));
    const float far_d2 = d2.maxCoeff();
    next = static_cast<int>(std::find(d2.data(), d2.data() + n, far_d2) - d2.data());
  }
  return order;
}

std::vector<int> SampleKeypointsLloyd(const std::vector<Eigen::Vector3f>& points, const KeypointOptions& options,
                                      Rng* rng) {
  std::vector<int> candidates = VoxelThin(points, options.density_voxel_m);
  const int n_keypoints = options.num_keypoints;
  if (static_cast<int>(candidates.size()) <= n_keypoints) return candidates;

  // Relaxation set: a seeded random subset when there are too many points (partial Fisher-Yates).
  std::vector<int> relax = candidates;
  if (static_cast<int>(relax.size()) > options.max_relaxation_points) {
    for (int i = 0; i < options.max_relaxation_points; ++i) {
      const int j = rng->UniformInt(i, static_cast<int>(relax.size()) - 1);
      std::swap(relax[i], relax[j]);
    }
    relax.resize(options.max_relaxation_points);
    std::sort(relax.begin(), relax.end());  // order independent of the shuffle's path
  }
  const int n = static_cast<int>(relax.size());
  std::vector<Eigen::Vector3f> pts(n);
  for (int i = 0; i < n; ++i) pts[i] = points[relax[i]];

  // Farthest-point initialisation from a seeded start.
  std::vector<Eigen::Vector3f> centres;
  centres.reserve(n_keypoints);
  for (int i : FarthestPointOrder(pts, n_keypoints, rng->UniformInt(0, n - 1))) centres.push_back(pts[i]);

  // Lloyd: assign every point to its nearest centre, move each centre to its cell's centroid.
  std::vector<Eigen::Vector3d> sums(n_keypoints);
  std::vector<int> counts(n_keypoints);
  KdTree3 centre_tree;
  std::vector<int> assignment(n, -1);
  for (int it = 0; it < options.lloyd_iterations; ++it) {
    centre_tree.Build(centres);
    std::fill(sums.begin(), sums.end(), Eigen::Vector3d::Zero());
    std::fill(counts.begin(), counts.end(), 0);
    for (int i = 0; i < n; ++i) {
      // Last round's centre (moved a little since) bounds the search; the result is still the exact
      // nearest, and a bound one ulp above its distance keeps ties resolved as an unbounded search does.
      int c = assignment[i];
      if (c < 0) {
        c = centre_tree.Nearest(pts[i], nullptr);
      } else {
        const float bound = std::nextafter((centres[c] - pts[i]).squaredNorm(), std::numeric_limits<float>::infinity());
        c = centre_tree.NearestBounded(pts[i], bound, c, nullptr);
      }
      assignment[i] = c;
      sums[c] += pts[i].cast<double>();
      ++counts[c];
    }
    for (int k = 0; k < n_keypoints; ++k) {
      if (counts[k] > 0) centres[k] = (sums[k] / counts[k]).cast<float>();
    }
  }

  // Snap each centre to the nearest unused candidate (of all thinned candidates), keeping them
  // distinct. A centre lies within a cell's width of the surface, so a search through shells of grid
  // cells around it ends after a few cells; a kd-tree (built only if needed) takes the rare centre
  // that is far from every candidate.
  std::vector<Eigen::Vector3f> candidate_points(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) candidate_points[i] = points[candidates[i]];
  const float cell_m = static_cast<float>(std::max(2.0 * options.density_voxel_m, 0.02));
  const ShellGrid grid(candidate_points, cell_m);
  KdTree3 point_tree;
  std::vector<char> used(candidates.size(), 0);
  std::vector<int> keypoints;
  keypoints.reserve(n_keypoints);
  std::vector<int> knn;
  for (int k = 0; k < n_keypoints; ++k) {
    int chosen = grid.NearestUnused(centres[k], used, kMaxShells);
    if (chosen == kNotFound) {
      if (point_tree.empty()) point_tree.Build(candidate_points);
      chosen = -1;
      for (int kk = 1; chosen < 0 && kk <= 4 * static_cast<int>(candidates.size()); kk *= 4) {
        point_tree.KNearest(centres[k], kk, &knn, nullptr);
        for (int idx : knn) {
          if (!used[idx]) {
            chosen = idx;
            break;
          }
        }
      }
    }
    if (chosen < 0) continue;
    used[chosen] = 1;
    keypoints.push_back(candidates[chosen]);
  }
  return keypoints;
}

}  // namespace objscan::recognition
