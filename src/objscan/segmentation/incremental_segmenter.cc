#include "objscan/segmentation/incremental_segmenter.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace objscan::segmentation {

void IncrementalSegmenterOptions::Validate() const {
  frame.Validate();
  config::RequireInRange("propagate_min_pixels", propagate_min_pixels, 1, 1 << 24);
  config::RequireInRange("propagate_min_share", propagate_min_share, 0.0, 1.0);
  config::RequireInRange("merge_min_share", merge_min_share, 0.0, 1.0);
  config::RequireInRange("merge_min_pixels", merge_min_pixels, 1, 1 << 24);
  config::RequireInRange("merge_min_frames", merge_min_frames, 1, 1000);
  config::RequirePositive("vote_weight", vote_weight);
  config::RequireInRange("min_component_elements", min_component_elements, 1, 1 << 24);
  // At most half a 16-voxel block: the neighbouring cells of a dirty block's cells stay inside the
  // blocks around it.
  config::RequireInRange("adjacency_cell_voxels", adjacency_cell_voxels, 1, 8);
  config::RequirePositive("floor_prior_tolerance_m", floor_prior_tolerance_m);
  config::RequireInRange("floor_prior_max_tilt_deg", floor_prior_max_tilt_deg, 0.0, 90.0);
  slot_split.Validate();
}

IncrementalSegmenter::IncrementalSegmenter(const IncrementalSegmenterOptions& options) : options_(options) {
  options_.Validate();
  parent_.push_back(0);
}

std::int32_t IncrementalSegmenter::FindRoot(std::int32_t label) {
  std::int32_t root = label;
  while (parent_[root] != root) root = parent_[root];
  while (parent_[label] != root) {
    const std::int32_t next = parent_[label];
    parent_[label] = root;
    label = next;
  }
  return root;
}

void IncrementalSegmenter::ClassifyPixels(const platform::DepthFrame& frame,
                                          const mapping::FrameAssociation& association,
                                          const mapping::SurfaceMap& map) {
  const mapping::VertexNormalMap& vnm = association.vertex_normals;
  const std::size_t n = vnm.valid.size();
  pixel_class_.assign(n, 0);
  const Eigen::Matrix3f R = frame.T_world_camera.rotation().cast<float>();
  const float tz = static_cast<float>(frame.T_world_camera.translation().z());
  // World z of a camera-frame vector is the last row of R.
  const Eigen::RowVector3f up_row = R.row(2);
  const float floor_z = static_cast<float>(options_.floor_prior_height_m);
  const float floor_tol = static_cast<float>(options_.floor_prior_tolerance_m);
  const float cos_tilt = static_cast<float>(std::cos(options_.floor_prior_max_tilt_deg * M_PI / 180.0));
  for (std::size_t i = 0; i < n; ++i) {
    if (!vnm.valid[i]) continue;
    const std::int32_t e = association.pixel_element[i];
    if (e >= 0) {
      const mapping::Structure s = map.structure(static_cast<std::size_t>(e));
      if (s != mapping::Structure::kNone) {
        pixel_class_[i] = static_cast<std::uint8_t>(s);
        continue;
      }
    }
    if (options_.floor_prior && up_row.dot(vnm.normal_camera[i]) >= cos_tilt &&
        std::fabs(up_row.dot(vnm.vertex_camera[i]) + tz - floor_z) < floor_tol) {
      pixel_class_[i] = static_cast<std::uint8_t>(mapping::Structure::kFloor);
    }
  }
}

SegmenterUpdateStats IncrementalSegmenter::Update(const platform::DepthFrame& frame,
                                                  const mapping::FrameAssociation& association,
                                                  mapping::SurfaceMap* map) {
  SegmenterUpdateStats stats;
  const std::size_t n = frame.depth_m.size();
  if (association.pixel_element.size() != n || association.vertex_normals.valid.size() != n) {
    throw InputError("IncrementalSegmenter::Update: association does not belong to this frame");
  }
  const std::vector<std::uint8_t>* pixel_class = nullptr;
  if (options_.separate_structure) {
    ClassifyPixels(frame, association, *map);
    pixel_class = &pixel_class_;
  }
  SegmentFrame(frame, association.vertex_normals, options_.frame, pixel_class, &frame_segmentation_);
  const FrameSegmentation& seg = frame_segmentation_;
  const int num_segments = seg.num_segments();
  stats.frame_segments = num_segments;

  // Step 2: overlap of each frame segment with the global labels of its pixels' elements.
  struct Overlap {
    std::int32_t label;
    int count;
  };
  std::vector<std::vector<Overlap>> overlaps(num_segments);
  std::vector<int> labelled(num_segments, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t s = seg.segment[i];
    const std::int32_t e = association.pixel_element[i];
    if (s < 0 || e < 0) continue;
    const std::int32_t l = map->label(e);
    if (l <= 0) continue;
    ++labelled[s];
    std::vector<Overlap>& o = overlaps[s];
    if (!o.empty() && o.back().label == l) {
      ++o.back().count;
      continue;
    }
    auto it = std::find_if(o.begin(), o.end(), [l](const Overlap& x) { return x.label == l; });
    if (it != o.end()) {
      ++it->count;
      std::iter_swap(it, o.end() - 1);  // recently seen label last: consecutive pixels repeat it
    } else {
      o.push_back({l, 1});
    }
  }

  std::vector<std::int32_t> segment_label(num_segments, 0);
  std::vector<std::int32_t> merged;
  for (int s = 0; s < num_segments; ++s) {
    std::vector<Overlap>& o = overlaps[s];
    std::sort(o.begin(), o.end(), [](const Overlap& a, const Overlap& b) {
      return a.count != b.count ? a.count > b.count : a.label < b.label;
    });
    const double size = seg.segment_size_px[s];
    if (!o.empty() && o[0].count >= options_.propagate_min_pixels &&
        o[0].count >= options_.propagate_min_share * size) {
      segment_label[s] = o[0].label;
      ++stats.propagated;
      // Step 3: further labels covering much of this segment were the same surface.
      for (std::size_t k = 1; k < o.size(); ++k) {
        if (o[k].count < options_.merge_min_pixels || o[k].count < options_.merge_min_share * labelled[s]) break;
        const auto key = std::make_pair(std::min(o[0].label, o[k].label), std::max(o[0].label, o[k].label));
        if (++merge_evidence_[key] < options_.merge_min_frames) continue;
        const std::int32_t ra = FindRoot(o[0].label), rb = FindRoot(o[k].label);
        if (ra == rb || SplitApart(ra, rb)) continue;
        parent_[std::max(ra, rb)] = std::min(ra, rb);
        merged.push_back(std::max(ra, rb));
        ++stats.merges;
      }
    } else {
      segment_label[s] = next_label_++;
      parent_.push_back(segment_label[s]);
      ++stats.new_labels;
    }
  }
  // Apply merges: every merged label is rewritten to its root in the map.
  if (!merged.empty()) {
    std::map<std::int32_t, std::vector<std::int32_t>> groups;
    for (std::int32_t l : merged) groups[FindRoot(l)].push_back(l);
    for (auto& [root, from] : groups) {
      std::sort(from.begin(), from.end());
      map->RelabelAll(from, root);
    }
    for (std::int32_t& l : segment_label) l = FindRoot(l);
  }

  // Step 4: confidence-weighted voting.
  const float weight = static_cast<float>(options_.vote_weight);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t s = seg.segment[i];
    const std::int32_t e = association.pixel_element[i];
    if (s < 0 || e < 0) continue;
    // A segment spanning a slot cut does not pull the other piece's elements back.
    if (SplitApart(segment_label[s], map->label(static_cast<std::size_t>(e)))) continue;
    map->VoteLabel(static_cast<std::size_t>(e), segment_label[s], weight);
  }
  return stats;
}

namespace {

std::int32_t FloorDiv(std::int32_t x, std::int32_t n) { return x >= 0 ? x / n : -((-x + n - 1) / n); }

std::uint64_t PackCell(std::int32_t x, std::int32_t y, std::int32_t z) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x) & 0x1FFFFF) << 42) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y) & 0x1FFFFF) << 21) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(z) & 0x1FFFFF));
}

}  // namespace

const ComponentGraph& IncrementalSegmenter::Components(mapping::SurfaceMap* map) {
  BuildComponents(map);
  // A cut relabels elements or parts neighbours: rebuild and look again (the pieces of a cut may
  // lie apart from their other neighbours), reporting the labels any pass changed.
  for (int pass = 0; pass < 3 && options_.slot_split.enabled && CutAtSlots(map); ++pass) {
    std::vector<std::int32_t> before = std::move(changed_labels_);
    BuildComponents(map);
    std::vector<std::int32_t> all;
    std::set_union(before.begin(), before.end(), changed_labels_.begin(), changed_labels_.end(),
                   std::back_inserter(all));
    changed_labels_ = std::move(all);
  }
  return graph_;
}

bool IncrementalSegmenter::CutAtSlots(mapping::SurfaceMap* map) {
  const SlotSplitOptions& o = options_.slot_split;
  const double element_area = map->voxel_size_m() * map->voxel_size_m();
  // Changed components holding a slot, and the first slot of each.
  std::map<std::int32_t, Slot> cut;
  for (std::int32_t label : changed_labels_) {
    const Component* c = graph_.Find(label);
    if (c == nullptr || static_cast<double>(c->points.size()) * element_area < 2.0 * o.min_part_area_m2) continue;
    const std::vector<Slot> slots = FindSlots(c->points, c->normals, element_area, o);
    if (!slots.empty()) cut.emplace(label, slots.front());
  }
  if (cut.empty()) return false;
  // The part after the slot takes a new label, apart from the part before for good.
  std::map<std::int32_t, std::int32_t> new_label;
  for (const auto& [label, slot] : cut) {
    const std::int32_t after = next_label_++;
    parent_.push_back(after);
    new_label[label] = after;
    split_pairs_.insert({label, after});
  }
  for (std::size_t i = 0; i < map->size(); ++i) {
    const std::int32_t l = map->label(i);
    if (l <= 0 || map->structure(i) != mapping::Structure::kNone) continue;
    auto it = cut.find(l);
    if (it == cut.end() || it->second.Before(map->position(i))) continue;
    map->SetLabel(i, new_label[l], map->label_confidence(i));
  }
  return true;
}

void IncrementalSegmenter::BuildComponents(mapping::SurfaceMap* map) {
  changed_labels_ = map->TakeDirtyLabels();
  std::int32_t max_label = 0;
  for (std::size_t i = 0; i < map->size(); ++i) max_label = std::max(max_label, map->label(i));
  for (std::int32_t l : changed_labels_) max_label = std::max(max_label, l);
  std::vector<std::uint8_t> dirty(static_cast<std::size_t>(max_label) + 1, 0);
  for (std::int32_t l : changed_labels_) dirty[l] = 1;

  // Keep the unchanged components, rebuild the dirty ones in one pass over the map.
  std::map<std::int32_t, Component> rebuilt;
  for (std::int32_t l : changed_labels_) rebuilt[l].label = l;
  const double voxel_area = map->voxel_size_m() * map->voxel_size_m();
  for (std::size_t i = 0; i < map->size(); ++i) {
    const std::int32_t l = map->label(i);
    if (l <= 0 || !dirty[l] || map->structure(i) != mapping::Structure::kNone) continue;
    Component& c = rebuilt[l];
    c.points.push_back(map->position(i));
    c.normals.push_back(map->normal(i));
    c.bounds.Extend(map->position(i).cast<double>());
  }
  ++revision_;
  std::vector<Component> components;
  components.reserve(graph_.components_.size() + rebuilt.size());
  for (Component& c : graph_.components_) {
    if (static_cast<std::size_t>(c.label) < dirty.size() && dirty[c.label]) continue;
    components.push_back(std::move(c));
  }
  for (auto& [label, c] : rebuilt) {
    if (static_cast<int>(c.points.size()) < options_.min_component_elements) continue;
    c.area_m2 = c.points.size() * voxel_area;
    c.revision = revision_;
    components.push_back(std::move(c));
  }
  std::sort(components.begin(), components.end(),
            [](const Component& a, const Component& b) { return a.label < b.label; });

  // Adjacency over cells of adjacency_cell_voxels: labels in the same or 26-neighbouring cells touch.
  // An edge between two unchanged components cannot have changed (their elements did not), so it is
  // kept from the last call; cells are indexed only inside blocks (16 voxels a side) that hold an
  // element of a changed label or neighbour such a block, which is where every other edge lies.
  std::vector<std::uint8_t> present(static_cast<std::size_t>(max_label) + 1, 0);
  for (const Component& c : components) present[c.label] = 1;
  std::unordered_set<std::uint64_t> edges;
  auto add_edge = [&edges](std::int32_t a, std::int32_t b) {
    if (a == b) return;
    if (a > b) std::swap(a, b);
    edges.insert((static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b));
  };
  for (const auto& [a, b] : graph_.Edges()) {
    const bool a_clean = static_cast<std::size_t>(a) < dirty.size() && !dirty[a] && present[a];
    const bool b_clean = static_cast<std::size_t>(b) < dirty.size() && !dirty[b] && present[b];
    if (a_clean && b_clean) add_edge(a, b);
  }
  // Blocks of 16 voxels; a dense grid over the map's key range (one byte per block).
  constexpr int kBlockShift = 4;
  Eigen::Vector3i key_min = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector3i key_max = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
  bool any_dirty = false;
  for (std::size_t i = 0; i < map->size(); ++i) {
    const std::int32_t l = map->label(i);
    if (l <= 0 || !present[l] || map->structure(i) != mapping::Structure::kNone) continue;
    const geometry::VoxelKey& k = map->key(i);
    key_min = key_min.cwiseMin(Eigen::Vector3i(k.x, k.y, k.z));
    key_max = key_max.cwiseMax(Eigen::Vector3i(k.x, k.y, k.z));
    any_dirty = any_dirty || dirty[l];
  }
  std::unordered_map<std::uint64_t, std::uint32_t> cell_index;
  std::vector<geometry::VoxelKey> cell_key;
  std::vector<std::int32_t> cell_label;  // first label seen in the cell
  std::unordered_map<std::uint32_t, std::vector<std::int32_t>> extra;  // further labels of a cell
  if (any_dirty) {
    // Block coordinates relative to key_min, with one block of margin on every side for the dilation.
    const Eigen::Vector3i block_min(key_min.x() >> kBlockShift, key_min.y() >> kBlockShift, key_min.z() >> kBlockShift);
    const Eigen::Vector3i dims = Eigen::Vector3i(key_max.x() >> kBlockShift, key_max.y() >> kBlockShift,
                                                 key_max.z() >> kBlockShift) - block_min + Eigen::Vector3i::Constant(3);
    auto block_of = [&](const geometry::VoxelKey& k) {
      return (static_cast<std::size_t>((k.z >> kBlockShift) - block_min.z() + 1) * dims.y() +
              static_cast<std::size_t>((k.y >> kBlockShift) - block_min.y() + 1)) * dims.x() +
             static_cast<std::size_t>((k.x >> kBlockShift) - block_min.x() + 1);
    };
    std::vector<std::uint8_t> seed(static_cast<std::size_t>(dims.prod()), 0);
    for (std::size_t i = 0; i < map->size(); ++i) {
      const std::int32_t l = map->label(i);
      if (l <= 0 || !present[l] || !dirty[l] || map->structure(i) != mapping::Structure::kNone) continue;
      seed[block_of(map->key(i))] = 1;
    }
    std::vector<std::uint8_t> marked(seed.size(), 0);
    const std::ptrdiff_t sy = dims.x(), sz = static_cast<std::ptrdiff_t>(dims.x()) * dims.y();
    for (int z = 1; z + 1 < dims.z(); ++z) {
      for (int y = 1; y + 1 < dims.y(); ++y) {
        for (int x = 1; x + 1 < dims.x(); ++x) {
          const std::ptrdiff_t b = z * sz + y * sy + x;
          if (!seed[static_cast<std::size_t>(b)]) continue;
          for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
              for (int dx = -1; dx <= 1; ++dx) marked[static_cast<std::size_t>(b + dz * sz + dy * sy + dx)] = 1;
            }
          }
        }
      }
    }
    const std::int32_t cell = options_.adjacency_cell_voxels;
    for (std::size_t i = 0; i < map->size(); ++i) {
      const std::int32_t l = map->label(i);
      if (l <= 0 || !present[l] || map->structure(i) != mapping::Structure::kNone) continue;
      const geometry::VoxelKey& k = map->key(i);
      if (!marked[block_of(k)]) continue;
      const geometry::VoxelKey ck{FloorDiv(k.x, cell), FloorDiv(k.y, cell), FloorDiv(k.z, cell)};
      auto [it, inserted] = cell_index.emplace(PackCell(ck.x, ck.y, ck.z), static_cast<std::uint32_t>(cell_key.size()));
      if (inserted) {
        cell_key.push_back(ck);
        cell_label.push_back(l);
        continue;
      }
      if (cell_label[it->second] == l) continue;
      std::vector<std::int32_t>& e = extra[it->second];
      if (std::find(e.begin(), e.end(), l) == e.end()) e.push_back(l);
    }
  }
  std::vector<std::int32_t> here, there;
  auto labels_of = [&](std::uint32_t c, std::vector<std::int32_t>* out) {
    out->assign(1, cell_label[c]);
    auto it = extra.find(c);
    if (it != extra.end()) out->insert(out->end(), it->second.begin(), it->second.end());
  };
  for (std::uint32_t c = 0; c < cell_key.size(); ++c) {
    labels_of(c, &here);
    for (std::size_t a = 0; a < here.size(); ++a) {
      for (std::size_t b = a + 1; b < here.size(); ++b) add_edge(here[a], here[b]);
    }
    const geometry::VoxelKey& k = cell_key[c];
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          // Each unordered pair of cells once: only "forward" neighbours.
          if (dz < 0 || (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0)))) continue;
          auto it = cell_index.find(PackCell(k.x + dx, k.y + dy, k.z + dz));
          if (it == cell_index.end()) continue;
          labels_of(it->second, &there);
          for (std::int32_t a : here) {
            for (std::int32_t b : there) add_edge(a, b);
          }
        }
      }
    }
  }
  std::vector<std::vector<std::int32_t>> neighbors(components.size());
  std::unordered_map<std::int32_t, std::size_t> index_of;
  for (std::size_t i = 0; i < components.size(); ++i) index_of[components[i].label] = i;
  for (std::uint64_t e : edges) {
    const std::int32_t a = static_cast<std::int32_t>(e >> 32), b = static_cast<std::int32_t>(e & 0xFFFFFFFFu);
    // Pieces cut apart at a slot are not neighbours: no grouping joins them again.
    if (SplitApart(a, b)) continue;
    neighbors[index_of[a]].push_back(b);
    neighbors[index_of[b]].push_back(a);
  }
  graph_.Assign(std::move(components), std::move(neighbors));
}

}  // namespace objscan::segmentation
