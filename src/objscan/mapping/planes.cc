#include "objscan/mapping/planes.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

namespace objscan::mapping {

void StructureOptions::Validate() const {
  config::RequirePositive("structure.floor_search_height_m", floor_search_height_m);
  config::RequireInRange("structure.floor_max_tilt_deg", floor_max_tilt_deg, 0.0, 90.0);
  config::RequireNonNegative("structure.floor_min_area_m2", floor_min_area_m2);
  config::RequirePositive("structure.plane_tolerance_m", plane_tolerance_m);
  config::RequireInRange("structure.wall_max_tilt_deg", wall_max_tilt_deg, 0.0, 90.0);
  config::RequireInRange("structure.wall_angle_bin_deg", wall_angle_bin_deg, 0.1, 45.0);
  config::RequirePositive("structure.wall_offset_bin_m", wall_offset_bin_m);
  config::RequireNonNegative("structure.wall_min_area_m2", wall_min_area_m2);
  config::RequireNonNegative("structure.wall_min_height_m", wall_min_height_m);
  config::RequireInRange("structure.wall_max_behind_fraction", wall_max_behind_fraction, 0.0, 1.0);
  config::RequireNonNegative("structure.wall_behind_min_depth_m", wall_behind_min_depth_m);
  config::RequireNonNegative("structure.furniture_top_margin_m", furniture_top_margin_m);
  config::RequireInRange("structure.wall_max_count", wall_max_count, 0, 1000);
  config::RequirePositive("structure.ceiling_min_height_m", ceiling_min_height_m);
  config::RequireNonNegative("structure.ceiling_min_area_m2", ceiling_min_area_m2);
}

bool StructureResult::InsideWalls(const Eigen::Vector3d& p, double margin_m) const {
  for (const WallPlane& w : walls) {
    const double s = w.Along(p);
    if (s < w.span_min_m - margin_m || s > w.span_max_m + margin_m) continue;
    if (w.SignedDistance(p) < -margin_m) return false;
  }
  return true;
}

bool StructureResult::OnStructure(const Eigen::Vector3d& p, double distance_m) const {
  if (has_floor && std::fabs(p.z() - floor_height_m) < distance_m) return true;
  return NearWall(p, distance_m);
}

bool StructureResult::NearWall(const Eigen::Vector3d& p, double distance_m) const {
  for (const WallPlane& w : walls) {
    if (std::fabs(w.SignedDistance(p)) >= distance_m) continue;
    const double s = w.Along(p);
    if (s > w.span_min_m - distance_m && s < w.span_max_m + distance_m) return true;
  }
  return false;
}

bool StructureResult::InWallReveal(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double depth_m,
                                   double max_cos) const {
  for (const WallPlane& w : walls) {
    const double d = w.SignedDistance(p);
    if (d >= 0.0 || d <= -depth_m) continue;
    if (std::fabs(n.dot(w.normal)) >= max_cos) continue;
    const double s = w.Along(p);
    if (s >= w.span_min_m && s <= w.span_max_m && p.z() >= w.z_min_m - depth_m && p.z() <= w.z_max_m + depth_m) {
      return true;
    }
  }
  return false;
}

int StructureResult::WallOpeningIndex(const Eigen::Vector3d& p, double min_depth_m, double max_depth_m) const {
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const WallPlane& w = walls[i];
    const double depth = -w.SignedDistance(p);
    if (depth <= min_depth_m || depth > max_depth_m) continue;
    if (w.Spans(p)) return static_cast<int>(i);
  }
  return -1;
}

bool StructureResult::IsPlaneNoise(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                                   double band_m, double min_side_share, double fraction) const {
  if (points.empty() || normals.size() != points.size() || band_m <= 0.0) return false;
  constexpr double kParallelMinCos = 0.8660254037844386;  // cos 30 deg
  const auto straddles = [&](auto&& signed_distance, const Eigen::Vector3d& plane_normal, auto&& spans) {
    std::size_t in_band = 0, in_front = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p = points[i].cast<double>();
      const double d = signed_distance(p);
      if (std::fabs(d) > band_m || !spans(p)) continue;
      if (std::fabs(normals[i].cast<double>().dot(plane_normal)) < kParallelMinCos) continue;
      ++in_band;
      in_front += d > 0.0;
    }
    if (in_band == 0 || static_cast<double>(in_band) < fraction * static_cast<double>(points.size())) return false;
    const double front = static_cast<double>(in_front) / static_cast<double>(in_band);
    return front >= min_side_share && 1.0 - front >= min_side_share;
  };
  if (has_floor &&
      straddles([&](const Eigen::Vector3d& p) { return p.z() - floor_height_m; }, Eigen::Vector3d::UnitZ(),
                [](const Eigen::Vector3d&) { return true; })) {
    return true;
  }
  for (const WallPlane& w : walls) {
    if (straddles([&](const Eigen::Vector3d& p) { return w.SignedDistance(p); }, w.normal,
                  [&](const Eigen::Vector3d& p) { return w.Spans(p, band_m); })) {
      return true;
    }
  }
  return false;
}

StructureDetector::StructureDetector(const StructureOptions& options) : options_(options) { options_.Validate(); }

namespace {
constexpr double kTagMaxAngleDeg = 35.0;  // element normal vs plane normal when tagging

double AngleDiff(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 2.0 * M_PI);
  return d > M_PI ? 2.0 * M_PI - d : d;
}

// Where plane v lies relative to a near-parallel wall w (normals within 3 angle bins, spans
// overlapping): w's signed distance of the middle of v's extent (negative: behind w). nullopt when
// they are not parallel or do not overlap along the wall.
std::optional<double> PlaneGap(const WallPlane& w, const WallPlane& v, double angle_bin) {
  if (AngleDiff(std::atan2(w.normal.y(), w.normal.x()), std::atan2(v.normal.y(), v.normal.x())) >= 3 * angle_bin) {
    return std::nullopt;
  }
  const Eigen::Vector3d mid = v.PointAt(0.5 * (v.span_min_m + v.span_max_m));
  const double s = w.Along(mid);
  const double half = 0.5 * (v.span_max_m - v.span_min_m);
  if (s + half < w.span_min_m || s - half > w.span_max_m) return std::nullopt;
  return w.SignedDistance(mid);
}
}  // namespace

StructureResult StructureDetector::Update(SurfaceMap* map) const {
  StructureResult result;
  const std::size_t n = map->size();
  const double voxel_area = map->voxel_size_m() * map->voxel_size_m();
  const double tol = options_.plane_tolerance_m;
  std::vector<Eigen::Vector3f> normals(n);
  for (std::size_t i = 0; i < n; ++i) normals[i] = map->normal(i);

  // Floor: peak of the height histogram of upward elements near z = 0 (1 cm bins).
  const double cos_floor = std::cos(options_.floor_max_tilt_deg * M_PI / 180.0);
  const double bin = 0.01;
  const int num_bins = static_cast<int>(std::ceil(2.0 * options_.floor_search_height_m / bin)) + 1;
  std::vector<double> hist(num_bins, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double z = map->position(i).z();
    if (normals[i].z() < cos_floor || std::fabs(z) > options_.floor_search_height_m) continue;
    const int b = std::clamp(static_cast<int>((z + options_.floor_search_height_m) / bin), 0, num_bins - 1);
    hist[b] += 1.0;
  }
  int best_bin = -1;
  double best = 0.0;
  for (int b = 0; b < num_bins; ++b) {
    const double s = hist[b] + (b > 0 ? hist[b - 1] : 0.0) + (b + 1 < num_bins ? hist[b + 1] : 0.0);
    if (s > best) {
      best = s;
      best_bin = b;
    }
  }
  if (best_bin >= 0 && best * voxel_area >= options_.floor_min_area_m2) {
    const double z_peak = (best_bin + 0.5) * bin - options_.floor_search_height_m;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double z = map->position(i).z();
      if (normals[i].z() >= cos_floor && std::fabs(z - z_peak) < tol) {
        sum += z;
        ++count;
      }
    }
    result.has_floor = count > 0;
    result.floor_height_m = count > 0 ? sum / count : z_peak;
    result.floor_area_m2 = count * voxel_area;
  }

  // Ceiling: the lowest height (1 cm bins, summed over three) at which downward elements high above
  // the floor cover ceiling_min_area_m2. A house's ceiling has several levels (lowered parts,
  // bulkheads, beams): everything from the lowest level up that does not face up is ceiling (see
  // TagElements).
  {
    const double z_min = (result.has_floor ? result.floor_height_m : 0.0) + options_.ceiling_min_height_m;
    std::map<std::int64_t, double> ceiling_hist;  // ordered: the lowest level is found first
    for (std::size_t i = 0; i < n; ++i) {
      const double z = map->position(i).z();
      if (-normals[i].z() < cos_floor || z < z_min) continue;
      ceiling_hist[static_cast<std::int64_t>(std::floor(z / bin))] += 1.0;
    }
    const auto at = [&](std::int64_t k) {
      const auto it = ceiling_hist.find(k);
      return it == ceiling_hist.end() ? 0.0 : it->second;
    };
    for (const auto& [b, count] : ceiling_hist) {
      if ((count + at(b - 1) + at(b + 1)) * voxel_area < options_.ceiling_min_area_m2) continue;
      // The level: the fullest bin of this one and the next two.
      std::int64_t level = b;
      for (std::int64_t k = b + 1; k <= b + 2; ++k) {
        if (at(k) > at(level)) level = k;
      }
      const double z_peak = (static_cast<double>(level) + 0.5) * bin;
      double sum = 0.0;
      std::size_t elements = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double z = map->position(i).z();
        if (-normals[i].z() >= cos_floor && std::fabs(z - z_peak) < tol) {
          sum += z;
          ++elements;
        }
      }
      result.has_ceiling = elements > 0;
      result.ceiling_height_m = elements > 0 ? sum / elements : z_peak;
      break;
    }
  }

  // Walls: Hough votes over (azimuth of the horizontal normal, offset along it).
  const double sin_wall = std::sin(options_.wall_max_tilt_deg * M_PI / 180.0);
  const double abin = options_.wall_angle_bin_deg * M_PI / 180.0;
  const int num_abins = std::max(1, static_cast<int>(std::round(2.0 * M_PI / abin)));
  const double obin = options_.wall_offset_bin_m;
  std::vector<std::uint32_t> vertical;
  std::vector<double> azimuth, offset;
  std::unordered_map<std::int64_t, double> votes;
  // Key o * 2^16 + a for an angle bin a in [0, 2^16): the same value as (o << 16) ^ a, without
  // shifting a negative offset bin (undefined behaviour before C++20).
  constexpr std::int64_t kAngleBins = std::int64_t{1} << 16;
  auto bin_key = [](std::int64_t a, std::int64_t o) { return o * kAngleBins + a; };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& nr = normals[i];
    if (std::fabs(nr.z()) > sin_wall) continue;
    const double th = std::atan2(nr.y(), nr.x());
    const double h = std::hypot(nr.x(), nr.y());
    const Eigen::Vector3f& p = map->position(i);
    const double d = (nr.x() * p.x() + nr.y() * p.y()) / h;
    vertical.push_back(static_cast<std::uint32_t>(i));
    azimuth.push_back(th);
    offset.push_back(d);
    const std::int64_t a = static_cast<std::int64_t>(std::floor((th + M_PI) / abin)) % num_abins;
    const std::int64_t o = static_cast<std::int64_t>(std::floor(d / obin));
    votes[bin_key(a, o)] += 1.0;
  }
  struct Candidate {
    double votes;
    std::int64_t a, o;
  };
  std::vector<Candidate> candidates;
  for (const auto& kv : votes) {
    const std::int64_t a = (kv.first % kAngleBins + kAngleBins) % kAngleBins;
    const std::int64_t o = (kv.first - a) / kAngleBins;
    candidates.push_back({kv.second, a, o});
  }
  // Neighbourhood sums (3 x 3 bins, angle wraps) make peaks robust to bin boundaries.
  for (Candidate& c : candidates) {
    double s = 0.0;
    for (int da = -1; da <= 1; ++da) {
      for (int dof = -1; dof <= 1; ++dof) {
        const std::int64_t a = ((c.a + da) % num_abins + num_abins) % num_abins;
        auto it = votes.find(bin_key(a, c.o + dof));
        if (it != votes.end()) s += it->second;
      }
    }
    c.votes = s;
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return x.votes != y.votes ? x.votes > y.votes : (x.a != y.a ? x.a < y.a : x.o < y.o);
  });
  const double cos_tag = std::cos(kTagMaxAngleDeg * M_PI / 180.0);
  // Every evaluated peak (accepted or not) suppresses its neighbourhood, so a rejected plane is
  // not evaluated again through its neighbouring bins.
  std::vector<std::pair<double, double>> evaluated_peaks;  // (azimuth, offset)
  for (const Candidate& c : candidates) {
    if (c.votes * voxel_area < options_.wall_min_area_m2) break;
    if (static_cast<int>(result.walls.size()) >= options_.wall_max_count ||
        static_cast<int>(evaluated_peaks.size()) > 4 * options_.wall_max_count) {
      break;
    }
    const double th_c = (c.a + 0.5) * abin - M_PI;
    const double d_c = (c.o + 0.5) * obin;
    bool suppressed = false;
    for (const auto& [th_p, d_p] : evaluated_peaks) {
      if (AngleDiff(th_p, th_c) < 3 * abin && std::fabs(d_p - d_c) < 3 * obin) suppressed = true;
    }
    for (const WallPlane& w : result.walls) {
      const double th_w = std::atan2(w.normal.y(), w.normal.x());
      if (AngleDiff(th_w, th_c) < 3 * abin && std::fabs(w.offset_m - d_c) < 3 * obin) suppressed = true;
    }
    if (suppressed) continue;
    evaluated_peaks.emplace_back(th_c, d_c);
    // Refine: mean normal and offset of the elements near the peak.
    Eigen::Vector2d nsum = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < vertical.size(); ++k) {
      if (AngleDiff(azimuth[k], th_c) <= 1.5 * abin && std::fabs(offset[k] - d_c) <= 1.5 * obin) {
        const Eigen::Vector3f& nr = normals[vertical[k]];
        nsum += Eigen::Vector2d(nr.x(), nr.y());
      }
    }
    if (nsum.norm() <= 0.0) continue;
    WallPlane wall;
    wall.normal = Eigen::Vector3d(nsum.x(), nsum.y(), 0.0).normalized();
    // Refine the plane by a least-squares line fit (in XY) of the elements near it, twice: a normal
    // averaged from noisy element normals is off by a degree or so, which along a 4 m wall puts its
    // ends beyond the tagging tolerance.
    wall.offset_m = d_c;
    bool fitted = false;
    for (int round = 0; round < 3; ++round) {
      const double band = round == 0 ? 1.5 * obin : tol;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
      std::size_t count = 0;
      for (std::size_t k = 0; k < vertical.size(); ++k) {
        const Eigen::Vector3d p = map->position(vertical[k]).cast<double>();
        if (std::fabs(wall.SignedDistance(p)) < band && normals[vertical[k]].cast<double>().dot(wall.normal) > cos_tag) {
          mean += p.head<2>();
          second += p.head<2>() * p.head<2>().transpose();
          ++count;
        }
      }
      if (count < 3) break;
      mean /= static_cast<double>(count);
      const Eigen::Matrix2d cov = second / static_cast<double>(count) - mean * mean.transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
      Eigen::Vector2d nxy = eig.eigenvectors().col(0);  // smallest spread: across the wall
      // A short or blob-like patch has no reliable direction: keep the normal from the normals.
      if (eig.eigenvalues()(1) > 4.0 * eig.eigenvalues()(0) + 1e-6) {
        if (nxy.dot(wall.normal.head<2>()) < 0.0) nxy = -nxy;
        wall.normal = Eigen::Vector3d(nxy.x(), nxy.y(), 0.0);
      }
      wall.offset_m = wall.normal.head<2>().dot(mean);
      fitted = true;
    }
    if (!fitted) continue;
    // Inliers and extent.
    std::size_t inliers = 0;
    wall.z_min_m = wall.span_min_m = std::numeric_limits<double>::infinity();
    wall.z_max_m = wall.span_max_m = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p = map->position(i).cast<double>();
      if (std::fabs(wall.SignedDistance(p)) < tol && normals[i].cast<double>().dot(wall.normal) > cos_tag) {
        ++inliers;
        wall.z_min_m = std::min(wall.z_min_m, p.z());
        wall.z_max_m = std::max(wall.z_max_m, p.z());
        const double s = wall.Along(p);
        wall.span_min_m = std::min(wall.span_min_m, s);
        wall.span_max_m = std::max(wall.span_max_m, s);
      }
    }
    wall.area_m2 = inliers * voxel_area;
    if (wall.area_m2 < options_.wall_min_area_m2) continue;
    if (wall.z_max_m - wall.z_min_m < options_.wall_min_height_m) continue;
    // A tilted neighbouring bin refines onto a wall already found: the same wall again (checked
    // before the scan of every element below).
    bool duplicate = false;
    for (const WallPlane& w : result.walls) {
      const std::optional<double> gap = PlaneGap(w, wall, abin);
      duplicate = duplicate || (gap && std::fabs(*gap) <= 2.0 * tol);
    }
    if (duplicate) continue;
    // A wall bounds the room: almost nothing lies behind it within its extent along the wall
    // (beyond its ends there may be more room, e.g. the other arm of an L-shaped room), apart from
    // what fills its openings a few cm deep.
    std::size_t behind = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p = map->position(i).cast<double>();
      if (wall.SignedDistance(p) >= -options_.wall_behind_min_depth_m) continue;
      const double s = wall.Along(p);
      if (s > wall.span_min_m + tol && s < wall.span_max_m - tol) ++behind;
    }
    if (static_cast<double>(behind) > options_.wall_max_behind_fraction * static_cast<double>(n)) continue;
    result.walls.push_back(wall);
  }

  // Of two parallel planes a few cm apart over a common extent, one larger and at least as long as
  // the other, the other is no wall: a recessed window pane found on its own (or a plane fitted
  // through pane and wall at a slight tilt) behind the wall, a curtain in front of it. Left in, the
  // pane would make the wall in front of it look like furniture (below). When neither dominates (a
  // door in front of a wall mostly hidden by furniture), the furniture rule below decides.
  {
    const auto span = [](const WallPlane& w) { return w.span_max_m - w.span_min_m; };
    std::vector<WallPlane> kept;
    for (const WallPlane& v : result.walls) {
      bool dominated = false;
      for (const WallPlane& w : result.walls) {
        if (&w == &v || span(w) < span(v) - 2.0 * obin) continue;
        if (w.area_m2 < v.area_m2 || (w.area_m2 == v.area_m2 && &w > &v)) continue;
        const std::optional<double> gap = PlaneGap(w, v, abin);
        dominated =
            dominated || (gap && std::fabs(*gap) > 2.0 * tol && std::fabs(*gap) <= options_.wall_behind_min_depth_m);
      }
      if (!dominated) kept.push_back(v);
    }
    result.walls.swap(kept);
  }

  // A vertical plane with a parallel wall behind it is the face of furniture standing against that
  // wall (a wardrobe), not a wall, when the wall overlaps it along the wall or rises clearly above
  // it (the wall behind a wardrobe in a corner is hidden where the two overlap), unless it is the
  // step of an L-shaped room. The step is told from a wardrobe in a corner by the wall joining it to
  // the wall behind: perpendicular, at one of its ends, running from its plane back to the other's
  // and no farther into the room, and rising above what was seen of it (its top may simply not have
  // been seen yet). A wardrobe's side is no taller than its front; a side wall runs on into the room.
  const double ends_m = 2.0 * obin;
  const auto is_room_step = [&](const WallPlane& w, const WallPlane& v) {
    const double depth = w.offset_m - v.offset_m;
    for (const WallPlane& c : result.walls) {
      if (std::fabs(c.normal.dot(w.normal)) > std::sin(2 * abin)) continue;
      if (c.z_max_m - w.z_max_m <= options_.furniture_top_margin_m) continue;
      const Eigen::Vector3d a = c.PointAt(c.span_min_m);
      const Eigen::Vector3d b = c.PointAt(c.span_max_m);
      const double along = w.Along(a);
      if (std::fabs(along - w.span_min_m) > ends_m && std::fabs(along - w.span_max_m) > ends_m) continue;
      const double near = std::max(w.SignedDistance(a), w.SignedDistance(b));
      const double far = std::min(w.SignedDistance(a), w.SignedDistance(b));
      if (near <= ends_m && far <= -depth + ends_m) return true;
    }
    return false;
  };
  std::vector<WallPlane> walls;
  for (const WallPlane& w : result.walls) {
    bool in_front = false;
    for (const WallPlane& v : result.walls) {
      if (&v == &w || w.normal.dot(v.normal) < std::cos(2 * abin) || v.offset_m > w.offset_m - 2.0 * tol) continue;
      const double overlap = std::min(w.span_max_m, v.span_max_m) - std::max(w.span_min_m, v.span_min_m);
      if (overlap > 0.5 * (w.span_max_m - w.span_min_m)) in_front = true;
      if (options_.furniture_top_margin_m > 0.0 && v.z_max_m - w.z_max_m > options_.furniture_top_margin_m &&
          !is_room_step(w, v)) {
        in_front = true;
      }
    }
    if (!in_front) walls.push_back(w);
  }
  result.walls.swap(walls);

  TagElements(map, &result);
  return result;
}

void StructureDetector::TagElements(SurfaceMap* map, StructureResult* result) const {
  const std::size_t n = map->size();
  const double tol = options_.plane_tolerance_m;
  const double cos_floor = std::cos(options_.floor_max_tilt_deg * M_PI / 180.0);
  const double cos_tag = std::cos(kTagMaxAngleDeg * M_PI / 180.0);
  result->num_floor_elements = 0;
  result->num_wall_elements = 0;
  result->num_ceiling_elements = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = map->position(i).cast<double>();
    const Eigen::Vector3d nr = map->normal(i).cast<double>();
    Structure s = Structure::kNone;
    if (result->has_floor && nr.z() >= cos_floor && std::fabs(p.z() - result->floor_height_m) < tol) {
      s = Structure::kFloor;
      ++result->num_floor_elements;
    } else if (result->has_ceiling && nr.z() < cos_floor && p.z() > result->ceiling_height_m - tol) {
      s = Structure::kCeiling;
      ++result->num_ceiling_elements;
    } else {
      for (const WallPlane& w : result->walls) {
        if (std::fabs(w.SignedDistance(p)) < tol && nr.dot(w.normal) > cos_tag) {
          s = Structure::kWall;
          ++result->num_wall_elements;
          break;
        }
      }
    }
    map->SetStructure(i, s);
  }
}

}  // namespace objscan::mapping
