#include "objscan/mapping/surface_map.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace objscan::mapping {

using geometry::VoxelKey;
using geometry::VoxelKeyHash;

void SurfaceMapOptions::Validate() const {
  config::RequireInRange("voxel_size_m", voxel_size_m, 0.001, 1.0);
  config::RequireNonNegative("association_base_m", association_base_m);
  config::RequireNonNegative("association_quadratic_per_m", association_quadratic_per_m);
  config::RequireInRange("association_max_normal_angle_deg", association_max_normal_angle_deg, 0.0, 180.0);
  config::RequireInRange("max_incidence_deg", max_incidence_deg, 0.0, 90.0);
  config::RequireInRange("pixel_stride", pixel_stride, 1, 64);
  normals.Validate();
}

SurfaceMap::SurfaceMap(const SurfaceMapOptions& options)
    : options_(options), inv_voxel_size_(static_cast<float>(1.0 / options.voxel_size_m)) {
  options_.Validate();
  RebuildIndex();
}

namespace {
// Arithmetic shifts floor negative coordinates, so blocks tile space without a seam at zero.
// Blocks of 4^3 voxels: a surface fills about a sixth of one, and a few percent of an 8^3 block (a
// house's map of 3.1M elements: 78 MB of voxel entries in 4^3 blocks, 160 MB in 8^3 ones, plus the
// copy when the array grows). Fusing a frame costs about 15% more (objscan_bench BM_FuseFrame*:
// more block lookups), under 1% of a run.
constexpr int kShift = 2;
constexpr std::int32_t kMask = (1 << kShift) - 1;
constexpr std::size_t kBlockVoxels = std::size_t{1} << (3 * kShift);
inline VoxelKey BlockOf(const VoxelKey& k) { return VoxelKey{k.x >> kShift, k.y >> kShift, k.z >> kShift}; }
// floor() without the library call (x is far inside the int range for any map).
inline std::int32_t FloorToInt(float x) {
  const std::int32_t i = static_cast<std::int32_t>(x);
  return i - (x < static_cast<float>(i) ? 1 : 0);
}
inline VoxelKey KeyOfPoint(const Eigen::Vector3f& p, float inv_voxel_size) {
  return VoxelKey{FloorToInt(p.x() * inv_voxel_size), FloorToInt(p.y() * inv_voxel_size),
                  FloorToInt(p.z() * inv_voxel_size)};
}
inline int LocalIndex(const VoxelKey& k) {
  return ((k.z & kMask) << (2 * kShift)) | ((k.y & kMask) << kShift) | (k.x & kMask);
}
}  // namespace

void SurfaceMap::RebuildIndex() {
  slots_.assign(1 << 12, Slot());
  slot_mask_ = slots_.size() - 1;
  num_blocks_ = 0;
  block_elements_.clear();
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const std::int32_t offset = FindOrAddBlock(BlockOf(keys_[i]));
    block_elements_[offset + LocalIndex(keys_[i])] = static_cast<std::int32_t>(i);
  }
}

std::int32_t SurfaceMap::FindBlock(const VoxelKey& block_key) const {
  std::size_t s = VoxelKeyHash()(block_key) & slot_mask_;
  while (true) {
    const Slot& slot = slots_[s];
    if (slot.offset < 0) return -1;
    if (slot.key == block_key) return slot.offset;
    s = (s + 1) & slot_mask_;
  }
}

void SurfaceMap::GrowBlockTable() {
  std::vector<Slot> old;
  old.swap(slots_);
  slots_.assign(2 * old.size(), Slot());
  slot_mask_ = slots_.size() - 1;
  const VoxelKeyHash hash;
  for (const Slot& o : old) {
    if (o.offset < 0) continue;
    std::size_t s = hash(o.key) & slot_mask_;
    while (slots_[s].offset >= 0) s = (s + 1) & slot_mask_;
    slots_[s] = o;
  }
}

std::int32_t SurfaceMap::FindOrAddBlock(const VoxelKey& block_key) {
  std::size_t s = VoxelKeyHash()(block_key) & slot_mask_;
  while (slots_[s].offset >= 0) {
    if (slots_[s].key == block_key) return slots_[s].offset;
    s = (s + 1) & slot_mask_;
  }
  if (2 * (num_blocks_ + 1) > slots_.size()) {
    GrowBlockTable();
    s = VoxelKeyHash()(block_key) & slot_mask_;
    while (slots_[s].offset >= 0) s = (s + 1) & slot_mask_;
  }
  const std::int32_t offset = static_cast<std::int32_t>(block_elements_.size());
  block_elements_.resize(block_elements_.size() + kBlockVoxels, -1);
  slots_[s].key = block_key;
  slots_[s].offset = offset;
  ++num_blocks_;
  return offset;
}

std::int32_t SurfaceMap::Find(const VoxelKey& key) const {
  const std::int32_t offset = FindBlock(BlockOf(key));
  return offset < 0 ? -1 : block_elements_[offset + LocalIndex(key)];
}

std::int32_t SurfaceMap::Insert(const VoxelKey& key) {
  const std::int32_t index = static_cast<std::int32_t>(keys_.size());
  block_elements_[FindOrAddBlock(BlockOf(key)) + LocalIndex(key)] = index;
  keys_.push_back(key);
  position_.emplace_back(Eigen::Vector3f::Zero());
  normal_sum_.emplace_back(Eigen::Vector3f::Zero());
  weight_.push_back(0.f);
  label_.push_back(0);
  label_confidence_.push_back(0.f);
  structure_.push_back(0);
  return index;
}

void SurfaceMap::Integrate(const platform::DepthFrame& frame, FrameAssociation* association) {
  if (frame.depth_m.size() != static_cast<std::size_t>(frame.width()) * frame.height()) {
    throw InputError("SurfaceMap::Integrate: depth_m has " + std::to_string(frame.depth_m.size()) +
                     " values for a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) +
                     " frame");
  }
  VertexNormalMap& vnm = association ? association->vertex_normals : scratch_vertex_normals_;
  ComputeVertexNormalMap(frame, options_.normals, &vnm);
  const int w = frame.width(), h = frame.height();
  if (association) {
    association->pixel_element.assign(static_cast<std::size_t>(w) * h, -1);
    association->num_fused = 0;
    association->num_created = 0;
  }

  const Eigen::Matrix3f R = frame.T_world_camera.rotation().cast<float>();
  const Eigen::Vector3f t = frame.T_world_camera.translation().cast<float>();
  const float voxel = static_cast<float>(options_.voxel_size_m);
  const float cos_incidence_min = static_cast<float>(std::cos(options_.max_incidence_deg * M_PI / 180.0));
  const float cos_assoc = static_cast<float>(std::cos(options_.association_max_normal_angle_deg * M_PI / 180.0));
  const float cos_assoc_sq = cos_assoc * cos_assoc;
  const float assoc_base = static_cast<float>(options_.association_base_m);
  const float assoc_quad = static_cast<float>(options_.association_quadratic_per_m);
  const platform::CameraIntrinsics& in = frame.intrinsics;
  const int stride = options_.pixel_stride;

  auto agrees = [&](std::int32_t idx, const Eigen::Vector3f& n) {
    const Eigen::Vector3f& ns = normal_sum_[idx];
    const float d = n.dot(ns);
    return d > 0.f && d * d >= cos_assoc_sq * ns.squaredNorm();
  };

  // Neighbouring pixels and the column search mostly stay in one block: remember the last one.
  std::int32_t cached_bx = INT32_MIN, cached_by = 0, cached_bz = 0;
  std::int32_t cached_offset = -1;
  auto find = [&](const VoxelKey& key) {
    const std::int32_t bx = key.x >> kShift, by = key.y >> kShift, bz = key.z >> kShift;
    if (bx != cached_bx || by != cached_by || bz != cached_bz) {
      cached_bx = bx;
      cached_by = by;
      cached_bz = bz;
      cached_offset = FindBlock(VoxelKey{bx, by, bz});
    }
    return cached_offset < 0 ? -1 : block_elements_[cached_offset + LocalIndex(key)];
  };

  ray_x_.resize(w);
  for (int u = 0; u < w; ++u) ray_x_[u] = static_cast<float>((u - in.cx_px) / in.fx_px);

  std::size_t fused = 0, created = 0;
  for (int v = 0; v < h; v += stride) {
    const float ray_y = static_cast<float>((v - in.cy_px) / in.fy_px);
    for (int u = 0; u < w; u += stride) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      if (!vnm.valid[i]) continue;
      const float z = frame.depth_m[i];
      const Eigen::Vector3f p_camera(ray_x_[u] * z, ray_y * z, z);
      const Eigen::Vector3f& n_camera = vnm.normal_camera[i];
      const float cos_incidence = -n_camera.dot(p_camera) / p_camera.norm();
      if (cos_incidence < cos_incidence_min) continue;
      const float zc = z < 1.f ? 1.f : z;
      const float weight = cos_incidence / (zc * zc);
      const Eigen::Vector3f p = R * p_camera + t;
      const Eigen::Vector3f n = R * n_camera;

      const VoxelKey key = KeyOfPoint(p, inv_voxel_size_);
      std::int32_t idx = find(key);
      bool own_voxel_taken = idx >= 0;
      if (idx >= 0 && !agrees(idx, n)) idx = -1;
      if (idx < 0) {
        // Search the voxel column along the normal's dominant axis: a surface voxelised that way
        // has one voxel per column, so this finds the element this surface already has. Elements
        // stay filed under the voxel of their first point while their mean converges, so search
        // twice the association distance and accept by the distance to the mean.
        const float assoc_m = assoc_base + assoc_quad * z * z;
        const int steps = 2 * static_cast<int>(std::ceil(assoc_m * inv_voxel_size_));
        int axis;
        n.cwiseAbs().maxCoeff(&axis);
        float best_dist = assoc_m;
        // One side of the column, then the other: consecutive probes stay in one cached block.
        for (int sign = -1; sign <= 1; sign += 2) {
          for (int s = 1; s <= steps; ++s) {
            VoxelKey k = key;
            (axis == 0 ? k.x : axis == 1 ? k.y : k.z) += sign * s;
            const std::int32_t j = find(k);
            if (j >= 0 && agrees(j, n)) {
              const float dist = std::fabs((position_[j] - p).dot(n));
              if (dist <= best_dist) {
                best_dist = dist;
                idx = j;
              }
            }
          }
        }
      }
      if (idx < 0) {
        VoxelKey k = key;
        if (own_voxel_taken) {
          // Another surface (e.g. the back of a thin board) owns this voxel: use the one in front.
          k = KeyOfPoint(p + (0.75f * voxel) * n, inv_voxel_size_);
          if (find(k) >= 0) continue;
        }
        idx = Insert(k);
        cached_bx = INT32_MIN;  // Insert may have added a block or moved block_elements_
        ++created;
      }
      // Running weighted mean.
      const float w_old = weight_[idx];
      const float w_new = w_old + weight;
      position_[idx] += (p - position_[idx]) * (weight / w_new);
      normal_sum_[idx] += weight * n;
      weight_[idx] = w_new;
      MarkDirty(label_[idx]);
      if (association) association->pixel_element[i] = idx;
      ++fused;
    }
  }
  if (association) {
    association->num_fused = fused;
    association->num_created = created;
  }
}

void SurfaceMap::SetLabel(std::size_t i, std::int32_t label, float confidence) {
  if (label_[i] != label) {
    MarkDirty(label_[i]);
    MarkDirty(label);
  }
  label_[i] = label;
  label_confidence_[i] = confidence;
}

void SurfaceMap::VoteLabel(std::size_t i, std::int32_t label, float weight) {
  if (label_[i] == label) {
    label_confidence_[i] += weight;
    return;
  }
  if (label_[i] == 0) {
    label_[i] = label;
    label_confidence_[i] = weight;
    MarkDirty(label);
    return;
  }
  label_confidence_[i] -= weight;
  if (label_confidence_[i] < 0.f) {
    MarkDirty(label_[i]);
    MarkDirty(label);
    label_[i] = label;
    label_confidence_[i] = -label_confidence_[i];
  }
}

void SurfaceMap::RelabelAll(const std::vector<std::int32_t>& from, std::int32_t to) {
  if (from.empty()) return;
  std::int32_t max_label = std::max(to, from.back());
  std::vector<std::uint8_t> is_from(static_cast<std::size_t>(max_label) + 1, 0);
  for (std::int32_t l : from) {
    if (l > 0) is_from[l] = 1;
  }
  for (std::size_t i = 0; i < label_.size(); ++i) {
    const std::int32_t l = label_[i];
    if (l > 0 && l <= max_label && is_from[l]) label_[i] = to;
  }
  for (std::int32_t l : from) MarkDirty(l);
  MarkDirty(to);
}

void SurfaceMap::SetStructure(std::size_t i, Structure s) {
  if (structure_[i] != static_cast<std::uint8_t>(s)) {
    structure_[i] = static_cast<std::uint8_t>(s);
    MarkDirty(label_[i]);
  }
}

namespace {
std::vector<std::uint8_t> LabelMask(const std::vector<std::int32_t>& labels) {
  std::int32_t max_label = 0;
  for (std::int32_t l : labels) max_label = std::max(max_label, l);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(max_label) + 1, 0);
  for (std::int32_t l : labels) {
    if (l > 0) mask[l] = 1;
  }
  return mask;
}
}  // namespace

geometry::PointCloud SurfaceMap::Cloud(std::int32_t label) const {
  return Cloud(std::vector<std::int32_t>{label});
}

geometry::PointCloud SurfaceMap::Cloud(const std::vector<std::int32_t>& labels) const {
  const std::vector<std::uint8_t> mask = LabelMask(labels);
  geometry::PointCloud cloud;
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const std::int32_t l = label_[i];
    if (l <= 0 || static_cast<std::size_t>(l) >= mask.size() || !mask[l] || structure_[i] != 0) continue;
    cloud.points.push_back(position_[i]);
    cloud.normals.push_back(normal(i));
    cloud.labels.push_back(l);
  }
  return cloud;
}

geometry::PointCloud SurfaceMap::AllPoints() const {
  geometry::PointCloud cloud;
  cloud.points = position_;
  cloud.normals.resize(keys_.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) cloud.normals[i] = normal(i);
  cloud.labels = label_;
  return cloud;
}

std::vector<std::int32_t> SurfaceMap::Labels() const {
  std::vector<std::uint8_t> seen;
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const std::int32_t l = label_[i];
    if (l <= 0 || structure_[i] != 0) continue;
    if (static_cast<std::size_t>(l) >= seen.size()) seen.resize(2 * l + 16, 0);
    if (!seen[l]) {
      seen[l] = 1;
      out.push_back(l);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::int32_t> SurfaceMap::TakeDirtyLabels() {
  std::vector<std::int32_t> out;
  out.swap(dirty_labels_);
  for (std::int32_t l : out) dirty_flag_[l] = 0;
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t SurfaceMap::Remove(const std::vector<std::int32_t>& labels) {
  const std::vector<std::uint8_t> mask = LabelMask(labels);
  std::size_t out = 0;
  const std::size_t n = keys_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t l = label_[i];
    if (l > 0 && static_cast<std::size_t>(l) < mask.size() && mask[l]) continue;
    if (out != i) {
      keys_[out] = keys_[i];
      position_[out] = position_[i];
      normal_sum_[out] = normal_sum_[i];
      weight_[out] = weight_[i];
      label_[out] = label_[i];
      label_confidence_[out] = label_confidence_[i];
      structure_[out] = structure_[i];
    }
    ++out;
  }
  const std::size_t removed = n - out;
  keys_.resize(out);
  position_.resize(out);
  normal_sum_.resize(out);
  weight_.resize(out);
  label_.resize(out);
  label_confidence_.resize(out);
  structure_.resize(out);
  RebuildIndex();
  for (std::int32_t l : labels) MarkDirty(l);
  return removed;
}

geometry::Aabb3 SurfaceMap::Bounds() const {
  geometry::Aabb3 box;
  for (const auto& p : position_) box.Extend(p.cast<double>());
  return box;
}

}  // namespace objscan::mapping
