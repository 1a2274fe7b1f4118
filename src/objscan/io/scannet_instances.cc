#include "objscan/io/scannet_instances.h"

#include <algorithm>
#include <unordered_map>

#include "objscan/common/union_find.h"
#include "objscan/geometry/aabb.h"
#include "objscan/geometry/voxel_key.h"

namespace objscan::io {
namespace {

constexpr int kMixed = -2;  // a grid cell holding vertices of several pieces

// Footprints (padded by `pad_m`, so that a flat panel still has an area) overlapping by at least
// `min_overlap` of the smaller one, and at most `max_gap_m` apart vertically.
bool Stacked(const geometry::Aabb3& a, const geometry::Aabb3& b, double pad_m, double min_overlap, double max_gap_m) {
  const double gap = std::max(a.min_m.z() - b.max_m.z(), b.min_m.z() - a.max_m.z());
  if (gap > max_gap_m) return false;
  auto side = [pad_m](const geometry::Aabb3& box, int k) { return box.max_m[k] - box.min_m[k] + 2 * pad_m; };
  double overlap = 1.0;
  for (int k = 0; k < 2; ++k) {
    overlap *= std::max(0.0, std::min(a.max_m[k], b.max_m[k]) - std::max(a.min_m[k], b.min_m[k]) + 2 * pad_m);
  }
  const double smaller = std::min(side(a, 0) * side(a, 1), side(b, 0) * side(b, 1));
  return overlap >= min_overlap * smaller;
}

}  // namespace

InferredInstances InferInstancesFromLabels(const std::vector<Eigen::Vector3f>& points_world,
                                           const std::vector<Eigen::Vector3i>& triangles,
                                           const std::vector<std::int32_t>& labels,
                                           const InstanceInferenceOptions& options) {
  const int n = static_cast<int>(labels.size());
  // Pieces: connected components over mesh edges of one label, numbered by their first vertex.
  UnionFind components(n);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (labels[a] != 0 && labels[a] == labels[b]) components.Union(a, b);
    }
  }
  std::vector<int> piece_of(labels.size(), -1);
  std::unordered_map<int, int> piece_of_root;
  std::vector<int> piece_label;
  std::vector<geometry::Aabb3> piece_box;
  for (int v = 0; v < n; ++v) {
    if (labels[v] == 0) continue;
    const auto [it, inserted] = piece_of_root.emplace(components.Find(v), static_cast<int>(piece_label.size()));
    if (inserted) {
      piece_label.push_back(labels[v]);
      piece_box.emplace_back();
    }
    piece_of[v] = it->second;
    piece_box[it->second].Extend(points_world[v].cast<double>());
  }
  const int num_pieces = static_cast<int>(piece_label.size());
  UnionFind groups(num_pieces);

  // Close pieces: vertices within join_distance_m, found through a grid of that cell size. A cell
  // (and its neighbours) holding one piece only cannot join anything, which skips most of the scan.
  const double d = options.join_distance_m;
  if (d > 0.0) {
    const float inv = static_cast<float>(1.0 / d);
    std::unordered_map<geometry::VoxelKey, std::vector<int>, geometry::VoxelKeyHash> cells;
    for (int v = 0; v < n; ++v) {
      if (piece_of[v] >= 0) cells[geometry::KeyOf(points_world[v], inv)].push_back(v);
    }
    std::unordered_map<geometry::VoxelKey, int, geometry::VoxelKeyHash> only_piece;
    for (const auto& [key, vertices] : cells) {
      int only = piece_of[vertices.front()];
      for (int v : vertices) {
        if (piece_of[v] != only) only = kMixed;
      }
      only_piece[key] = only;
    }
    const float d2 = static_cast<float>(d * d);
    for (int v = 0; v < n; ++v) {
      if (piece_of[v] < 0) continue;
      const geometry::VoxelKey k = geometry::KeyOf(points_world[v], inv);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const geometry::VoxelKey nk{k.x + dx, k.y + dy, k.z + dz};
            const auto only = only_piece.find(nk);
            if (only == only_piece.end() || only->second == piece_of[v]) continue;
            for (int w : cells.at(nk)) {
              if (piece_of[w] == piece_of[v] || labels[w] != labels[v]) continue;
              if (groups.Find(piece_of[w]) == groups.Find(piece_of[v])) continue;
              if ((points_world[w] - points_world[v]).squaredNorm() <= d2) groups.Union(piece_of[w], piece_of[v]);
            }
          }
    }
  }

  // Stacked pieces, until no group joins another (a join grows a group's box).
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<geometry::Aabb3> box(static_cast<std::size_t>(num_pieces));
    std::vector<int> roots;
    for (int p = 0; p < num_pieces; ++p) {
      const int r = groups.Find(p);
      if (r == p) roots.push_back(p);
      box[r].Extend(piece_box[p]);
    }
    for (std::size_t i = 0; i < roots.size(); ++i) {
      for (std::size_t j = i + 1; j < roots.size(); ++j) {
        const int a = roots[i], b = roots[j];
        if (piece_label[a] != piece_label[b] || groups.Find(a) == groups.Find(b)) continue;
        if (Stacked(box[a], box[b], 0.5 * d, options.stack_min_overlap, options.stack_max_gap_m)) {
          groups.Union(a, b);
          changed = true;
        }
      }
    }
  }

  // Instances: the groups with enough vertices, numbered by their first vertex.
  std::vector<std::size_t> group_size(static_cast<std::size_t>(num_pieces), 0);
  for (int v = 0; v < n; ++v) {
    if (piece_of[v] >= 0) ++group_size[groups.Find(piece_of[v])];
  }
  InferredInstances out;
  out.vertex_instance.assign(labels.size(), -1);
  std::unordered_map<int, int> instance_of_group;
  for (int v = 0; v < n; ++v) {
    if (piece_of[v] < 0) continue;
    const int g = groups.Find(piece_of[v]);
    if (group_size[g] < options.min_vertices) continue;
    const auto [it, inserted] = instance_of_group.emplace(g, static_cast<int>(out.instance_label.size()));
    if (inserted) out.instance_label.push_back(labels[v]);
    out.vertex_instance[v] = it->second;
  }
  return out;
}

}  // namespace objscan::io
