// GenerateRoom: per-category furnishing plans on top of RoomBuilder.
#include <algorithm>
#include <cmath>
#include <string>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/world/procedural/procedural.h"
#include "objscan/world/procedural/room.h"
#include "objscan/world/procedural/room_builder.h"

namespace objscan::world::procedural {
namespace {

using Accept = std::function<bool(const FurnitureModel&)>;
using Eigen::Vector2d;
using Eigen::Vector3d;

int RoomIndex(const std::string& room_category) {
  const auto& names = RoomCategories();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == room_category) return static_cast<int>(i);
  }
  throw InputError("procedural room: unknown category '" + room_category +
                   "' (bedroom, living_room, kitchen, bathroom, office)");
}

bool Has(const FurnitureModel& m, const char* part) { return m.name.find(part) != std::string::npos; }
Vector3d SizeOf(const FurnitureModel& m) { return geometry::Bounds(m.mesh).Size(); }

Accept TableLamp() {
  return [](const FurnitureModel& m) { return (Has(m, "lamp_table") || Has(m, "lamp_desk")) && SizeOf(m).z() < 0.7; };
}
Accept FloorLamp() { return [](const FurnitureModel& m) { return Has(m, "lamp_floor") || Has(m, "lamp_arc"); }; }
Accept Tv() { return [](const FurnitureModel& m) { return Has(m, "_tv_"); }; }
Accept ComputerMonitor() { return [](const FurnitureModel& m) { return !Has(m, "_tv_"); }; }
Accept Named(const char* part) { return [part](const FurnitureModel& m) { return Has(m, part); }; }
Accept NotNamed(const char* part) { return [part](const FurnitureModel& m) { return !Has(m, part); }; }
Accept Any() { return {}; }

// Something standing on `support`, drawn from `category`.
Placement OnTop(RoomBuilder& b, const Placement& support, Category category, const Accept& accept, double p,
                bool back_bias = false) {
  if (!support.Valid() || b.Full() || !b.rng().Bernoulli(p)) return {};
  for (int k = 0; k < 3; ++k) {
    const auto model = b.DrawModel(category, accept);
    if (!model) return {};
    const Placement placed = b.PlaceOnTop(*model, support, 15, back_bias);
    if (placed.Valid()) return placed;
  }
  return {};
}

Placement WallItem(RoomBuilder& b, Category category, const Accept& accept, double corner_bias = 0.3,
                   double gap_m = 0.02) {
  if (b.Full()) return {};
  for (int k = 0; k < 3; ++k) {
    const auto model = b.DrawModel(category, accept);
    if (!model) return {};
    const Placement placed = b.PlaceAgainstAnyWall(*model, 25, corner_bias, gap_m);
    if (placed.Valid()) return placed;
  }
  return {};
}

// Door, windows (sill height range) and curtains (probability per window).
void Structure(RoomBuilder& b, int windows, double sill_lo, double sill_hi, double curtain_p) {
  for (int k = 0; k < 5; ++k) {
    const auto door = b.DrawModel(Category::kDoor);
    if (door && b.ChooseDoor(*door)) break;
  }
  for (int i = 0; i < windows; ++i) {
    const double sill = b.rng().Uniform(sill_lo, sill_hi);
    const double max_h = b.wall_height() - 0.15 - sill;
    const auto window = b.DrawModel(Category::kWindow, [&](const FurnitureModel& m) { return SizeOf(m).z() <= max_h; });
    if (window) b.ChooseWindow(*window, sill);
  }
  b.BuildStructure();
  for (int i = 0; i < b.NumWindows(); ++i) {
    if (!b.rng().Bernoulli(curtain_p)) continue;
    const double w = b.WindowWidth(i);
    const auto curtain = b.DrawModel(Category::kCurtain, [&](const FurnitureModel& m) {
      const double cw = SizeOf(m).y();
      return cw >= w + 0.1 && cw <= w + 0.8;
    });
    if (curtain) b.PlaceCurtain(*curtain, i);
  }
}

// Outline with an optional L notch; arms of the L stay at least `min_arm_m` wide.
void Outline(RoomBuilder& b, double w_lo, double w_hi, double d_lo, double d_hi, double l_shape_p) {
  Rng& rng = b.rng();
  const double w = rng.Uniform(w_lo, w_hi), d = rng.Uniform(d_lo, d_hi);
  const double h = rng.Uniform(2.4, 3.0);
  int corner = -1;
  double nw = 0.0, nd = 0.0;
  if (rng.Bernoulli(l_shape_p)) {
    corner = rng.UniformInt(0, 3);
    nw = std::min(rng.Uniform(0.25, 0.45) * w, w - 2.2);
    nd = std::min(rng.Uniform(0.25, 0.45) * d, d - 2.2);
    if (nw < 0.8 || nd < 0.8) corner = -1;
  }
  b.SetOutline(w, d, h, corner, nw, nd);
}

// A desk against a wall with a chair in front and things on it.
void DeskGroup(RoomBuilder& b, const Accept& desk_accept, int monitors, double lamp_p, double radio_p) {
  const Placement desk = WallItem(b, Category::kDesk, desk_accept, 0.3, 0.02);
  if (!desk.Valid()) return;
  if (const auto chair = b.DrawModel(Category::kChair)) {
    const double gap = b.rng().Uniform(0.05, 0.15);
    const Vector2d c = desk.center + desk.Front() * (0.5 * desk.size_m.x() + gap + 0.5 * SizeOf(*chair).x());
    b.PlaceFree(*chair, c, desk.yaw_rad + M_PI);
  }
  for (int k = 0; k < monitors; ++k) OnTop(b, desk, Category::kMonitor, ComputerMonitor(), 1.0, true);
  OnTop(b, desk, Category::kLamp, TableLamp(), lamp_p);
  OnTop(b, desk, Category::kRadio, Any(), radio_p);
}

// A free-standing table with chairs around it, facing it.
void TableGroup(RoomBuilder& b, const Accept& table_accept, int max_chairs) {
  if (b.Full()) return;
  const auto table = b.DrawModel(Category::kTable, table_accept);
  const auto chair = b.DrawModel(Category::kChair, [](const FurnitureModel& m) { return !Has(m, "pedestal"); });
  if (!table || !chair) return;
  const Vector3d ts = SizeOf(*table), cs = SizeOf(*chair);
  const double reach = 0.5 * std::max(ts.x(), ts.y()) + cs.x() + 0.1;
  Placement tp;
  for (int k = 0; k < 30 && !tp.Valid(); ++k) {
    const double yaw = b.rng().Bernoulli(0.5) ? 0.0 : 0.5 * M_PI;
    const double mx = std::min(0.5 * b.width(), reach + 0.2), my = std::min(0.5 * b.depth(), reach + 0.2);
    const Vector2d c(b.rng().Uniform(mx, b.width() - mx), b.rng().Uniform(my, b.depth() - my));
    tp = b.PlaceFree(*table, c, yaw);
  }
  if (!tp.Valid()) return;
  // Seats in the table's frame (x across the table, y along it), each facing the table centre.
  std::vector<std::pair<Vector2d, double>> seats;
  const double gap = 0.06;
  const double side_x = 0.5 * ts.x() + gap + 0.5 * cs.x(), end_y = 0.5 * ts.y() + gap + 0.5 * cs.x();
  const int per_side = std::clamp(static_cast<int>(std::round(ts.y() / 0.7)), 1, 3);
  for (int k = 0; k < per_side; ++k) {
    const double y = per_side == 1 ? 0.0 : -0.5 * ts.y() + ts.y() * (k + 0.5) / per_side;
    seats.push_back({Vector2d(side_x, y), M_PI});
    seats.push_back({Vector2d(-side_x, y), 0.0});
  }
  seats.push_back({Vector2d(0, end_y), -0.5 * M_PI});
  seats.push_back({Vector2d(0, -end_y), 0.5 * M_PI});
  // Shuffle deterministically, then seat up to max_chairs.
  for (int i = static_cast<int>(seats.size()) - 1; i > 0; --i) std::swap(seats[i], seats[b.rng().UniformInt(0, i)]);
  const Eigen::Rotation2Dd R(tp.yaw_rad);
  int placed = 0;
  for (const auto& seat : seats) {
    if (placed >= max_chairs || b.Full()) break;
    if (b.PlaceFree(*chair, tp.center + R * seat.first, tp.yaw_rad + seat.second).Valid()) ++placed;
  }
}

// The wall whose inward normal points along `direction` (e.g. the wall facing a sofa).
int WallFacing(const RoomBuilder& b, const Vector2d& direction) {
  for (int i = 0; i < static_cast<int>(b.edges().size()); ++i) {
    if (b.edges()[i].inward.dot(direction) > 0.99) return i;
  }
  return -1;
}

void PlanBedroom(RoomBuilder& b) {
  Rng& rng = b.rng();
  Outline(b, 3.2, 4.6, 3.5, 5.0, 0.3);
  Structure(b, rng.UniformInt(1, 2), 0.75, 0.95, 0.7);
  const bool dbl = rng.Bernoulli(0.65);
  const Placement bed = WallItem(b, Category::kBed, Named(dbl ? "double" : "single"), 0.25, 0.02);
  if (bed.Valid()) {
    const int stands = dbl ? (rng.Bernoulli(0.8) ? 2 : 1) : (rng.Bernoulli(0.7) ? 1 : 2);
    const double first = rng.Bernoulli(0.5) ? 1.0 : -1.0;
    for (int k = 0; k < stands; ++k) {
      const auto ns = b.DrawModel(Category::kNightStand);
      if (!ns) break;
      const double side = k == 0 ? first : -first;
      const double s = bed.s_center + side * (0.5 * bed.size_m.y() + 0.04 + 0.5 * SizeOf(*ns).y());
      const Placement nsp = b.PlaceAgainstWall(*ns, bed.edge, s, 0.02);
      OnTop(b, nsp, Category::kLamp, TableLamp(), 0.75);
    }
  }
  const Placement dresser = rng.Bernoulli(0.8) ? WallItem(b, Category::kDresser, Any()) : Placement{};
  OnTop(b, dresser, Category::kRadio, Any(), 0.35);
  OnTop(b, dresser, Category::kLamp, TableLamp(), 0.3);
  OnTop(b, dresser, Category::kMonitor, Tv(), 0.15, true);
  if (rng.Bernoulli(0.6)) WallItem(b, Category::kCabinet, Named("wardrobe"), 0.6);
  if (rng.Bernoulli(0.5)) {
    const Placement shelves = WallItem(b, Category::kShelves, Any());
    OnTop(b, shelves, Category::kRadio, Any(), 0.3);
  }
  if (rng.Bernoulli(0.45)) DeskGroup(b, NotNamed("lshape"), rng.UniformInt(0, 1), 0.5, 0.1);
  if (rng.Bernoulli(0.3)) WallItem(b, Category::kChair, Named("_arms"), 0.4, 0.1);
  if (rng.Bernoulli(0.3)) WallItem(b, Category::kLamp, FloorLamp(), 0.8, 0.05);
  if (rng.Bernoulli(0.2)) {
    const Placement stand = WallItem(b, Category::kTvStand, Any());
    OnTop(b, stand, Category::kMonitor, Tv(), 0.9, true);
  }
}

void PlanLivingRoom(RoomBuilder& b) {
  Rng& rng = b.rng();
  Outline(b, 4.5, 6.5, 5.0, 7.0, 0.35);
  Structure(b, rng.UniformInt(1, 3), 0.6, 0.9, 0.7);
  const Placement sofa = WallItem(b, Category::kSofa, Any(), 0.2, 0.05);
  if (sofa.Valid()) {
    // Coffee table in front of the sofa, armchairs beside it facing it.
    const auto table = b.DrawModel(Category::kTable, Named("coffee"));
    Placement tp;
    if (table) {
      const double gap = rng.Uniform(0.35, 0.5);
      tp = b.PlaceFree(*table, sofa.center + sofa.Front() * (0.5 * sofa.size_m.x() + gap + 0.5 * SizeOf(*table).x()),
                       sofa.yaw_rad);
    }
    if (tp.Valid()) {
      OnTop(b, tp, Category::kRadio, Any(), 0.1);
      const int chairs = rng.UniformInt(0, 2);
      const auto chair = b.DrawModel(Category::kChair, Named("_arms"));
      const Eigen::Rotation2Dd R(tp.yaw_rad);
      const double first = rng.Bernoulli(0.5) ? 1.0 : -1.0;
      for (int k = 0; k < chairs && chair; ++k) {
        const double side = k == 0 ? first : -first;
        const Vector2d offset(0.0, side * (0.5 * tp.size_m.y() + 0.3 + 0.5 * SizeOf(*chair).x()));
        b.PlaceFree(*chair, tp.center + R * offset, tp.yaw_rad - side * 0.5 * M_PI);
      }
    }
    // TV on a stand on the wall facing the sofa.
    const int wall = WallFacing(b, -sofa.Front());
    const auto stand = b.DrawModel(Category::kTvStand);
    Placement sp;
    if (stand && wall >= 0) {
      const RoomEdge& e = b.edges()[wall];
      const double s0 = (sofa.center - e.a).dot(e.dir);
      for (int k = 0; k < 9 && !sp.Valid(); ++k) {
        const double s = s0 + ((k + 1) / 2) * 0.35 * (k % 2 == 0 ? 1.0 : -1.0);
        sp = b.PlaceAgainstWall(*stand, wall, s, 0.02);
      }
    }
    if (!sp.Valid() && stand) sp = b.PlaceAgainstAnyWall(*stand, 20, 0.0);
    OnTop(b, sp, Category::kMonitor, Tv(), 0.9, true);
    OnTop(b, sp, Category::kRadio, Any(), 0.2);
  }
  if (rng.Bernoulli(0.3)) WallItem(b, Category::kSofa, NotNamed("lshape"), 0.3, 0.05);
  const int shelves = rng.UniformInt(0, 2);
  for (int k = 0; k < shelves; ++k) {
    const Placement sh = WallItem(b, Category::kShelves, Any());
    OnTop(b, sh, Category::kRadio, Any(), 0.25);
  }
  const int floor_lamps = rng.UniformInt(0, 2);
  for (int k = 0; k < floor_lamps; ++k) WallItem(b, Category::kLamp, FloorLamp(), 0.7, 0.05);
  if (rng.Bernoulli(0.4)) {
    const Placement side = WallItem(b, Category::kCabinet, Named("sideboard"), 0.2);
    OnTop(b, side, Category::kLamp, TableLamp(), 0.5);
    OnTop(b, side, Category::kRadio, Any(), 0.3);
  }
  if (rng.Bernoulli(0.45)) TableGroup(b, Named("dining"), rng.UniformInt(2, 4));
  if (rng.Bernoulli(0.25)) WallItem(b, Category::kChair, Named("_arms"), 0.3, 0.1);
}

void PlanKitchen(RoomBuilder& b) {
  Rng& rng = b.rng();
  Outline(b, 3.0, 4.5, 3.5, 5.5, 0.25);
  Structure(b, rng.UniformInt(1, 2), 0.95, 1.1, 0.2);
  // A counter run: base cabinets with the sink among them and the refrigerator at one end, starting
  // in a corner and turning the next corner when the wall is full.
  std::vector<Category> run;
  const int cabinets = rng.UniformInt(2, 5);
  for (int k = 0; k < cabinets; ++k) run.push_back(Category::kCabinet);
  run.insert(run.begin() + rng.UniformInt(0, cabinets), Category::kSink);
  if (rng.Bernoulli(0.9)) {
    if (rng.Bernoulli(0.5)) {
      run.insert(run.begin(), Category::kRefrigerator);
    } else {
      run.push_back(Category::kRefrigerator);
    }
  }
  const int n_edges = static_cast<int>(b.edges().size());
  int edge = rng.UniformInt(0, n_edges - 1);
  double s = 0.01;
  int turns = 0;
  Placement counter;
  for (std::size_t i = 0; i < run.size() && turns < 2 && !b.Full();) {
    const Accept accept = run[i] == Category::kCabinet ? Named("kitchenbase")
                          : run[i] == Category::kSink  ? Named("kitchen")
                                                       : NotNamed("mini");
    const auto model = b.DrawModel(run[i], accept);
    if (!model) {
      ++i;
      continue;
    }
    const double half = 0.5 * SizeOf(*model).y();
    Placement p;
    while (!p.Valid() && s + 2 * half <= b.edges()[edge].length) {
      p = b.PlaceAgainstWall(*model, edge, s + half, 0.02);
      if (!p.Valid()) s += 0.1;
    }
    if (p.Valid()) {
      s = p.s_center + half + 0.025;
      if (run[i] == Category::kCabinet) counter = p;
      ++i;
    } else {
      edge = (edge + 1) % n_edges;
      s = 0.7;  // clear of the run around the corner
      ++turns;
    }
  }
  OnTop(b, counter, Category::kRadio, Any(), 0.4);
  OnTop(b, counter, Category::kMonitor, Tv(), 0.1, true);
  if (rng.Bernoulli(0.4)) WallItem(b, Category::kCabinet, Named("pantry"), 0.5);
  TableGroup(b, [](const FurnitureModel& m) { return Has(m, "dining") && SizeOf(m).y() < 1.5; }, rng.UniformInt(2, 4));
  if (rng.Bernoulli(0.3)) {
    const Placement sh = WallItem(b, Category::kShelves, [](const FurnitureModel& m) { return SizeOf(m).z() < 1.6; });
    OnTop(b, sh, Category::kRadio, Any(), 0.3);
  }
  if (rng.Bernoulli(0.15)) WallItem(b, Category::kLamp, FloorLamp(), 0.8, 0.05);
}

void PlanBathroom(RoomBuilder& b) {
  Rng& rng = b.rng();
  Outline(b, 2.2, 3.0, 2.6, 3.6, 0.0);
  Structure(b, rng.Bernoulli(0.85) ? 1 : 0, 1.2, 1.4, 0.1);
  WallItem(b, Category::kBathtub, Any(), 0.9, 0.0);
  WallItem(b, Category::kToilet, Any(), 0.2, 0.03);
  const Accept basin = [](const FurnitureModel& m) { return !Has(m, "kitchen") && SizeOf(m).y() < 1.0; };
  const Placement sink = WallItem(b, Category::kSink, basin, 0.2, 0.02);
  if (sink.Valid() && rng.Bernoulli(0.2)) WallItem(b, Category::kSink, basin, 0.2, 0.02);
  const Placement cab = WallItem(b, Category::kCabinet, [](const FurnitureModel& m) {
    return (Has(m, "pantry") || Has(m, "kitchenbase") || Has(m, "filing")) && SizeOf(m).y() < 0.75;
  }, 0.5);
  OnTop(b, cab, Category::kRadio, Any(), 0.25);
  if (rng.Bernoulli(0.5)) {
    WallItem(b, Category::kShelves, [](const FurnitureModel& m) { return SizeOf(m).y() < 0.8 && SizeOf(m).x() < 0.35; },
             0.5);
  }
  if (rng.Bernoulli(0.15)) OnTop(b, sink, Category::kRadio, Any(), 1.0);
}

void PlanOffice(RoomBuilder& b) {
  Rng& rng = b.rng();
  Outline(b, 3.5, 5.5, 4.0, 6.5, 0.3);
  Structure(b, rng.UniformInt(1, 3), 0.7, 0.95, 0.3);
  const int desks = rng.UniformInt(1, 3);
  for (int k = 0; k < desks; ++k) DeskGroup(b, Any(), rng.UniformInt(1, 2), 0.4, 0.1);
  const int shelves = rng.UniformInt(1, 2);
  for (int k = 0; k < shelves; ++k) {
    const Placement sh = WallItem(b, Category::kShelves, Any());
    OnTop(b, sh, Category::kRadio, Any(), 0.15);
  }
  const int cabinets = rng.UniformInt(1, 3);
  for (int k = 0; k < cabinets; ++k) {
    const Placement cab = WallItem(b, Category::kCabinet, Named("filing"), 0.5);
    OnTop(b, cab, Category::kLamp, TableLamp(), 0.2);
  }
  if (b.width() * b.depth() > 20.0 && rng.Bernoulli(0.5)) TableGroup(b, Named("dining"), rng.UniformInt(2, 4));
  if (rng.Bernoulli(0.25)) WallItem(b, Category::kSofa, NotNamed("lshape"), 0.3, 0.05);
  if (rng.Bernoulli(0.3)) WallItem(b, Category::kLamp, FloorLamp(), 0.8, 0.05);
  if (rng.Bernoulli(0.15)) WallItem(b, Category::kRefrigerator, Named("mini"), 0.5);
}

// The furniture that makes a room recognisable as its category.
bool HasKeyFurniture(int room, const Scene& scene) {
  auto has = [&](Category c) {
    for (const auto& o : scene.objects()) {
      if (o.category == c) return true;
    }
    return false;
  };
  switch (room) {
    case 0: return has(Category::kBed);
    case 1: return has(Category::kSofa);
    case 2: return has(Category::kCabinet) || has(Category::kSink);
    case 3: return has(Category::kToilet);
    default: return has(Category::kDesk);
  }
}

}  // namespace

const std::vector<std::string>& RoomCategories() {
  static const std::vector<std::string> kNames = {"bedroom", "living_room", "kitchen", "bathroom", "office"};
  return kNames;
}

std::uint64_t SceneModelSeed(const std::string& room_category, std::uint64_t scene_seed, std::uint64_t k) {
  const auto room = static_cast<std::uint64_t>(RoomIndex(room_category));
  return DeriveSeed(DeriveSeed(scene_seed, kSceneModelStream + room), k) & ~kDatabaseSeedBit;
}

Scene GenerateRoom(const std::string& room_category, std::uint64_t scene_seed, const RoomOptions& options) {
  options.Validate();
  const int room = RoomIndex(room_category);
  const std::uint64_t layout_seed = DeriveSeed(scene_seed, kSceneLayoutStream + static_cast<std::uint64_t>(room));
  Scene best;
  int best_count = -1;
  for (int attempt = 0; attempt < options.max_attempts; ++attempt) {
    RoomBuilder b(room_category, scene_seed, DeriveSeed(layout_seed, static_cast<std::uint64_t>(attempt)),
                  static_cast<std::uint64_t>(attempt) * 100000u, options);
    switch (room) {
      case 0: PlanBedroom(b); break;
      case 1: PlanLivingRoom(b); break;
      case 2: PlanKitchen(b); break;
      case 3: PlanBathroom(b); break;
      default: PlanOffice(b); break;
    }
    // Keep the first complete attempt, else the fullest one.
    const bool complete = HasKeyFurniture(room, b.scene());
    const int count = b.NumFurniture() + (complete ? 1000 : 0);
    if (count > best_count) {
      best_count = count;
      best = b.TakeScene();
    }
    if (complete && b.NumFurniture() >= options.min_objects) break;
  }
  best.set_name("procedural:" + room_category + ":" + std::to_string(scene_seed));
  return best;
}

Scene GenerateRoom(const std::string& room_category, std::uint64_t scene_seed) {
  return GenerateRoom(room_category, scene_seed, RoomOptions{});
}

}  // namespace objscan::world::procedural
