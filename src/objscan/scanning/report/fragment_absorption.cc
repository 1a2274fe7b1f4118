#include "objscan/scanning/report/fragment_absorption.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "objscan/geometry/aabb.h"
#include "objscan/recognition/kd_tree.h"

namespace objscan::scanning {
namespace {

std::size_t SizeOf(const FragmentCandidate& c) { return c.num_points > 0 ? c.num_points : c.points_world.size(); }

}  // namespace

std::vector<int> AbsorbExplainedFragments(const std::vector<FragmentCandidate>& objects,
                                          const FragmentAbsorptionOptions& options) {
  const int n = static_cast<int>(objects.size());
  std::vector<int> host(static_cast<std::size_t>(n));
  std::iota(host.begin(), host.end(), 0);
  std::vector<int> order(host);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return SizeOf(objects[a]) > SizeOf(objects[b]); });
  const float max_d2 = static_cast<float>(options.distance_m * options.distance_m);
  for (int h : order) {
    const FragmentCandidate& H = objects[h];
    if (host[h] != h || H.model_points.empty() ||
        H.objectness < options.min_host_objectness) {
      continue;
    }
    // The model's box in the model frame, grown by the distance: points outside it cannot lie on it.
    geometry::Aabb3 model_box;
    for (const auto& p : H.model_points) model_box.Extend(p.cast<double>());
    const geometry::Pose3 T_model_world = H.T_world_model.inverse();
    recognition::KdTree3 tree;  // over the model's points, built when a fragment first comes near
    for (int f : order) {
      const FragmentCandidate& F = objects[f];
      if (f == h || host[f] != f || !F.may_be_absorbed || F.points_world.empty()) continue;
      if (static_cast<double>(SizeOf(F)) > options.max_size_ratio * static_cast<double>(SizeOf(H))) continue;
      const std::size_t needed = static_cast<std::size_t>(
          std::ceil(options.min_explained_fraction * static_cast<double>(F.points_world.size())));
      std::size_t explained = 0, missed = 0;
      const std::size_t allowed_misses = F.points_world.size() - std::min(needed, F.points_world.size());
      for (const auto& p_world : F.points_world) {
        const Eigen::Vector3d p = T_model_world * p_world.cast<double>();
        bool on_surface = false;
        if (model_box.Contains(p, options.distance_m)) {
          if (tree.empty()) tree.Build(H.model_points);
          float d2 = 0.f;
          tree.Nearest(p.cast<float>(), &d2);
          on_surface = d2 <= max_d2;
        }
        if (on_surface) {
          ++explained;
        } else if (++missed > allowed_misses) {
          break;
        }
      }
      if (explained >= needed) host[f] = h;
    }
  }
  return host;
}

}  // namespace objscan::scanning
