#include "objscan/recognition/fpfh_descriptor.h"

#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "objscan/geometry/voxel_key.h"
#include "objscan/recognition/keypoints.h"

// PCL objects made here are allocated partly inside libpcl_* and freed here, or the other way round,
// through Eigen's aligned allocator: both sides must pick the same one. Debian's PCL is built for
// baseline x86-64 (no AVX in libpcl_features: 16-byte Eigen alignment), so its Eigen allocates with
// plain malloc. So must ours: -march=native (AVX, 32 bytes) would switch Eigen to its
// handmade_aligned_malloc, and so does gcc's -fsanitize=address unless EIGEN_MALLOC_ALREADY_ALIGNED=1
// is defined (CMakeLists.txt does for OBJSCAN_SANITIZE); freeing PCL's blocks with
// handmade_aligned_free corrupts the heap (ASan's heap-buffer-overflow in MatchesPclFpfhEstimation).
static_assert(EIGEN_DEFAULT_ALIGN_BYTES == 16 && EIGEN_MALLOC_ALREADY_ALIGNED == 1,
              "objscan must use the Eigen allocator Debian's PCL uses (16-byte alignment, malloc): "
              "build without -march=native / AVX flags (and, with gcc's -fsanitize=address, with "
              "EIGEN_MALLOC_ALREADY_ALIGNED=1)");

namespace objscan::recognition {

void DescriptorOptions::Validate() const {
  config::Require(type == "fpfh", "recognition.descriptor.type", "must be fpfh (got '" + type + "')");
  config::RequirePositive("recognition.descriptor.support_radius_m", support_radius_m);
  config::RequirePositive("recognition.descriptor.normal_radius_m", normal_radius_m);
  config::RequireNonNegative("recognition.descriptor.surface_voxel_m", surface_voxel_m);
}

std::unique_ptr<DescriptorExtractor> MakeDescriptorExtractor(const DescriptorOptions& options) {
  options.Validate();
  return std::make_unique<FpfhDescriptor>(options);
}

namespace {

// The thinned surface with PCA normals oriented to the sensor side (or away from the centroid),
// points without a usable normal dropped.
struct OrientedSurface {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
  pcl::PointCloud<pcl::Normal>::Ptr normals{new pcl::PointCloud<pcl::Normal>};
};

constexpr int kBins = 11;  // per feature; FpfhDescriptor::kDimension = 3 * kBins

// Fixed-radius neighbours through a grid with cells of the radius (27 cells per query): a dense
// array of cell ranges over the points' bounds, or a hash map when that would be mostly empty.
class RadiusGrid {
 public:
  RadiusGrid(const std::vector<Eigen::Vector3f>& points, float radius)
      : points_(points), radius2_(radius * radius), inv_(1.f / radius) {
    const int n = static_cast<int>(points.size());
    std::vector<geometry::VoxelKey> keys(n);
    for (int i = 0; i < n; ++i) {
      keys[i] = geometry::KeyOf(points[i], inv_);
      if (i == 0) lo_ = hi_ = keys[i];
      lo_ = {std::min(lo_.x, keys[i].x), std::min(lo_.y, keys[i].y), std::min(lo_.z, keys[i].z)};
      hi_ = {std::max(hi_.x, keys[i].x), std::max(hi_.y, keys[i].y), std::max(hi_.z, keys[i].z)};
    }
    const long cells = n == 0 ? 0
                              : static_cast<long>(hi_.x - lo_.x + 1) * (hi_.y - lo_.y + 1) * (hi_.z - lo_.z + 1);
    dense_ = n > 0 && cells <= 8L * n + 65536;
    if (dense_) {
      // Counting sort by cell, stable in the point index: cells in (x, y, z) order, each ascending.
      ny_ = hi_.y - lo_.y + 1;
      nz_ = hi_.z - lo_.z + 1;
      start_.assign(cells + 1, 0);
      std::vector<int> cell_of(n);
      for (int i = 0; i < n; ++i) {
        cell_of[i] = Linear(keys[i]);
        ++start_[cell_of[i] + 1];
      }
      for (long c = 0; c < cells; ++c) start_[c + 1] += start_[c];
      sorted_.resize(n);
      std::vector<int> fill(start_.begin(), start_.end() - 1);
      for (int i = 0; i < n; ++i) sorted_[fill[cell_of[i]]++] = i;
      return;
    }
    std::vector<std::pair<geometry::VoxelKey, int>> keyed(n);
    for (int i = 0; i < n; ++i) keyed[i] = {keys[i], i};
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
      return std::tie(a.first.x, a.first.y, a.first.z, a.second) < std::tie(b.first.x, b.first.y, b.first.z, b.second);
    });
    sorted_.reserve(n);
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      if (i == 0 || !(keyed[i].first == keyed[i - 1].first)) cells_[keyed[i].first] = {static_cast<int>(i), 0};
      ++cells_[keyed[i].first].second;
      sorted_.push_back(keyed[i].second);
    }
  }

  // Indices and squared distances of the points with d^2 < radius^2, cell by cell.
  void Query(const Eigen::Vector3f& q, std::vector<int>* indices, std::vector<float>* d2) const {
    indices->clear();
    d2->clear();
    const geometry::VoxelKey c = geometry::KeyOf(q, inv_);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const geometry::VoxelKey k{c.x + dx, c.y + dy, c.z + dz};
          int begin = 0, end = 0;
          if (dense_) {
            if (k.x < lo_.x || k.y < lo_.y || k.z < lo_.z || k.x > hi_.x || k.y > hi_.y || k.z > hi_.z) continue;
            const int cell = Linear(k);
            begin = start_[cell];
            end = start_[cell + 1];
          } else {
            const auto it = cells_.find(k);
            if (it == cells_.end()) continue;
            begin = it->second.first;
            end = begin + it->second.second;
          }
          for (int s = begin; s < end; ++s) {
            const int i = sorted_[s];
            const float d = (points_[i] - q).squaredNorm();
            if (d < radius2_) {
              indices->push_back(i);
              d2->push_back(d);
            }
          }
        }
      }
    }
  }

 private:
  int Linear(const geometry::VoxelKey& k) const { return ((k.x - lo_.x) * ny_ + (k.y - lo_.y)) * nz_ + (k.z - lo_.z); }

  const std::vector<Eigen::Vector3f>& points_;
  float radius2_, inv_;
  std::vector<int> sorted_;
  bool dense_ = false;
  geometry::VoxelKey lo_, hi_;
  int ny_ = 0, nz_ = 0;
  std::vector<int> start_;  // dense: cell c holds sorted_[start_[c], start_[c + 1])
  std::unordered_map<geometry::VoxelKey, std::pair<int, int>, geometry::VoxelKeyHash> cells_;
};

OrientedSurface PrepareSurface(const geometry::PointCloud& surface, const DescriptorOptions& options) {
  const std::vector<int> kept = VoxelThin(surface.points, options.surface_voxel_m);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(kept.size());
  for (int i : kept) {
    const auto& p = surface.points[i];
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  // Normals are always re-estimated by PCA over normal_radius_m of the thinned surface: a single noisy
  // view and a fused clean scan then get equally smooth normals (per-pixel map normals of one noisy
  // frame would make the same shape look different). Given normals only decide the orientation.
  // PCL's NormalEstimation step by step (its covariance and plane fit over the neighbours sorted by
  // distance, flipped towards the origin), with the neighbours from a radius grid instead of FLANN.
  std::vector<Eigen::Vector3f> pts(cloud->size());
  for (std::size_t i = 0; i < cloud->size(); ++i) pts[i] = (*cloud)[i].getVector3fMap();
  const RadiusGrid grid(pts, static_cast<float>(options.normal_radius_m));
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  normals->resize(cloud->size());
  std::vector<int> nbrs;
  std::vector<float> nbr_d2;
  std::vector<std::pair<float, int>> sorted;
  pcl::Indices indices;
  Eigen::Matrix3f covariance;
  Eigen::Vector4f centroid4;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    pcl::Normal& n = (*normals)[i];
    const float nan = std::numeric_limits<float>::quiet_NaN();
    n.normal_x = n.normal_y = n.normal_z = n.curvature = nan;
    grid.Query(pts[i], &nbrs, &nbr_d2);
    if (nbrs.size() < 3) continue;
    sorted.resize(nbrs.size());
    for (std::size_t k = 0; k < nbrs.size(); ++k) sorted[k] = {nbr_d2[k], nbrs[k]};
    std::sort(sorted.begin(), sorted.end());
    indices.resize(sorted.size());
    for (std::size_t k = 0; k < sorted.size(); ++k) indices[k] = sorted[k].second;
    if (pcl::computeMeanAndCovarianceMatrix(*cloud, indices, covariance, centroid4) == 0) continue;
    pcl::solvePlaneParameters(covariance, n.normal_x, n.normal_y, n.normal_z, n.curvature);
    pcl::flipNormalTowardsViewpoint((*cloud)[i], 0.f, 0.f, 0.f, n.normal_x, n.normal_y, n.normal_z);
  }
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : *cloud) centroid += p.getVector3fMap();
  centroid /= static_cast<float>(cloud->size());
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    Eigen::Map<Eigen::Vector3f> n = (*normals)[i].getNormalVector3fMap();
    // Orientation: towards the sensor side when the surface has normals, else away from the centroid.
    const Eigen::Vector3f reference = surface.HasNormals() ? surface.normals[kept[i]]
                                                           : Eigen::Vector3f((*cloud)[i].getVector3fMap() - centroid);
    if (n.dot(reference) < 0.f) n = -n;
  }
  // Drop surface points without a usable normal (isolated points).
  OrientedSurface out;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const auto n = (*normals)[i].getNormalVector3fMap();
    if (!n.allFinite() || n.squaredNorm() < 0.25f) continue;
    out.cloud->push_back((*cloud)[i]);
    out.normals->push_back((*normals)[i]);
  }
  return out;
}

// PCL's pair features of (p1, n1) and (p2, n2) (Rusu et al.): the Darboux frame on the point whose
// normal makes the smaller angle with the connecting line. False for coincident or degenerate pairs.
// *symmetric tells whether (p2, n2, p1, n1) gives bit for bit the same features (whenever the choice
// of the frame's point is strict): then one evaluation serves both points' histograms.
bool PairFeatures(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                  const Eigen::Vector3f& n2, float* f1, float* f2, float* f3, bool* symmetric) {
  Eigen::Vector3f d = p2 - p1;
  const float f4 = d.norm();
  *symmetric = true;
  if (f4 == 0.f) return false;
  const float angle1 = n1.dot(d) / f4, angle2 = n2.dot(d) / f4;
  *symmetric = std::abs(angle1) <= 1.f && std::abs(angle2) <= 1.f && std::abs(angle1) != std::abs(angle2);
  const Eigen::Vector3f* u = &n1;
  const Eigen::Vector3f* other = &n2;
  // acos(|angle1|) > acos(|angle2|), without the acos (NaN beyond 1 compares false, as there).
  if (std::abs(angle1) <= 1.f && std::abs(angle2) <= 1.f && std::abs(angle1) < std::abs(angle2)) {
    u = &n2;
    other = &n1;
    d = -d;
    *f3 = -angle2;
  } else {
    *f3 = angle1;
  }
  Eigen::Vector3f v = d.cross(*u);
  const float v_norm = v.norm();
  if (v_norm == 0.f) return false;
  v /= v_norm;
  const Eigen::Vector3f w = u->cross(v);
  *f2 = v.dot(*other);
  *f1 = std::atan2(w.dot(*other), u->dot(*other));
  return true;
}

// The symmetry test of PairFeatures alone (the same answer from either end of the pair).
bool PairIsSymmetric(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                     const Eigen::Vector3f& n2) {
  const Eigen::Vector3f d = p2 - p1;
  const float f4 = d.norm();
  if (f4 == 0.f) return true;
  const float angle1 = n1.dot(d) / f4, angle2 = n2.dot(d) / f4;
  return std::abs(angle1) <= 1.f && std::abs(angle2) <= 1.f && std::abs(angle1) != std::abs(angle2);
}

int Bin(double normalised) {
  return std::clamp(static_cast<int>(std::floor(kBins * normalised)), 0, kBins - 1);
}

}  // namespace

void FpfhDescriptor::Compute(const geometry::PointCloud& surface, const std::vector<Eigen::Vector3f>& keypoints,
                             std::vector<float>* descriptors) const {
  descriptors->assign(keypoints.size() * kDimension, 0.f);
  if (keypoints.empty() || surface.empty()) return;
  const OrientedSurface s = PrepareSurface(surface, options_);
  if (s.cloud->size() < 3) return;
  const int n = static_cast<int>(s.cloud->size());
  std::vector<Eigen::Vector3f> pts(n), nrm(n);
  for (int i = 0; i < n; ++i) {
    pts[i] = (*s.cloud)[i].getVector3fMap();
    nrm[i] = (*s.normals)[i].getNormalVector3fMap();
  }
  const RadiusGrid grid(pts, static_cast<float>(options_.support_radius_m));

  // Keypoint neighbourhoods, and which surface points need a simplified histogram (SPFH).
  std::vector<std::vector<int>> key_nbrs(keypoints.size());
  std::vector<std::vector<float>> key_d2(keypoints.size());
  std::vector<char> needed(n, 0);
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    grid.Query(keypoints[k], &key_nbrs[k], &key_d2[k]);
    for (int i : key_nbrs[k]) needed[i] = 1;
  }
  // SPFH of each needed point over its own neighbourhood: 3 x 11 bins, each feature summing to 100.
  // A pair's features are symmetric (almost always), so each is evaluated once for both points and
  // counted per bin; the bins are then summed increment by increment, as a direct loop would.
  std::vector<int> counts(static_cast<std::size_t>(n) * kDimension, 0);
  std::vector<int> nbr_count(n, 0);
  std::vector<int> nbrs;
  std::vector<float> nbr_d2;
  // In float, as PCL has it, so bin edges fall where they fall there.
  const float kInvTwoPi = 1.0f / (2.0f * static_cast<float>(M_PI));
  const auto count = [&](int point, float f1, float f2, float f3) {
    int* c = &counts[static_cast<std::size_t>(point) * kDimension];
    ++c[Bin((f1 + M_PI) * kInvTwoPi)];
    ++c[kBins + Bin((f2 + 1.0) * 0.5)];
    ++c[2 * kBins + Bin((f3 + 1.0) * 0.5)];
  };
  for (int p = 0; p < n; ++p) {
    if (!needed[p]) continue;
    grid.Query(pts[p], &nbrs, &nbr_d2);
    nbr_count[p] = static_cast<int>(nbrs.size());
    if (nbrs.size() < 2) continue;
    for (int q : nbrs) {
      if (q == p) continue;
      // An earlier needed point already counted a symmetric pair for both.
      if (q < p && needed[q] && PairIsSymmetric(pts[p], nrm[p], pts[q], nrm[q])) continue;
      float f1, f2, f3;
      bool symmetric = false;
      if (!PairFeatures(pts[p], nrm[p], pts[q], nrm[q], &f1, &f2, &f3, &symmetric)) continue;
      count(p, f1, f2, f3);
      if (q > p && needed[q] && symmetric) count(q, f1, f2, f3);
    }
  }
  std::vector<float> spfh(static_cast<std::size_t>(n) * kDimension, 0.f);
  for (int p = 0; p < n; ++p) {
    if (!needed[p] || nbr_count[p] < 2) continue;
    const float increment = 100.f / static_cast<float>(nbr_count[p] - 1);
    const int* c = &counts[static_cast<std::size_t>(p) * kDimension];
    float* h = &spfh[static_cast<std::size_t>(p) * kDimension];
    for (int b = 0; b < kDimension; ++b) {
      for (int k = 0; k < c[b]; ++k) h[b] += increment;
    }
  }
  // FPFH of each keypoint: its neighbours' SPFH weighted by 1/d^2, each feature rescaled to sum 100.
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    if (key_nbrs[k].empty()) continue;  // no support: all-zero row
    float hist[kDimension] = {};
    // Three register accumulators (one per feature, each summed in the same order as bin by bin).
    double sum0 = 0.0, sum1 = 0.0, sum2 = 0.0;
    for (std::size_t j = 0; j < key_nbrs[k].size(); ++j) {
      if (key_d2[k][j] == 0.f) continue;
      const float weight = 1.f / key_d2[k][j];
      const float* h = &spfh[static_cast<std::size_t>(key_nbrs[k][j]) * kDimension];
      for (int b = 0; b < kBins; ++b) {
        const float v0 = h[b] * weight, v1 = h[kBins + b] * weight, v2 = h[2 * kBins + b] * weight;
        hist[b] += v0;
        hist[kBins + b] += v1;
        hist[2 * kBins + b] += v2;
        sum0 += v0;
        sum1 += v1;
        sum2 += v2;
      }
    }
    const double sum[3] = {sum0, sum1, sum2};
    float* out = descriptors->data() + k * kDimension;
    for (int b = 0; b < kDimension; ++b) {
      const double total = sum[b / kBins];
      out[b] = total != 0.0 ? static_cast<float>(hist[b] * (100.0 / total)) : hist[b];
    }
  }
}

void FpfhDescriptor::ComputeWithPcl(const geometry::PointCloud& surface, const std::vector<Eigen::Vector3f>& keypoints,
                                    std::vector<float>* descriptors) const {
  descriptors->assign(keypoints.size() * kDimension, 0.f);
  if (keypoints.empty() || surface.empty()) return;
  const OrientedSurface s = PrepareSurface(surface, options_);
  if (s.cloud->size() < 3) return;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::PointCloud<pcl::PointXYZ>::Ptr keypoint_cloud(new pcl::PointCloud<pcl::PointXYZ>);
  keypoint_cloud->reserve(keypoints.size());
  for (const auto& k : keypoints) keypoint_cloud->push_back(pcl::PointXYZ(k.x(), k.y(), k.z()));

  pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
  fpfh.setInputCloud(keypoint_cloud);
  fpfh.setSearchSurface(s.cloud);
  fpfh.setInputNormals(s.normals);
  fpfh.setSearchMethod(tree);
  fpfh.setRadiusSearch(options_.support_radius_m);
  pcl::PointCloud<pcl::FPFHSignature33> features;
  fpfh.compute(features);
  for (std::size_t i = 0; i < features.size() && i < keypoints.size(); ++i) {
    const float* h = features[i].histogram;
    bool finite = true;
    for (int b = 0; b < kDimension; ++b) finite = finite && std::isfinite(h[b]);
    if (!finite) continue;
    std::copy(h, h + kDimension, descriptors->begin() + i * kDimension);
  }
}

}  // namespace objscan::recognition
