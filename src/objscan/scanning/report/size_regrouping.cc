#include "objscan/scanning/report/size_regrouping.h"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "objscan/geometry/point_cloud.h"
#include "objscan/geometry/voxel_key.h"
#include "objscan/mapping/planes.h"

namespace objscan::scanning {

RegroupResult RegroupImplausibleFragments(const std::vector<RegroupCandidate>& objects,
                                          const std::vector<std::pair<int, int>>& adjacency,
                                          const recognition::CategoryExtents& extents,
                                          const recognition::SizePlausibilityOptions& options,
                                          const RecognizeUnion& recognize) {
  const int n = static_cast<int>(objects.size());
  RegroupResult out;
  out.host.resize(static_cast<std::size_t>(n));
  out.category.resize(static_cast<std::size_t>(n));
  std::vector<std::vector<Eigen::Vector3f>>& points = out.points_world;
  points.resize(static_cast<std::size_t>(n));
  std::vector<std::set<int>> neighbors(static_cast<std::size_t>(n));
  std::vector<std::vector<int>> members(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) members[static_cast<std::size_t>(i)] = {i};
  for (int i = 0; i < n; ++i) {
    out.host[static_cast<std::size_t>(i)] = i;
    out.category[static_cast<std::size_t>(i)] = objects[static_cast<std::size_t>(i)].category;
    points[static_cast<std::size_t>(i)] = objects[static_cast<std::size_t>(i)].points_world;
  }
  for (const auto& [a, b] : adjacency) {
    if (a == b || a < 0 || b < 0 || a >= n || b >= n) continue;
    neighbors[static_cast<std::size_t>(a)].insert(b);
    neighbors[static_cast<std::size_t>(b)].insert(a);
  }
  const auto fits = [&](const recognition::ObjectExtent& e, world::Category c) {
    return recognition::IsPlausibleExtent(e, extents.Find(c), options);
  };
  const auto movable = [&](int i) {
    return out.host[static_cast<std::size_t>(i)] == i && !objects[static_cast<std::size_t>(i)].fixed &&
           out.category[static_cast<std::size_t>(i)].has_value();
  };
  std::vector<recognition::ObjectExtent> extent(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    extent[k] = recognition::MeasureObjectExtent(points[k], options);
  }
  std::set<int> tried_and_stayed;  // implausible objects no neighbour takes (until something changes)
  while (true) {
    // The smallest implausible object not yet known to stay.
    int piece = -1;
    for (int i = 0; i < n; ++i) {
      if (!movable(i) || tried_and_stayed.count(i) || fits(extent[static_cast<std::size_t>(i)], *out.category[static_cast<std::size_t>(i)])) continue;
      if (piece < 0 || points[static_cast<std::size_t>(i)].size() < points[static_cast<std::size_t>(piece)].size()) piece = i;
    }
    if (piece < 0) break;
    int best_host = -1;
    world::Category best_category = world::Category::kOther;
    recognition::ObjectExtent best_extent;
    bool best_host_joins_piece = false;
    bool best_preferred = false;  // the best host takes the piece (or is no mere part of it)
    for (int h : neighbors[static_cast<std::size_t>(piece)]) {
      if (!movable(h)) continue;
      std::vector<Eigen::Vector3f> joined = points[static_cast<std::size_t>(h)];
      joined.insert(joined.end(), points[static_cast<std::size_t>(piece)].begin(), points[static_cast<std::size_t>(piece)].end());
      const recognition::ObjectExtent e = recognition::MeasureObjectExtent(joined, options);
      const world::Category host_category = *out.category[static_cast<std::size_t>(h)];
      const world::Category piece_category = *out.category[static_cast<std::size_t>(piece)];
      const bool host_plausible = fits(extent[static_cast<std::size_t>(h)], host_category);
      std::optional<world::Category> category;
      bool host_joins_piece = false;
      const bool smaller_host = points[static_cast<std::size_t>(h)].size() < points[static_cast<std::size_t>(piece)].size();
      // The host takes the piece: the union fits the host's label.
      const bool takes = fits(e, host_category);
      if (takes) {
        category = host_category;
        // When the union fits the piece's label too and the piece is the larger, the piece's label
        // stands (a table top over a pedestal labelled sink is a table).
        if (host_plausible && smaller_host && piece_category != host_category && fits(e, piece_category)) {
          category = piece_category;
          host_joins_piece = true;
        }
      } else if (host_plausible && smaller_host) {
        // A plausible neighbour smaller than the piece may be a part of what the piece is (a table's
        // legs apart from its top): the union keeps the piece's label when it fits it.
        if (fits(e, piece_category)) {
          category = piece_category;
          host_joins_piece = true;
        }
      } else if (!host_plausible) {
        std::vector<world::Category> options_in_order = {piece_category};
        if (recognize) {
          std::vector<int> joined_members = members[static_cast<std::size_t>(h)];
          joined_members.insert(joined_members.end(), members[static_cast<std::size_t>(piece)].begin(),
                                members[static_cast<std::size_t>(piece)].end());
          std::sort(joined_members.begin(), joined_members.end());
          options_in_order = recognize(joined_members);
        }
        for (world::Category c : options_in_order) {
          if (fits(e, c)) {
            category = c;
            break;
          }
        }
      }
      if (!category) continue;
      // A neighbour that takes the piece is preferred to one that would only join it.
      const bool preferred = takes || !host_joins_piece;
      if (best_host >= 0 && preferred != best_preferred) {
        if (!preferred) continue;
        best_host = -1;
      }
      if (best_host < 0 || points[static_cast<std::size_t>(h)].size() > points[static_cast<std::size_t>(best_host)].size()) {
        best_host = h;
        best_category = *category;
        best_extent = e;
        best_host_joins_piece = host_joins_piece;
        best_preferred = preferred;
      }
    }
    if (best_host < 0) {
      tried_and_stayed.insert(piece);
      continue;
    }
    // `from` joins `into`: the piece joins its host, or the host joins the larger piece (whose
    // record, model included, then stands for the union).
    const int from = best_host_joins_piece ? best_host : piece;
    const int into = best_host_joins_piece ? piece : best_host;
    auto& into_points = points[static_cast<std::size_t>(into)];
    into_points.insert(into_points.end(), points[static_cast<std::size_t>(from)].begin(),
                       points[static_cast<std::size_t>(from)].end());
    points[static_cast<std::size_t>(from)] = {};
    extent[static_cast<std::size_t>(into)] = best_extent;
    out.category[static_cast<std::size_t>(into)] = best_category;
    auto& merged_members = members[static_cast<std::size_t>(into)];
    merged_members.insert(merged_members.end(), members[static_cast<std::size_t>(from)].begin(),
                          members[static_cast<std::size_t>(from)].end());
    for (int k : neighbors[static_cast<std::size_t>(from)]) {
      if (k == into) continue;
      neighbors[static_cast<std::size_t>(into)].insert(k);
      neighbors[static_cast<std::size_t>(k)].insert(into);
    }
    for (int i = 0; i < n; ++i) {
      if (out.host[static_cast<std::size_t>(i)] == from) out.host[static_cast<std::size_t>(i)] = into;
    }
    ++out.merges;
    tried_and_stayed.clear();  // the host grew: pieces that stayed may fit now
  }
  return out;
}

RegroupResult JoinStackedPieces(const std::vector<RegroupCandidate>& objects, double max_gap_m, double margin_m,
                                const recognition::CategoryExtents& extents,
                                const recognition::SizePlausibilityOptions& options) {
  const int n = static_cast<int>(objects.size());
  RegroupResult out;
  for (int i = 0; i < n; ++i) {
    out.host.push_back(i);
    out.category.push_back(objects[static_cast<std::size_t>(i)].category);
    out.points_world.push_back(objects[static_cast<std::size_t>(i)].points_world);
  }
  const auto joinable = [&](int i) {
    const RegroupCandidate& o = objects[static_cast<std::size_t>(i)];
    if (out.host[static_cast<std::size_t>(i)] != i || o.fixed || !o.category) return false;
    return *o.category != world::Category::kWindow && *o.category != world::Category::kDoor &&
           *o.category != world::Category::kCurtain;
  };
  for (const auto& [a, b] : ObjectsStandingUnder(out.points_world, max_gap_m, margin_m)) {
    const std::size_t ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    if (!joinable(a) || !joinable(b) || objects[ua].category == objects[ub].category) continue;
    // Ties go to the lower index, so the outcome does not depend on anything but the input.
    const bool a_larger = out.points_world[ua].size() >= out.points_world[ub].size();
    const int into = a_larger ? a : b, from = a_larger ? b : a;
    std::vector<Eigen::Vector3f> joined = out.points_world[static_cast<std::size_t>(into)];
    const auto& from_points = out.points_world[static_cast<std::size_t>(from)];
    joined.insert(joined.end(), from_points.begin(), from_points.end());
    const world::Category label = *objects[static_cast<std::size_t>(into)].category;
    const recognition::ObjectExtent joined_extent = recognition::MeasureObjectExtent(joined, options);
    if (!recognition::IsPlausibleExtent(joined_extent, extents.Find(label), options)) continue;
    out.points_world[static_cast<std::size_t>(into)] = std::move(joined);
    out.points_world[static_cast<std::size_t>(from)].clear();
    // What joined `from` before now belongs to `into`: hosts are always objects that host themselves.
    for (int& h : out.host) {
      if (h == from) h = into;
    }
    ++out.merges;
  }
  return out;
}

std::vector<std::pair<int, int>> ObjectsWithinDistance(const std::vector<std::vector<Eigen::Vector3f>>& points_world,
                                                       double distance_m) {
  const float inv = static_cast<float>(1.0 / std::max(1e-6, distance_m));
  // Each cell lists the objects with a point in it, ascending, once.
  std::unordered_map<geometry::VoxelKey, std::vector<int>, geometry::VoxelKeyHash> cells;
  for (int i = 0; i < static_cast<int>(points_world.size()); ++i) {
    for (const auto& p : points_world[static_cast<std::size_t>(i)]) {
      auto& list = cells[geometry::KeyOf(p, inv)];
      if (list.empty() || list.back() != i) list.push_back(i);
    }
  }
  std::set<std::pair<int, int>> pairs;
  for (const auto& [key, here] : cells) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells.find(geometry::VoxelKey{key.x + dx, key.y + dy, key.z + dz});
          if (it == cells.end()) continue;
          for (int a : here)
            for (int b : it->second)
              if (a < b) pairs.emplace(a, b);
        }
  }
  return {pairs.begin(), pairs.end()};
}

std::vector<std::pair<int, int>> ObjectsStandingUnder(const std::vector<std::vector<Eigen::Vector3f>>& points_world,
                                                      double max_gap_m, double margin_m) {
  std::vector<geometry::Aabb3> bounds;
  std::vector<int> nonempty;
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    bounds.push_back(geometry::Bounds(points_world[i]));
    if (!points_world[i].empty()) nonempty.push_back(static_cast<int>(i));
  }
  // Whether object `lower` stands under object `upper`.
  const auto under = [&](int lower, int upper) {
    const geometry::Aabb3& l = bounds[static_cast<std::size_t>(lower)];
    const geometry::Aabb3& u = bounds[static_cast<std::size_t>(upper)];
    for (int k = 0; k < 2; ++k) {
      if (l.min_m[k] < u.min_m[k] - margin_m || l.max_m[k] > u.max_m[k] + margin_m) return false;
    }
    return l.max_m.z() >= u.min_m.z() - max_gap_m && l.max_m.z() <= u.Center().z() && l.min_m.z() < u.min_m.z();
  };
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t a = 0; a < nonempty.size(); ++a) {
    for (std::size_t b = a + 1; b < nonempty.size(); ++b) {
      const int i = nonempty[a], j = nonempty[b];
      if (under(i, j) || under(j, i)) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

std::vector<Eigen::Vector3f> PointsAwayFromWalls(const std::vector<Eigen::Vector3f>& points,
                                                 const mapping::StructureResult& structure, double wall_margin_m) {
  if (wall_margin_m <= 0.0 || structure.walls.empty()) return points;
  std::vector<Eigen::Vector3f> away;
  away.reserve(points.size());
  for (const auto& p : points) {
    if (!structure.NearWall(p.cast<double>(), wall_margin_m)) away.push_back(p);
  }
  return 2 * away.size() >= points.size() ? away : points;
}

}  // namespace objscan::scanning
