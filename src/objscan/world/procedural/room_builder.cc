#include "objscan/world/procedural/room_builder.h"

#include <algorithm>
#include <cmath>

#include "objscan/world/procedural/floor_check.h"
#include "objscan/world/procedural/surface_probe.h"

namespace objscan::world::procedural {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {
constexpr double kFootprintGapM = 0.02;  // minimum gap between floor-standing footprints
}  // namespace

double RoomEdge::InwardYaw() const { return std::atan2(inward.y(), inward.x()); }

std::string ProceduralModelName(Category category, std::uint64_t model_seed) {
  return std::string("procedural/") + CategoryName(category) + "/" + std::to_string(model_seed);
}

bool ParseProceduralModelName(const std::string& model_name, Category* category, std::uint64_t* model_seed) {
  const std::string prefix = "procedural/";
  if (model_name.compare(0, prefix.size(), prefix) != 0) return false;
  const std::size_t slash = model_name.find('/', prefix.size());
  if (slash == std::string::npos || slash + 1 >= model_name.size()) return false;
  const auto c = ParseCategory(model_name.substr(prefix.size(), slash - prefix.size()));
  if (!c) return false;
  std::uint64_t seed = 0;
  for (std::size_t i = slash + 1; i < model_name.size(); ++i) {
    const char ch = model_name[i];
    if (ch < '0' || ch > '9') return false;
    seed = seed * 10 + static_cast<std::uint64_t>(ch - '0');
  }
  *category = *c;
  *model_seed = seed;
  return true;
}

RoomBuilder::RoomBuilder(std::string room_category, std::uint64_t scene_seed, std::uint64_t layout_seed,
                         std::uint64_t first_model_slot, const RoomOptions& options)
    : room_category_(std::move(room_category)),
      scene_seed_(scene_seed),
      options_(options),
      rng_(layout_seed),
      next_model_(first_model_slot) {}

void RoomBuilder::SetOutline(double w, double d, double wall_height_m, int notch_corner, double nw, double nd) {
  width_ = w;
  depth_ = d;
  wall_height_ = wall_height_m;
  switch (notch_corner) {
    case 0: outline_ = {{nw, 0}, {w, 0}, {w, d}, {0, d}, {0, nd}, {nw, nd}}; notch_ = Rect{0, 0, nw, nd}; break;
    case 1: outline_ = {{0, 0}, {w - nw, 0}, {w - nw, nd}, {w, nd}, {w, d}, {0, d}}; notch_ = Rect{w - nw, 0, w, nd}; break;
    case 2: outline_ = {{0, 0}, {w, 0}, {w, d - nd}, {w - nw, d - nd}, {w - nw, d}, {0, d}}; notch_ = Rect{w - nw, d - nd, w, d}; break;
    case 3: outline_ = {{0, 0}, {w, 0}, {w, d}, {nw, d}, {nw, d - nd}, {0, d - nd}}; notch_ = Rect{0, d - nd, nw, d}; break;
    default: outline_ = {{0, 0}, {w, 0}, {w, d}, {0, d}}; notch_.reset(); break;
  }
  edges_.clear();
  for (std::size_t i = 0; i < outline_.size(); ++i) {
    RoomEdge e;
    e.a = outline_[i];
    e.b = outline_[(i + 1) % outline_.size()];
    e.length = (e.b - e.a).norm();
    e.dir = (e.b - e.a) / e.length;
    e.inward = Vector2d(-e.dir.y(), e.dir.x());
    edges_.push_back(e);
  }
}

bool RoomBuilder::Inside(const Rect& r) const {
  const double eps = 1e-9;
  if (r.x0 < -eps || r.y0 < -eps || r.x1 > width_ + eps || r.y1 > depth_ + eps) return false;
  return !(notch_ && r.Overlaps(*notch_, -eps));
}

std::optional<FurnitureModel> RoomBuilder::DrawModel(Category category,
                                                     const std::function<bool(const FurnitureModel&)>& accept,
                                                     int max_draws) {
  for (int k = 0; k < max_draws; ++k) {
    FurnitureModel m = GenerateFurniture(category, SceneModelSeed(room_category_, scene_seed_, next_model_++));
    if (!accept || accept(m)) return m;
  }
  return std::nullopt;
}

geometry::Pose3 RoomBuilder::PoseOf(const Vector2d& center, double z_m, double yaw_rad) const {
  geometry::Pose3 pose = geometry::Pose3::Identity();
  pose.translate(Vector3d(center.x(), center.y(), z_m));
  pose.rotate(Eigen::AngleAxisd(yaw_rad, Vector3d::UnitZ()));
  return pose;
}

Rect RoomBuilder::FootprintOf(const FurnitureModel& model, const geometry::Pose3& pose) {
  const geometry::Aabb3 box = geometry::Bounds(model.mesh, pose);
  return Rect{box.min_m.x(), box.min_m.y(), box.max_m.x(), box.max_m.y()};
}

bool RoomBuilder::ChooseDoor(const FurnitureModel& door) {
  const Vector3d size = geometry::Bounds(door.mesh).Size();
  const double leaf_w = size.y(), open_w = leaf_w + 0.04, open_h = std::min(size.z() + 0.03, wall_height_ - 0.15);
  // Candidate walls: long enough for the opening plus the leaf resting beside it.
  std::vector<int> candidates;
  for (int i = 0; i < static_cast<int>(edges_.size()); ++i) {
    if (edges_[i].length >= open_w + leaf_w + 0.35) candidates.push_back(i);
  }
  if (candidates.empty()) return false;
  const int ei = candidates[rng_.UniformInt(0, static_cast<int>(candidates.size()) - 1)];
  RoomEdge& e = edges_[ei];
  const bool leaf_after = rng_.Bernoulli(0.5);
  // Opening position leaving room for the leaf on its side.
  const double lo = leaf_after ? 0.15 : 0.15 + leaf_w + 0.05;
  const double hi = leaf_after ? e.length - open_w - leaf_w - 0.2 : e.length - open_w - 0.15;
  if (hi < lo) return false;
  const double s0 = rng_.Uniform(lo, hi), s1 = s0 + open_w;
  e.openings.push_back({s0, s1, 0.0, open_h});
  // The leaf, opened flat against the wall next to the opening.
  const double leaf_s = leaf_after ? s1 + 0.03 + 0.5 * leaf_w : s0 - 0.03 - 0.5 * leaf_w;
  const double hx = 0.5 * size.x();
  const geometry::Pose3 pose = PoseOf(e.At(leaf_s, 0.01 + hx), 0.0, e.InwardYaw());
  pending_.push_back({door, pose});
  // Keep the way in clear.
  const Vector2d p0 = e.At(s0 - 0.05, 0.0), p1 = e.At(s1 + 0.05, 1.0);
  reserved_.push_back(Rect{std::min(p0.x(), p1.x()), std::min(p0.y(), p1.y()), std::max(p0.x(), p1.x()),
                           std::max(p0.y(), p1.y())});
  reserved_.push_back(FootprintOf(door, pose));
  return true;
}

bool RoomBuilder::ChooseWindow(const FurnitureModel& window, double sill_z_m) {
  const Vector3d size = geometry::Bounds(window.mesh).Size();
  const double z1 = sill_z_m + size.z();
  if (z1 > wall_height_ - 0.1) return false;
  std::vector<std::pair<int, double>> candidates;  // (edge, s0)
  for (int tries = 0; tries < 20; ++tries) {
    const int ei = rng_.UniformInt(0, static_cast<int>(edges_.size()) - 1);
    const RoomEdge& e = edges_[ei];
    if (e.length < size.y() + 0.7) continue;
    const double s0 = rng_.Uniform(0.35, e.length - size.y() - 0.35), s1 = s0 + size.y();
    bool clear = true;
    for (const auto& o : e.openings) clear = clear && (s1 + 0.3 < o.s0 || o.s1 + 0.3 < s0);
    if (!clear) continue;
    edges_[ei].openings.push_back({s0, s1, sill_z_m, z1});
    const double hx = 0.5 * size.x();
    // Back of the frame flush with the outside of the wall; a sill may stand a little proud inside.
    const double inward = -options_.wall_thickness_m + hx;
    const double s_c = 0.5 * (s0 + s1);
    pending_.push_back({window, PoseOf(e.At(s_c, inward), sill_z_m, e.InwardYaw())});
    windows_.push_back({ei, s_c, size.y(), sill_z_m, z1, std::max(0.0, inward + hx)});
    const Vector2d p0 = e.At(s0 - 0.1, 0.0), p1 = e.At(s1 + 0.1, 0.8);
    window_zones_.push_back({Rect{std::min(p0.x(), p1.x()), std::min(p0.y(), p1.y()), std::max(p0.x(), p1.x()),
                                  std::max(p0.y(), p1.y())},
                             sill_z_m - 0.02});
    return true;
  }
  return false;
}

void RoomBuilder::BuildStructure() {
  auto add_structure = [&](Category c, const std::string& name, geometry::TriangleMesh mesh) {
    SceneObject o;
    o.category = c;
    o.model_name = "procedural/" + name;
    o.mesh = std::move(mesh);
    const auto id = scene_.Add(std::move(o));
    scene_.mutable_objects().back().name = name + "_" + std::to_string(id);
    footprints_.push_back({Rect{}, -1});
  };
  // Floor: one or two quads at z = 0 covering the outline.
  geometry::TriangleMesh floor;
  if (!notch_) {
    floor = geometry::MakeQuadXY(0, 0, width_, depth_);
  } else {
    const Rect& n = *notch_;
    const double ya0 = n.y0 <= 0.0 ? n.y1 : 0.0, ya1 = n.y0 <= 0.0 ? depth_ : n.y0;
    const double xb0 = n.x0 <= 0.0 ? n.x1 : 0.0, xb1 = n.x0 <= 0.0 ? width_ : n.x0;
    geometry::Append(geometry::MakeQuadXY(0, ya0, width_, ya1), &floor);
    geometry::Append(geometry::MakeQuadXY(xb0, n.y0, xb1, n.y1), &floor);
  }
  add_structure(Category::kFloor, "floor", floor);

  // Walls: one object per edge, boxes outside the outline, split around openings; convex corners
  // are closed by extending the wall by its thickness.
  const double t = options_.wall_thickness_m;
  const int n = static_cast<int>(edges_.size());
  for (int i = 0; i < n; ++i) {
    const RoomEdge& e = edges_[i];
    const RoomEdge& prev = edges_[(i + n - 1) % n];
    const RoomEdge& next = edges_[(i + 1) % n];
    auto convex = [](const RoomEdge& a, const RoomEdge& b) { return a.dir.x() * b.dir.y() - a.dir.y() * b.dir.x() > 0; };
    const double s_lo = convex(prev, e) ? -t : 0.0, s_hi = e.length + (convex(e, next) ? t : 0.0);
    geometry::TriangleMesh mesh;
    auto piece = [&](double s0, double s1, double z0, double z1) {
      if (s1 - s0 <= 1e-6 || z1 - z0 <= 1e-6) return;
      const Vector2d p0 = e.At(s0, 0.0), p1 = e.At(s1, -t);
      geometry::Append(geometry::MakeBox(Vector3d(std::min(p0.x(), p1.x()), std::min(p0.y(), p1.y()), z0),
                                         Vector3d(std::max(p0.x(), p1.x()), std::max(p0.y(), p1.y()), z1)),
                       &mesh);
    };
    std::vector<RoomEdge::Opening> openings = e.openings;
    std::sort(openings.begin(), openings.end(), [](const auto& a, const auto& b) { return a.s0 < b.s0; });
    double s = s_lo;
    for (const auto& o : openings) {
      piece(s, o.s0, 0.0, wall_height_);
      piece(o.s0, o.s1, 0.0, o.z0);
      piece(o.s0, o.s1, o.z1, wall_height_);
      s = o.s1;
    }
    piece(s, s_hi, 0.0, wall_height_);
    add_structure(Category::kWall, "wall", mesh);
  }
  // Door and windows.
  for (const auto& p : pending_) {
    const Rect r = FootprintOf(p.model, p.pose);
    SceneObject o;
    o.category = p.model.category;
    o.model_name = ProceduralModelName(p.model.category, p.model.model_seed);
    o.mesh = p.model.mesh;
    o.T_world_object = p.pose;
    const auto id = scene_.Add(std::move(o));
    scene_.mutable_objects().back().name = std::string(CategoryName(p.model.category)) + "_" + std::to_string(id);
    // Windows sit in the wall band: they take no floor space.
    footprints_.push_back({p.model.category == Category::kWindow ? Rect{} : r, -1});
    ++num_furniture_;
  }
  pending_.clear();
}

bool RoomBuilder::FloorFits(const Rect& r, double height_m) const {
  if (!Inside(r)) return false;
  for (const auto& f : footprints_) {
    if (f.support < 0 && f.rect.Width() > 0 && r.Overlaps(f.rect, kFootprintGapM)) return false;
  }
  for (const auto& z : reserved_) {
    if (r.Overlaps(z)) return false;
  }
  for (const auto& z : window_zones_) {
    if (height_m > z.max_height_m && r.Overlaps(z.rect)) return false;
  }
  return true;
}

Placement RoomBuilder::Commit(const FurnitureModel& model, const Vector2d& center, double z_m, double yaw_rad,
                              bool check_floor, int support) {
  Placement p;
  if (Full()) return p;
  const geometry::Pose3 pose = PoseOf(center, z_m, yaw_rad);
  SceneObject o;
  o.category = model.category;
  o.model_name = ProceduralModelName(model.category, model.model_seed);
  o.mesh = model.mesh;
  o.T_world_object = pose;
  const auto id = scene_.Add(std::move(o));
  scene_.mutable_objects().back().name = std::string(CategoryName(model.category)) + "_" + std::to_string(id);
  const Rect r = FootprintOf(model, pose);
  footprints_.push_back({r, support});
  if (check_floor) {
    const FloorConnectivityReport report =
        CheckFreeFloor(scene_, options_.floor_cell_m, options_.passage_m, options_.max_reach_m);
    if (!report.ok) {
      scene_.mutable_objects().pop_back();
      footprints_.pop_back();
      return p;
    }
  }
  ++num_furniture_;
  p.index = static_cast<int>(scene_.objects().size()) - 1;
  p.footprint = r;
  const geometry::Aabb3 box = geometry::Bounds(model.mesh, pose);
  p.height_m = box.max_m.z();
  p.center = center;
  p.yaw_rad = yaw_rad;
  p.size_m = geometry::Bounds(model.mesh).Size();
  return p;
}

Placement RoomBuilder::PlaceCurtain(const FurnitureModel& curtain, int window) {
  const WindowInfo& w = windows_.at(window);
  const RoomEdge& e = edges_[w.edge];
  const Vector3d size = geometry::Bounds(curtain.mesh).Size();
  if (w.s_center - 0.5 * size.y() < 0.02 || w.s_center + 0.5 * size.y() > e.length - 0.02) return {};
  // Floor-length curtains hang just above the floor, short ones cover the window from the sill down a little.
  double z = size.z() > 1.8 ? 0.01 : std::max(0.01, w.z0_m - 0.1);
  if (z + size.z() > wall_height_ - 0.02) z = wall_height_ - 0.02 - size.z();
  if (z < 0.0) return {};
  const Vector2d c = e.At(w.s_center, w.protrusion_m + 0.01 + 0.5 * size.x());
  const double yaw = e.InwardYaw();
  const Rect r = FootprintOf(curtain, PoseOf(c, z, yaw));
  if (!FloorFits(r, 0.0)) return {};
  Placement p = Commit(curtain, c, z, yaw, true, -1);
  if (p.Valid()) {
    p.edge = w.edge;
    p.s_center = w.s_center;
  }
  return p;
}

Placement RoomBuilder::PlaceAgainstWall(const FurnitureModel& model, int edge, double s_center, double gap_m) {
  const RoomEdge& e = edges_.at(edge);
  const Vector3d size = geometry::Bounds(model.mesh).Size();
  if (s_center - 0.5 * size.y() < 0.0 || s_center + 0.5 * size.y() > e.length) return {};
  const Vector2d c = e.At(s_center, gap_m + 0.5 * size.x());
  const double yaw = e.InwardYaw();
  const Rect r = FootprintOf(model, PoseOf(c, 0.0, yaw));
  if (!FloorFits(r, size.z())) return {};
  Placement p = Commit(model, c, 0.0, yaw, true, -1);
  if (p.Valid()) {
    p.edge = edge;
    p.s_center = s_center;
  }
  return p;
}

Placement RoomBuilder::PlaceAgainstAnyWall(const FurnitureModel& model, int tries, double corner_bias, double gap_m) {
  const Vector3d size = geometry::Bounds(model.mesh).Size();
  double total = 0.0;
  for (const auto& e : edges_) total += std::max(0.0, e.length - size.y());
  if (total <= 0.0) return {};
  for (int k = 0; k < tries; ++k) {
    // Pick a wall with probability proportional to its usable length.
    double u = rng_.Uniform(0.0, total);
    int ei = 0;
    for (; ei + 1 < static_cast<int>(edges_.size()); ++ei) {
      const double usable = std::max(0.0, edges_[ei].length - size.y());
      if (u < usable) break;
      u -= usable;
    }
    const RoomEdge& e = edges_[ei];
    if (e.length < size.y() + 0.02) continue;
    const double lo = 0.5 * size.y() + 0.01, hi = e.length - 0.5 * size.y() - 0.01;
    double s = rng_.Uniform(lo, hi);
    if (rng_.Bernoulli(corner_bias)) s = rng_.Bernoulli(0.5) ? lo : hi;
    const Placement p = PlaceAgainstWall(model, ei, s, gap_m);
    if (p.Valid()) return p;
  }
  return {};
}

Placement RoomBuilder::PlaceFree(const FurnitureModel& model, const Vector2d& center, double yaw_rad) {
  const Rect r = FootprintOf(model, PoseOf(center, 0.0, yaw_rad));
  if (!FloorFits(r, geometry::Bounds(model.mesh).max_m.z())) return {};
  return Commit(model, center, 0.0, yaw_rad, true, -1);
}

Placement RoomBuilder::PlaceOnTop(const FurnitureModel& model, const Placement& support, int tries, bool back_bias) {
  if (!support.Valid() || Full()) return {};
  const SurfaceProbe probe(scene_.objects()[support.index]);
  const geometry::Aabb3 local = geometry::Bounds(model.mesh);
  const Vector3d half = 0.5 * local.Size();
  const Vector3d support_half = 0.5 * support.size_m;
  const double range_x = support_half.x() - half.x() - 0.01, range_y = support_half.y() - half.y() - 0.01;
  if (range_x < 0.0 || range_y < 0.0) return {};
  const Eigen::Rotation2Dd R(support.yaw_rad);
  for (int k = 0; k < tries; ++k) {
    // Position in the support's frame (models are centred, so its box is +-support_half).
    const double lx = back_bias ? rng_.Uniform(-range_x, std::min(range_x, -range_x + 0.15)) : rng_.Uniform(-range_x, range_x);
    const double ly = rng_.Uniform(-range_y, range_y);
    const Vector2d c = support.center + R * Vector2d(lx, ly);
    // Probe the surface under the corners and the centre of the object's footprint.
    const geometry::Pose3 flat = PoseOf(c, 0.0, support.yaw_rad);
    const Rect r = FootprintOf(model, flat);
    const double cs[5][2] = {{r.x0 + 0.01, r.y0 + 0.01}, {r.x1 - 0.01, r.y0 + 0.01}, {r.x0 + 0.01, r.y1 - 0.01},
                             {r.x1 - 0.01, r.y1 - 0.01}, {0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1)}};
    double zmin = 0.0, zmax = 0.0;
    bool ok = true;
    for (int i = 0; i < 5 && ok; ++i) {
      double z = 0.0;
      ok = probe.TopHeightAt(cs[i][0], cs[i][1], &z);
      if (!ok) break;
      zmin = i == 0 ? z : std::min(zmin, z);
      zmax = i == 0 ? z : std::max(zmax, z);
    }
    if (!ok || zmax - zmin > 0.002 || zmax < 0.2) continue;
    // Not on another object standing on the same support.
    bool free = true;
    for (const auto& f : footprints_) free = free && !(f.support == support.index && r.Overlaps(f.rect, 0.02));
    if (!free) continue;
    // Checked too: a small object must itself be within reach, not only its support.
    Placement p = Commit(model, c, zmax, support.yaw_rad, true, support.index);
    if (p.Valid()) return p;
  }
  return {};
}

}  // namespace objscan::world::procedural
