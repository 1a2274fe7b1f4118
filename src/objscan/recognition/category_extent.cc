#include "objscan/recognition/category_extent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "objscan/common/trimmed_range.h"
#include "objscan/recognition/model_database.h"

namespace objscan::recognition {

ObjectExtent MeasureExtent(const std::vector<Eigen::Vector3f>& points, int yaw_steps, double trim_fraction) {
  ObjectExtent e;
  if (points.empty()) return e;
  yaw_steps = std::max(1, yaw_steps);
  const double trim = std::isfinite(trim_fraction) ? std::clamp(trim_fraction, 0.0, 0.49) : 0.0;
  const std::size_t k = static_cast<std::size_t>(trim * static_cast<double>(points.size()));
  std::vector<float> a(points.size()), b(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) a[i] = points[i].z();
  const auto z = TrimmedRange(&a, k);
  e.height_m = static_cast<double>(z.second - z.first);
  // A rectangle rotated by yaw and by yaw + 90° is the same one, so yaw in [0, 90°) covers all.
  double best = std::numeric_limits<double>::infinity();
  const double kPi = 3.14159265358979323846;
  for (int s = 0; s < yaw_steps; ++s) {
    const double yaw = 0.5 * kPi * s / yaw_steps;
    const float c = static_cast<float>(std::cos(yaw)), sn = static_cast<float>(std::sin(yaw));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3f& p = points[i];
      a[i] = c * p.x() + sn * p.y();
      b[i] = -sn * p.x() + c * p.y();
    }
    const auto u = TrimmedRange(&a, k);
    const auto v = TrimmedRange(&b, k);
    best = std::min(best, std::hypot(static_cast<double>(u.second - u.first), static_cast<double>(v.second - v.first)));
  }
  e.footprint_diagonal_m = best;
  return e;
}

ObjectExtent MeasureObjectExtent(const std::vector<Eigen::Vector3f>& points, const SizePlausibilityOptions& options) {
  return MeasureExtent(points, 16, options.extent_trim_fraction);
}

void CategoryExtents::Add(world::Category category, const ObjectExtent& extent) {
  const int id = world::CategoryId(category);
  if (id < 0 || id >= world::kNumObjectCategories) return;
  ExtentRange& r = ranges_[static_cast<std::size_t>(id)];
  if (r.num_models == 0) {
    r.min = r.max = extent;
  } else {
    r.min.height_m = std::min(r.min.height_m, extent.height_m);
    r.min.footprint_diagonal_m = std::min(r.min.footprint_diagonal_m, extent.footprint_diagonal_m);
    r.max.height_m = std::max(r.max.height_m, extent.height_m);
    r.max.footprint_diagonal_m = std::max(r.max.footprint_diagonal_m, extent.footprint_diagonal_m);
  }
  ++r.num_models;
}

const ExtentRange* CategoryExtents::Find(world::Category category) const {
  const int id = world::CategoryId(category);
  if (id < 0 || id >= world::kNumObjectCategories) return nullptr;
  const ExtentRange& r = ranges_[static_cast<std::size_t>(id)];
  return r.num_models > 0 ? &r : nullptr;
}

CategoryExtents CategoryExtents::FromDatabase(const ModelDatabase& database) {
  CategoryExtents out;
  for (const DatabaseModel& model : database.models()) {
    if (model.full_entry < 0 || model.full_entry >= static_cast<std::int32_t>(database.entries().size())) continue;
    out.Add(model.category, MeasureExtent(database.entries()[static_cast<std::size_t>(model.full_entry)].points));
  }
  return out;
}

void SizePlausibilityOptions::Validate() const {
  config::RequireInRange("report.size_check.min_ratio", min_ratio, 0.0, 1.0);
  config::RequireInRange("report.size_check.extent_trim_fraction", extent_trim_fraction, 0.0, 0.25);
  config::RequireNonNegative("report.size_check.wall_margin_m", wall_margin_m);
  config::RequirePositive("report.size_check.adjacency_m", adjacency_m);
  config::RequireNonNegative("report.size_check.support_gap_m", support_gap_m);
  config::RequireInRange("report.size_check.relabel_min_objectness", relabel_min_objectness, 0.0, 1.0);
  config::Require(max_ratio >= 1.0 && std::isfinite(max_ratio), "report.size_check.max_ratio",
                  "must be a finite number >= 1 (got " + std::to_string(max_ratio) + ")");
}

bool IsPlausibleExtent(const ObjectExtent& extent, const ExtentRange* range, const SizePlausibilityOptions& options) {
  if (range == nullptr) return true;
  const auto within = [&](double value, double lo, double hi) {
    return value >= options.min_ratio * lo && value <= options.max_ratio * hi;
  };
  return within(extent.height_m, range->min.height_m, range->max.height_m) &&
         within(extent.footprint_diagonal_m, range->min.footprint_diagonal_m, range->max.footprint_diagonal_m);
}

}  // namespace objscan::recognition
