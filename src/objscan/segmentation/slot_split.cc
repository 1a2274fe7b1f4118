#include "objscan/segmentation/slot_split.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "objscan/common/trimmed_range.h"

namespace objscan::segmentation {

void SlotSplitOptions::Validate() const {
  config::RequirePositive("min_gap_m", min_gap_m);
  config::RequireInRange("max_gap_m", max_gap_m, min_gap_m, 1.0);
  config::RequirePositive("min_sheet_area_m2", min_sheet_area_m2);
  config::RequireNonNegative("min_part_area_m2", min_part_area_m2);
  config::RequireInRange("min_sheet_overlap", min_sheet_overlap, 0.0, 1.0);
  config::RequireInRange("sheet_min_cos", sheet_min_cos, 0.0, 1.0);
  config::RequireInRange("bin_m", bin_m, 0.001, 0.1);
}

namespace {

// Yaw (radians, in [0, pi/2)) of the elements' dominant side-face orientation, modulo 90 degrees;
// negative when no element faces sideways.
double DominantYaw(const std::vector<Eigen::Vector3f>& normals) {
  constexpr int kBins = 90;
  std::vector<double> hist(kBins, 0.0);
  bool any = false;
  for (const Eigen::Vector3f& n : normals) {
    const double horizontal = std::hypot(n.x(), n.y());
    if (horizontal < 0.7) continue;
    const double yaw = std::fmod(std::atan2(n.y(), n.x()) + 4.0 * M_PI, 0.5 * M_PI);
    hist[std::min(kBins - 1, static_cast<int>(yaw / (0.5 * M_PI) * kBins))] += horizontal;
    any = true;
  }
  if (!any) return -1.0;
  int best = 0;
  double best_sum = -1.0;
  for (int b = 0; b < kBins; ++b) {
    const double sum = hist[(b + kBins - 1) % kBins] + hist[b] + hist[(b + 1) % kBins];
    if (sum > best_sum) {
      best_sum = sum;
      best = b;
    }
  }
  return (best + 0.5) * (0.5 * M_PI) / kBins;
}

using Range = std::pair<float, float>;  // [first, second]

// Share of the smaller range that the other covers (1 for two points at one place).
double Overlap(const Range& a, const Range& b) {
  const double shorter = std::min(a.second - a.first, b.second - b.first);
  const double common = std::min(a.second, b.second) - std::max(a.first, b.first);
  if (shorter <= 0.0) return common >= 0.0 ? 1.0 : 0.0;
  return std::clamp(common / shorter, 0.0, 1.0);
}

// The 5% and 95% quantiles of `values` (reordered).
Range QuantileRange(std::vector<float>* values) { return TrimmedRange(values, values->size() / 20); }

void SlotsAlong(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                const Eigen::Vector3f& axis, double element_area_m2, const SlotSplitOptions& o,
                std::vector<Slot>* slots) {
  float t_min = std::numeric_limits<float>::max(), t_max = std::numeric_limits<float>::lowest();
  for (const auto& p : points) {
    const float t = p.dot(axis);
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
  }
  const double bin = o.bin_m;
  const int nb = static_cast<int>((t_max - t_min) / bin) + 2;
  if (nb < 4 || nb > 100000) return;
  std::vector<int> bin_of(points.size());
  std::vector<double> facing_plus(nb, 0.0), facing_minus(nb, 0.0), all(nb, 0.0);
  const float c = static_cast<float>(o.sheet_min_cos);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int b = std::clamp(static_cast<int>((points[i].dot(axis) - t_min) / bin), 0, nb - 1);
    bin_of[i] = b;
    all[b] += element_area_m2;
    const float d = normals[i].dot(axis);
    if (d >= c) facing_plus[b] += element_area_m2;
    if (d <= -c) facing_minus[b] += element_area_m2;
  }
  auto window = [&](const std::vector<double>& h, int b) { return h[b] + (b + 1 < nb ? h[b + 1] : 0.0); };
  const int gap_lo = std::max(1, static_cast<int>(std::ceil(o.min_gap_m / bin - 1e-9)));
  const int gap_hi = static_cast<int>(std::floor(o.max_gap_m / bin + 1e-9));
  std::vector<double> below(nb + 1, 0.0);  // surface in bins [0, b)
  for (int b = 0; b < nb; ++b) below[b + 1] = below[b] + all[b];
  const double total = below[nb];
  const Eigen::Vector3f across(-axis.y(), axis.x(), 0.f);
  double last_cut_area = 0.0;  // surface before the last slot kept
  for (int b = 0; b < nb; ++b) {
    const double plus = window(facing_plus, b);
    if (plus < o.min_sheet_area_m2) continue;
    if (b + 1 < nb && window(facing_plus, b + 1) > plus) continue;  // the sheet's strongest placement
    int q = b + gap_lo;
    for (; q <= std::min(nb - 1, b + gap_hi); ++q) {
      if (window(facing_minus, q) >= o.min_sheet_area_m2) break;
    }
    if (q > std::min(nb - 1, b + gap_hi)) continue;
    // Each sheet's extent across and in height (5% to 95% quantiles).
    std::vector<float> u_plus, z_plus, u_minus, z_minus;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int bi = bin_of[i];
      const float d = normals[i].dot(axis);
      if ((bi == b || bi == b + 1) && d >= c) {
        u_plus.push_back(points[i].dot(across));
        z_plus.push_back(points[i].z());
      } else if ((bi == q || bi == q + 1) && d <= -c) {
        u_minus.push_back(points[i].dot(across));
        z_minus.push_back(points[i].z());
      }
    }
    const Range up = QuantileRange(&u_plus), zp = QuantileRange(&z_plus);
    const Range um = QuantileRange(&u_minus), zm = QuantileRange(&z_minus);
    if (Overlap(up, um) < o.min_sheet_overlap || Overlap(zp, zm) < o.min_sheet_overlap) continue;
    const int cut_bin = (b + q + 2) / 2;  // between the two sheets' centres
    const double before = below[std::min(cut_bin, nb)];
    if (before - last_cut_area >= o.min_part_area_m2 && total - before >= o.min_part_area_m2) {
      Slot s;
      s.axis = axis;
      s.across = across;
      s.offset_m = t_min + bin * cut_bin;
      s.across_min_m = std::min(up.first, um.first);
      s.across_max_m = std::max(up.second, um.second);
      s.z_min_m = std::min(zp.first, zm.first);
      s.z_max_m = std::max(zp.second, zm.second);
      slots->push_back(s);
      last_cut_area = before;
    }
    b = q + 1;
  }
}

}  // namespace

std::vector<Slot> FindSlots(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                            double element_area_m2, const SlotSplitOptions& options) {
  std::vector<Slot> slots;
  if (!options.enabled || points.size() != normals.size() || points.empty()) return slots;
  const double yaw = DominantYaw(normals);
  if (yaw < 0.0) return slots;
  const Eigen::Vector3f a1(static_cast<float>(std::cos(yaw)), static_cast<float>(std::sin(yaw)), 0.f);
  const Eigen::Vector3f a2(-a1.y(), a1.x(), 0.f);
  SlotsAlong(points, normals, a1, element_area_m2, options, &slots);
  SlotsAlong(points, normals, a2, element_area_m2, options, &slots);
  return slots;
}

}  // namespace objscan::segmentation
