#include "objscan/world/procedural/floor_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "objscan/common/error.h"

namespace objscan::world::procedural {
namespace {

constexpr std::uint8_t kOffFloor = 0, kObstacle = 1, kFree = 2, kErodedFree = 3;

// 1-D squared distance transform of a sampled function (Felzenszwalb & Huttenlocher), in place.
void DistanceTransform1d(std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                         std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  const double kInf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    if (f[q] == kInf) continue;
    if (f[v[0]] == kInf) {
      v[0] = q;
      continue;
    }
    double s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * (q - v[k]));
    while (s <= z[k]) {
      --k;
      s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * (q - v[k]));
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (f[v[0]] == kInf) {
    std::fill(d.begin(), d.end(), kInf);
    return;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = (q - v[k]) * static_cast<double>(q - v[k]) + f[v[k]];
  }
}

// Squared distance (in cells) from each cell centre to the nearest blocked cell centre.
std::vector<double> SquaredDistanceToBlocked(const std::vector<std::uint8_t>& cells, int width, int height) {
  const double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) dist[i] = cells[i] >= kFree ? kInf : 0.0;
  const int n = std::max(width, height);
  std::vector<double> f(n), d(n), z(n + 1);
  std::vector<int> v(n);
  f.resize(width);
  d.resize(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) f[x] = dist[y * width + x];
    DistanceTransform1d(f, d, v, z);
    for (int x = 0; x < width; ++x) dist[y * width + x] = d[x];
  }
  f.resize(height);
  d.resize(height);
  for (int x = 0; x < width; ++x) {
    for (int y = 0; y < height; ++y) f[y] = dist[y * width + x];
    DistanceTransform1d(f, d, v, z);
    for (int y = 0; y < height; ++y) dist[y * width + x] = d[y];
  }
  return dist;
}

}  // namespace

FloorConnectivityReport CheckFreeFloor(const Scene& scene, double cell_m, double passage_m, double max_reach_m) {
  if (!(cell_m > 0.0)) throw InputError("CheckFreeFloor: cell_m must be > 0");
  const geometry::Aabb3 floor_box = scene.StructureBounds(Category::kFloor);
  if (floor_box.Empty()) throw InputError("CheckFreeFloor: scene '" + scene.name() + "' has no floor");

  FloorConnectivityReport report;
  report.cell_m = cell_m;
  // One off-floor cell of padding on every side so the border counts as blocked.
  report.origin_x_m = floor_box.min_m.x() - cell_m;
  report.origin_y_m = floor_box.min_m.y() - cell_m;
  const int width = static_cast<int>(std::ceil((floor_box.max_m.x() - floor_box.min_m.x()) / cell_m)) + 2;
  const int height = static_cast<int>(std::ceil((floor_box.max_m.y() - floor_box.min_m.y()) / cell_m)) + 2;
  report.width = width;
  report.height = height;
  report.cells.assign(static_cast<std::size_t>(width) * height, kOffFloor);
  auto cx = [&](int x) { return report.origin_x_m + (x + 0.5) * cell_m; };
  auto cy = [&](int y) { return report.origin_y_m + (y + 0.5) * cell_m; };
  auto clamp_x = [&](double v) { return std::clamp(static_cast<int>(std::floor(v)), 0, width - 1); };
  auto clamp_y = [&](double v) { return std::clamp(static_cast<int>(std::floor(v)), 0, height - 1); };

  // Floor: cells whose centre lies on a floor triangle (seen from above).
  for (const auto& object : scene.objects()) {
    if (object.category != Category::kFloor) continue;
    for (const auto& t : object.mesh.triangles) {
      Eigen::Vector2d p[3];
      for (int k = 0; k < 3; ++k) p[k] = (object.T_world_object * object.mesh.vertices[t[k]].cast<double>()).head<2>();
      const double area2 = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
      if (std::abs(area2) < 1e-12) continue;
      const double sign = area2 > 0 ? 1.0 : -1.0;
      const Eigen::Vector2d lo = p[0].cwiseMin(p[1]).cwiseMin(p[2]), hi = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
      const int x0 = clamp_x((lo.x() - report.origin_x_m) / cell_m), x1 = clamp_x((hi.x() - report.origin_x_m) / cell_m);
      const int y0 = clamp_y((lo.y() - report.origin_y_m) / cell_m), y1 = clamp_y((hi.y() - report.origin_y_m) / cell_m);
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d c(cx(x), cy(y));
          bool inside = true;
          for (int k = 0; k < 3 && inside; ++k) {
            const Eigen::Vector2d a = p[k], b = p[(k + 1) % 3];
            const double e = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
            inside = sign * e >= -1e-12;
          }
          if (inside) report.cells[y * width + x] = kFree;
        }
      }
    }
  }
  for (auto c : report.cells) report.floor_cells += c == kFree ? 1 : 0;

  // Obstacles: XY bounding boxes of everything in the robot's height band (cells they touch).
  for (const auto& object : scene.objects()) {
    if (object.category == Category::kFloor) continue;
    const geometry::Aabb3 box = scene.ObjectBounds(object);
    if (box.Empty() || box.max_m.z() < kObstacleMinZ || box.min_m.z() > kObstacleMaxZ) continue;
    const double gx0 = (box.min_m.x() - report.origin_x_m) / cell_m, gx1 = (box.max_m.x() - report.origin_x_m) / cell_m;
    const double gy0 = (box.min_m.y() - report.origin_y_m) / cell_m, gy1 = (box.max_m.y() - report.origin_y_m) / cell_m;
    if (gx1 <= 0 || gy1 <= 0 || gx0 >= width || gy0 >= height) continue;
    // Cells the box overlaps with positive area (a box edge on a cell border does not take the cell).
    const double eps = 1e-7;
    const int x0 = clamp_x(gx0 + eps), x1 = std::clamp(static_cast<int>(std::ceil(gx1 - eps)) - 1, 0, width - 1);
    const int y0 = clamp_y(gy0 + eps), y1 = std::clamp(static_cast<int>(std::ceil(gy1 - eps)) - 1, 0, height - 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (report.cells[y * width + x] == kFree) report.cells[y * width + x] = kObstacle;
      }
    }
  }
  for (auto c : report.cells) report.free_cells += c == kFree ? 1 : 0;

  // Erosion: keep cells whose centre is at least passage_m / 2 from every blocked cell centre, so a
  // passage at least passage_m wide always survives and one narrower than passage_m - cell_m never does.
  const std::vector<double> dist2 = SquaredDistanceToBlocked(report.cells, width, height);
  const double r_cells = 0.5 * passage_m / cell_m;
  const double r2 = r_cells * r_cells - 1e-6;
  for (std::size_t i = 0; i < report.cells.size(); ++i) {
    if (report.cells[i] == kFree && dist2[i] >= r2) {
      report.cells[i] = kErodedFree;
      ++report.eroded_free_cells;
    }
  }

  // 4-connected components of the eroded free space.
  std::vector<int> label(report.cells.size(), -1);
  std::vector<int> stack;
  for (int start = 0; start < width * height; ++start) {
    if (report.cells[start] != kErodedFree || label[start] >= 0) continue;
    const int id = report.num_components++;
    label[start] = id;
    stack.push_back(start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int x = i % width, y = i / width;
      const int nbr[4] = {x > 0 ? i - 1 : -1, x + 1 < width ? i + 1 : -1, y > 0 ? i - width : -1,
                          y + 1 < height ? i + width : -1};
      for (int j : nbr) {
        if (j >= 0 && report.cells[j] == kErodedFree && label[j] < 0) {
          label[j] = id;
          stack.push_back(j);
        }
      }
    }
  }

  // Reach: an eroded-free cell centre within max_reach_m of each furniture footprint.
  for (const auto& object : scene.objects()) {
    if (object.IsStructural()) continue;
    const geometry::Aabb3 box = scene.ObjectBounds(object);
    bool reachable = false;
    const int x0 = clamp_x((box.min_m.x() - max_reach_m - report.origin_x_m) / cell_m);
    const int x1 = clamp_x((box.max_m.x() + max_reach_m - report.origin_x_m) / cell_m);
    const int y0 = clamp_y((box.min_m.y() - max_reach_m - report.origin_y_m) / cell_m);
    const int y1 = clamp_y((box.max_m.y() + max_reach_m - report.origin_y_m) / cell_m);
    for (int y = y0; y <= y1 && !reachable; ++y) {
      for (int x = x0; x <= x1 && !reachable; ++x) {
        if (report.cells[y * width + x] != kErodedFree) continue;
        const double dx = std::max({box.min_m.x() - cx(x), 0.0, cx(x) - box.max_m.x()});
        const double dy = std::max({box.min_m.y() - cy(y), 0.0, cy(y) - box.max_m.y()});
        reachable = dx * dx + dy * dy <= max_reach_m * max_reach_m;
      }
    }
    if (!reachable) report.unreachable_instances.push_back(object.instance_id);
  }
  report.ok = report.num_components == 1 && report.unreachable_instances.empty();
  return report;
}

}  // namespace objscan::world::procedural
