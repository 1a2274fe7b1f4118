#include "objscan/eval/observability.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "objscan/common/error.h"
#include "objscan/eval/exposure.h"
#include "objscan/common/parallel_for.h"
#include "objscan/render/raycaster.h"

namespace objscan::eval {
namespace {

void Validate(const ObservabilityOptions& o) {
  auto fail = [](const std::string& what) { throw InputError("ObservableVoxels: " + what); };
  if (!(o.min_range_m >= 0.0) || !(o.max_range_m > o.min_range_m)) fail("the range must be 0 <= min < max");
  if (!(o.max_incidence_deg > 0.0 && o.max_incidence_deg <= 90.0)) fail("max_incidence_deg must be in (0, 90]");
  if (std::isnan(o.min_camera_z_m) || std::isnan(o.max_camera_z_m) || o.min_camera_z_m > o.max_camera_z_m) {
    fail("the camera heights must be an interval");
  }
  if (!(o.own_surface_m >= 0.0) || !(o.own_surface_m < o.min_range_m)) fail("own_surface_m must be in [0, min_range_m)");
  if (o.num_directions < 16) fail("num_directions must be at least 16");
}

}  // namespace

void AddNormalLine(NormalLines* lines, const Eigen::Vector3f& normal, float area, double merge_deg,
                   std::size_t max_lines) {
  if (!(area > 0.f) || !normal.allFinite() || normal.squaredNorm() < 1e-12f) return;
  const Eigen::Vector3f n = normal.normalized();
  const float merge_cos = static_cast<float>(std::cos(merge_deg * M_PI / 180.0));
  int best = -1;
  float best_cos = -2.f;
  for (std::size_t i = 0; i < lines->size(); ++i) {
    const float c = (*lines)[i].normalized().dot(n);
    if (c > best_cos) {
      best_cos = c;
      best = static_cast<int>(i);
    }
  }
  if (best >= 0 && (best_cos >= merge_cos || lines->size() >= max_lines)) {
    (*lines)[best] += area * n;
    return;
  }
  lines->push_back(area * n);
}

std::vector<char> ObservableVoxels(const render::Raycaster& caster, const std::vector<Eigen::Vector3d>& centers_world,
                                   const std::vector<NormalLines>& normal_lines, const ObservabilityOptions& options,
                                   const RoomAir* camera_air) {
  Validate(options);
  if (centers_world.size() != normal_lines.size()) {
    throw InputError("ObservableVoxels: " + std::to_string(centers_world.size()) + " centres but " +
                     std::to_string(normal_lines.size()) + " normal line sets");
  }
  const std::vector<Eigen::Vector3f> sphere = render::FibonacciDirections(options.num_directions);
  const float min_cos = static_cast<float>(std::cos(options.max_incidence_deg * M_PI / 180.0));
  const double free_margin_m = 0.01;  // a camera is not on the surface it would stop at
  std::vector<char> observable(centers_world.size(), 0);

  auto observe = [&](std::size_t i) -> char {
    std::vector<Eigen::Vector3f> lines;
    for (const auto& l : normal_lines[i]) {
      if (l.allFinite() && l.squaredNorm() > 1e-20f) lines.push_back(l.normalized());
    }
    if (lines.empty()) return 1;
    // Directions within the dropout angle of a surface orientation, the most head-on first: an
    // observable voxel is usually settled by the first packet.
    std::vector<std::pair<float, int>> order;
    for (int d = 0; d < static_cast<int>(sphere.size()); ++d) {
      float best = 0.f;
      for (const auto& l : lines) best = std::max(best, l.dot(sphere[d]));
      if (best >= min_cos) order.emplace_back(-best, d);
    }
    std::sort(order.begin(), order.end());
    const Eigen::Vector3f origin = centers_world[i].cast<float>();
    constexpr std::size_t kPacket = 16;
    std::array<float, 3 * kPacket> directions;
    std::array<render::RayHit, kPacket> hits;
    for (std::size_t start = 0; start < order.size(); start += kPacket) {
      const std::size_t count = std::min(kPacket, order.size() - start);
      for (std::size_t k = 0; k < count; ++k) {
        const Eigen::Vector3f& d = sphere[order[start + k].second];
        directions[3 * k] = d.x();
        directions[3 * k + 1] = d.y();
        directions[3 * k + 2] = d.z();
      }
      caster.Cast(origin.data(), true, directions.data(), count, static_cast<float>(options.own_surface_m),
                  static_cast<float>(options.max_range_m), hits.data());
      for (std::size_t k = 0; k < count; ++k) {
        // A first hit on a back face: the ray ran inside a solid (into the voxel's own object).
        const Eigen::Vector3f d(directions[3 * k], directions[3 * k + 1], directions[3 * k + 2]);
        if (hits[k].Hit() && hits[k].normal_world.dot(d) > 0.f) continue;
        const double free_m = hits[k].Hit() ? hits[k].distance - free_margin_m : options.max_range_m;
        if (free_m < options.min_range_m) continue;
        // Heights along the free stretch [min_range, free] of the ray.
        const double end_m = std::min(free_m, options.max_range_m);
        const double dz = d.z();
        const double z0 = centers_world[i].z() + options.min_range_m * dz;
        const double z1 = centers_world[i].z() + end_m * dz;
        if (std::max(z0, z1) < options.min_camera_z_m || std::min(z0, z1) > options.max_camera_z_m) continue;
        if (!camera_air) return 1;
        // The stretch of the ray inside the band, then a camera position on it where the camera can
        // be, at voxel steps.
        double s0 = options.min_range_m, s1 = end_m;
        if (std::abs(dz) > 1e-9) {
          const double a = (options.min_camera_z_m - centers_world[i].z()) / dz;
          const double b = (options.max_camera_z_m - centers_world[i].z()) / dz;
          s0 = std::max(s0, std::min(a, b));
          s1 = std::min(s1, std::max(a, b));
        }
        for (double s = s0; s <= s1; s += camera_air->voxel_m()) {
          if (camera_air->CameraCanBeAt(centers_world[i] + s * d.cast<double>())) return 1;
        }
      }
    }
    return 0;
  };

  constexpr int kBlock = 256;
  const int blocks = static_cast<int>((centers_world.size() + kBlock - 1) / kBlock);
  ParallelForBlocks(blocks, options.threads, [&](int b) {
    const std::size_t end = std::min(centers_world.size(), static_cast<std::size_t>(b + 1) * kBlock);
    for (std::size_t i = static_cast<std::size_t>(b) * kBlock; i < end; ++i) observable[i] = observe(i);
  });
  return observable;
}

}  // namespace objscan::eval
