#include "objscan/navigation/navigator.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>

#include "objscan/common/error.h"

namespace objscan::navigation {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The 8 moves: 4 straight, then 4 diagonal.
constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// Octile distance in cells.
double Octile(int dx, int dy) {
  const int ax = std::abs(dx), ay = std::abs(dy);
  return (std::max(ax, ay) - std::min(ax, ay)) + kSqrt2 * std::min(ax, ay);
}

double PolylineLength(const std::vector<Eigen::Vector2d>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

}  // namespace

void NavigatorOptions::Validate() const {
  config::RequirePositive("cell_size_m", cell_size_m);
  config::RequireNonNegative("min_obstacle_height_m", min_obstacle_height_m);
  config::RequireNonNegative("start_escape_m", start_escape_m);
  config::RequireNonNegative("start_escape_route_m", start_escape_route_m);
}

const char* PlanStatusName(PlanStatus status) {
  switch (status) {
    case PlanStatus::kReached: return "reached";
    case PlanStatus::kStartBlocked: return "start_blocked";
    case PlanStatus::kGoalBlocked: return "goal_blocked";
    case PlanStatus::kUnreachable: return "unreachable";
  }
  return "unknown";
}

Navigator::Navigator(const OccupancySource& source, double robot_radius_m, double robot_height_m,
                     const NavigatorOptions& options)
    : options_(options), robot_radius_m_(robot_radius_m), robot_height_m_(robot_height_m) {
  options_.Validate();
  config::RequireNonNegative("robot_radius_m", robot_radius_m);
  config::Require(robot_height_m > options_.min_obstacle_height_m, "robot_height_m",
                  "must exceed min_obstacle_height_m");
  Update(source);
}

void Navigator::Update(const OccupancySource& source) {
  grid_ = source.Grid(options_.min_obstacle_height_m, robot_height_m_, options_.cell_size_m);
  if (grid_.cells.size() != static_cast<std::size_t>(grid_.width) * grid_.height || grid_.width <= 0 ||
      grid_.height <= 0 || !(grid_.cell_size_m > 0.0)) {
    throw InputError("occupancy source returned a malformed grid");
  }
  Inflate();
}

void Navigator::Inflate() {
  const double s = grid_.cell_size_m;
  inflation_radius_m_ = robot_radius_m_ + 0.5 * kSqrt2 * s;
  const double r = inflation_radius_m_ / s;  // in cells
  // Offsets of the cells whose square comes closer than r to the centre of cell (0, 0).
  std::vector<Eigen::Vector2i> kernel;
  const int reach = static_cast<int>(std::ceil(r + 0.5));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const double gx = std::max(0.0, std::abs(dx) - 0.5), gy = std::max(0.0, std::abs(dy) - 0.5);
      if (gx * gx + gy * gy < r * r) kernel.emplace_back(dx, dy);
    }
  }
  const int w = grid_.width, h = grid_.height;
  blocked_.assign(grid_.cells.size(), 0);
  auto obstacle = [&](int ix, int iy) { return grid_.At(ix, iy) != CellState::kFree; };
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      if (!obstacle(ix, iy)) continue;
      // Only cells on the rim of an obstacle region need stamping: the interior is covered by it.
      const bool interior = obstacle(ix - 1, iy) && obstacle(ix + 1, iy) && obstacle(ix, iy - 1) &&
                            obstacle(ix, iy + 1) && ix > 0 && iy > 0 && ix + 1 < w && iy + 1 < h;
      if (interior) {
        blocked_[grid_.Index(ix, iy)] = 1;
        continue;
      }
      for (const auto& k : kernel) {
        const int jx = ix + k.x(), jy = iy + k.y();
        if (grid_.Contains(jx, jy)) blocked_[grid_.Index(jx, jy)] = 1;
      }
    }
  }
  // Beyond the grid everything is unknown: block the rim within reach of the border as well.
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      const double gx = std::min(ix + 0.5, w - ix - 0.5), gy = std::min(iy + 0.5, h - iy - 0.5);
      if (std::min(gx, gy) < r) blocked_[grid_.Index(ix, iy)] = 1;
    }
  }
}

bool Navigator::IsFree(const Eigen::Vector2d& xy) const {
  if (!xy.allFinite()) return false;
  const Eigen::Vector2i c = grid_.CellOf(xy);
  return CellFree(c.x(), c.y());
}

bool Navigator::LineOfSight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  if (!a.allFinite() || !b.allFinite()) return false;
  const double s = grid_.cell_size_m;
  const Eigen::Vector2d ga = (a - grid_.origin_m) / s, gb = (b - grid_.origin_m) / s;
  int ix = static_cast<int>(std::floor(ga.x())), iy = static_cast<int>(std::floor(ga.y()));
  const int jx = static_cast<int>(std::floor(gb.x())), jy = static_cast<int>(std::floor(gb.y()));
  if (!CellFree(ix, iy) || !CellFree(jx, jy)) return false;
  // Amanatides-Woo traversal; a segment through a cell corner touches both side cells.
  const double dx = gb.x() - ga.x(), dy = gb.y() - ga.y();
  const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
  const double delta_x = dx != 0 ? 1.0 / std::abs(dx) : kInf, delta_y = dy != 0 ? 1.0 / std::abs(dy) : kInf;
  double t_x = dx > 0 ? (ix + 1 - ga.x()) * delta_x : dx < 0 ? (ga.x() - ix) * delta_x : kInf;
  double t_y = dy > 0 ? (iy + 1 - ga.y()) * delta_y : dy < 0 ? (ga.y() - iy) * delta_y : kInf;
  const int max_steps = std::abs(jx - ix) + std::abs(jy - iy) + 2;
  constexpr double kTie = 1e-9;
  for (int step = 0; step < max_steps && (ix != jx || iy != jy); ++step) {
    if (t_x < t_y - kTie) {
      ix += step_x;
      t_x += delta_x;
    } else if (t_y < t_x - kTie) {
      iy += step_y;
      t_y += delta_y;
    } else {
      if (!CellFree(ix + step_x, iy) || !CellFree(ix, iy + step_y)) return false;
      ix += step_x;
      iy += step_y;
      t_x += delta_x;
      t_y += delta_y;
    }
    if (!CellFree(ix, iy)) return false;
  }
  return true;
}

bool Navigator::StartFrom(const Eigen::Vector2d& xy, Eigen::Vector2d* start_xy,
                          std::vector<Eigen::Vector2d>* via) const {
  if (via != nullptr) via->clear();
  if (IsFree(xy)) {
    *start_xy = xy;
    return true;
  }
  if (!xy.allFinite()) return false;
  if (options_.start_escape_m > 0.0 && NearestFree(xy, options_.start_escape_m, start_xy)) return true;
  if (!(options_.start_escape_route_m > 0.0)) return false;
  std::vector<Eigen::Vector2d> route = EscapeRoute(xy, options_.start_escape_route_m);
  if (route.empty()) return false;
  *start_xy = route.back();
  if (via != nullptr) {
    route.pop_back();
    *via = std::move(route);
  }
  return true;
}

std::vector<Eigen::Vector2d> Navigator::EscapeRoute(const Eigen::Vector2d& xy, double max_m) const {
  std::vector<Eigen::Vector2d> route;
  if (!xy.allFinite() || !(max_m > 0.0)) return route;
  const Eigen::Vector2i c = grid_.CellOf(xy);
  if (!grid_.Contains(c.x(), c.y()) || grid_.At(c.x(), c.y()) == CellState::kOccupied) return route;
  // Dijkstra in a window of max_m around xy's cell (costs in cells, octile moves, ties by index).
  const int reach = static_cast<int>(std::ceil(max_m / grid_.cell_size_m));
  const double max_cells = max_m / grid_.cell_size_m;
  const int x0 = c.x() - reach, y0 = c.y() - reach, side = 2 * reach + 1;
  const auto local = [&](int ix, int iy) { return static_cast<std::size_t>((iy - y0) * side + (ix - x0)); };
  std::vector<double> cost(static_cast<std::size_t>(side) * side, kInf);
  std::vector<std::int32_t> parent(cost.size(), -1);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[local(c.x(), c.y())] = 0.0;
  open.emplace(0.0, local(c.x(), c.y()));
  std::int64_t found = -1;
  while (!open.empty()) {
    const auto [d, index] = open.top();
    open.pop();
    if (d > cost[index]) continue;
    const int ix = x0 + static_cast<int>(index % side), iy = y0 + static_cast<int>(index / side);
    if (CellFree(ix, iy)) {
      found = static_cast<std::int64_t>(index);
      break;
    }
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int jx = ix + dx, jy = iy + dy;
        if (std::abs(jx - c.x()) > reach || std::abs(jy - c.y()) > reach || !grid_.Contains(jx, jy)) continue;
        if (grid_.At(jx, jy) == CellState::kOccupied) continue;
        // A diagonal move must not cut the corner of an occupied cell.
        if (dx != 0 && dy != 0 &&
            (grid_.At(ix + dx, iy) == CellState::kOccupied || grid_.At(ix, iy + dy) == CellState::kOccupied)) {
          continue;
        }
        const double next = d + (dx != 0 && dy != 0 ? kSqrt2 : 1.0);
        if (next > max_cells) continue;
        const std::size_t j = local(jx, jy);
        if (next < cost[j]) {
          cost[j] = next;
          parent[j] = static_cast<std::int32_t>(index);
          open.emplace(next, j);
        }
      }
    }
  }
  if (found < 0) return route;
  for (std::int64_t i = found; i >= 0 && static_cast<std::size_t>(i) != local(c.x(), c.y());
       i = parent[static_cast<std::size_t>(i)]) {
    route.push_back(grid_.CellCenter(x0 + static_cast<int>(i % side), y0 + static_cast<int>(i / side)));
  }
  std::reverse(route.begin(), route.end());
  return route;
}

Path2D Navigator::Plan(const Eigen::Vector2d& start, const Eigen::Vector2d& goal) const {
  Path2D path;
  if (!IsFree(start)) {
    Eigen::Vector2d escape;
    std::vector<Eigen::Vector2d> via;
    if (StartFrom(start, &escape, &via)) {
      path = Plan(escape, goal);
      if (path.ok()) {
        via.insert(via.begin(), start);
        path.waypoints.insert(path.waypoints.begin(), via.begin(), via.end());
        via.push_back(escape);
        path.grid_length_m += PolylineLength(via);
        path.length_m = PolylineLength(path.waypoints);
      }
      return path;
    }
    path.status = PlanStatus::kStartBlocked;
    return path;
  }
  if (!IsFree(goal)) {
    path.status = PlanStatus::kGoalBlocked;
    return path;
  }
  const Eigen::Vector2i s = grid_.CellOf(start), g = grid_.CellOf(goal);
  const std::size_t start_index = grid_.Index(s.x(), s.y()), goal_index = grid_.Index(g.x(), g.y());
  const int w = grid_.width;
  std::vector<double> cost(grid_.NumCells(), kInf);
  std::vector<std::int32_t> parent(grid_.NumCells(), -1);
  std::vector<std::uint8_t> closed(grid_.NumCells(), 0);
  // (f, -g, index): lowest f first, then deepest, then lowest index, so ties resolve the same way
  // on every platform.
  using Entry = std::tuple<double, double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[start_index] = 0.0;
  open.emplace(Octile(g.x() - s.x(), g.y() - s.y()), 0.0, start_index);
  bool found = false;
  while (!open.empty()) {
    const auto [f, neg_g, index] = open.top();
    open.pop();
    (void)f;
    if (closed[index]) continue;
    closed[index] = 1;
    ++path.expansions;
    if (index == goal_index) {
      found = true;
      break;
    }
    const int ix = static_cast<int>(index % w), iy = static_cast<int>(index / w);
    for (int m = 0; m < 8; ++m) {
      const int nx = ix + kDx[m], ny = iy + kDy[m];
      if (!CellFree(nx, ny)) continue;
      // No corner cutting: a diagonal move needs both straight neighbours free.
      if (m >= 4 && (!CellFree(ix + kDx[m], iy) || !CellFree(ix, iy + kDy[m]))) continue;
      const std::size_t n = grid_.Index(nx, ny);
      if (closed[n]) continue;
      const double g_new = -neg_g + (m >= 4 ? kSqrt2 : 1.0);
      if (g_new < cost[n]) {
        cost[n] = g_new;
        parent[n] = static_cast<std::int32_t>(index);
        open.emplace(g_new + Octile(g.x() - nx, g.y() - ny), -g_new, n);
      }
    }
  }
  if (!found) {
    path.status = PlanStatus::kUnreachable;
    return path;
  }
  std::vector<Eigen::Vector2d> points;
  for (std::int64_t i = static_cast<std::int64_t>(goal_index); i >= 0; i = parent[i]) {
    points.push_back(grid_.CellCenter(static_cast<int>(i % w), static_cast<int>(i / w)));
    if (static_cast<std::size_t>(i) == start_index) break;
  }
  std::reverse(points.begin(), points.end());
  path.grid_length_m = cost[goal_index] * grid_.cell_size_m;
  // The exact start and goal replace their cell centres (each lies inside its free cell).
  points.front() = start;
  points.back() = goal;
  if (points.size() == 1) points.push_back(goal);
  path.waypoints = options_.smooth_path ? Smooth(points) : points;
  path.length_m = PolylineLength(path.waypoints);
  path.status = PlanStatus::kReached;
  return path;
}

std::vector<Eigen::Vector2d> Navigator::Smooth(const std::vector<Eigen::Vector2d>& points) const {
  // Greedy: from each kept point jump to the farthest later point in sight.
  std::vector<Eigen::Vector2d> out{points.front()};
  std::size_t i = 0;
  while (i + 1 < points.size()) {
    std::size_t next = i + 1;
    for (std::size_t j = points.size() - 1; j > i + 1; --j) {
      if (LineOfSight(points[i], points[j])) {
        next = j;
        break;
      }
    }
    out.push_back(points[next]);
    i = next;
  }
  return out;
}

std::vector<double> Navigator::Dijkstra(const Eigen::Vector2d& start, const std::vector<std::uint8_t>& target,
                                        int remaining_targets) const {
  std::vector<double> cost(grid_.NumCells(), kInf);
  if (!IsFree(start)) return cost;
  const bool stop_early = remaining_targets > 0;
  const Eigen::Vector2i s = grid_.CellOf(start);
  const int w = grid_.width;
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const std::size_t start_index = grid_.Index(s.x(), s.y());
  cost[start_index] = 0.0;
  open.emplace(0.0, start_index);
  while (!open.empty()) {
    const auto [c, index] = open.top();
    open.pop();
    if (c > cost[index]) continue;
    if (stop_early && target[index] && --remaining_targets == 0) break;
    const int ix = static_cast<int>(index % w), iy = static_cast<int>(index / w);
    for (int m = 0; m < 8; ++m) {
      const int nx = ix + kDx[m], ny = iy + kDy[m];
      if (!CellFree(nx, ny)) continue;
      if (m >= 4 && (!CellFree(ix + kDx[m], iy) || !CellFree(ix, iy + kDy[m]))) continue;
      const std::size_t n = grid_.Index(nx, ny);
      const double c_new = c + (m >= 4 ? kSqrt2 : 1.0);
      if (c_new < cost[n]) {
        cost[n] = c_new;
        open.emplace(c_new, n);
      }
    }
  }
  return cost;
}

std::vector<double> Navigator::DistanceField(const Eigen::Vector2d& start) const {
  std::vector<double> cost = Dijkstra(start, {}, 0);
  for (double& c : cost) c *= grid_.cell_size_m;
  return cost;
}

std::vector<double> Navigator::PathCosts(const Eigen::Vector2d& start,
                                         const std::vector<Eigen::Vector2d>& targets) const {
  std::vector<double> result(targets.size(), kInf);
  std::vector<std::uint8_t> target_mask(grid_.NumCells(), 0);
  int distinct = 0;
  for (const auto& t : targets) {
    if (!IsFree(t)) continue;
    const Eigen::Vector2i c = grid_.CellOf(t);
    std::uint8_t& m = target_mask[grid_.Index(c.x(), c.y())];
    distinct += m ? 0 : 1;
    m = 1;
  }
  if (distinct == 0) return result;
  const std::vector<double> cost = Dijkstra(start, target_mask, distinct);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!IsFree(targets[i])) continue;
    const Eigen::Vector2i c = grid_.CellOf(targets[i]);
    const std::size_t index = grid_.Index(c.x(), c.y());
    // Every target is settled when the search stops, so its cost is final.
    result[i] = cost[index] * grid_.cell_size_m;
  }
  return result;
}

bool Navigator::NearestFree(const Eigen::Vector2d& xy, double max_distance_m, Eigen::Vector2d* free_xy) const {
  if (IsFree(xy)) {
    *free_xy = xy;
    return true;
  }
  if (!xy.allFinite()) return false;
  const Eigen::Vector2i c = grid_.CellOf(xy);
  const int reach = static_cast<int>(std::ceil(max_distance_m / grid_.cell_size_m)) + 1;
  double best = kInf;
  for (int iy = c.y() - reach; iy <= c.y() + reach; ++iy) {
    for (int ix = c.x() - reach; ix <= c.x() + reach; ++ix) {
      if (!CellFree(ix, iy)) continue;
      const Eigen::Vector2d p = grid_.CellCenter(ix, iy);
      const double d = (p - xy).norm();
      if (d <= max_distance_m && d < best) {
        best = d;
        *free_xy = p;
      }
    }
  }
  return best < kInf;
}

}  // namespace objscan::navigation
