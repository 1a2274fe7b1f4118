#include "objscan/world/procedural/furniture_generators.h"

#include <algorithm>

namespace objscan::world::procedural::internal {

bool BuildFurniture(Category category, Rng& rng, PartBuilder& parts, std::string* variant) {
  switch (category) {
    case Category::kBathtub: *variant = BuildBathtub(rng, parts); return true;
    case Category::kBed: *variant = BuildBed(rng, parts); return true;
    case Category::kCabinet: *variant = BuildCabinet(rng, parts); return true;
    case Category::kChair: *variant = BuildChair(rng, parts); return true;
    case Category::kCurtain: *variant = BuildCurtain(rng, parts); return true;
    case Category::kDesk: *variant = BuildDesk(rng, parts); return true;
    case Category::kDoor: *variant = BuildDoor(rng, parts); return true;
    case Category::kDresser: *variant = BuildDresser(rng, parts); return true;
    case Category::kLamp: *variant = BuildLamp(rng, parts); return true;
    case Category::kMonitor: *variant = BuildMonitor(rng, parts); return true;
    case Category::kNightStand: *variant = BuildNightStand(rng, parts); return true;
    case Category::kRadio: *variant = BuildRadio(rng, parts); return true;
    case Category::kRefrigerator: *variant = BuildRefrigerator(rng, parts); return true;
    case Category::kShelves: *variant = BuildShelves(rng, parts); return true;
    case Category::kSink: *variant = BuildSink(rng, parts); return true;
    case Category::kSofa: *variant = BuildSofa(rng, parts); return true;
    case Category::kTable: *variant = BuildTable(rng, parts); return true;
    case Category::kToilet: *variant = BuildToilet(rng, parts); return true;
    case Category::kTvStand: *variant = BuildTvStand(rng, parts); return true;
    case Category::kWindow: *variant = BuildWindow(rng, parts); return true;
    default: return false;
  }
}

void FourLegs(PartBuilder& p, double x0, double x1, double y0, double y1, double z_top_m, double t,
              LegStyle style) {
  const double xs[2] = {x0 + 0.5 * t, x1 - 0.5 * t};
  const double ys[2] = {y0 + 0.5 * t, y1 - 0.5 * t};
  for (double x : xs) {
    for (double y : ys) {
      switch (style) {
        case LegStyle::kSquare: p.Box(x - 0.5 * t, y - 0.5 * t, 0.0, x + 0.5 * t, y + 0.5 * t, z_top_m); break;
        case LegStyle::kRound: p.CylinderZ(x, y, 0.0, z_top_m, 0.5 * t, 12); break;
        case LegStyle::kTapered: p.FrustumZ(x, y, 0.0, z_top_m, 0.3 * t, 0.5 * t, 12); break;
      }
    }
  }
}

void Knob(PartBuilder& p, double x_front_m, double y_m, double z_m) {
  p.Box(x_front_m - 0.003, y_m - 0.012, z_m - 0.012, x_front_m + 0.025, y_m + 0.012, z_m + 0.012);
}

void BarHandle(PartBuilder& p, double x_front_m, double y_m, double z_m, double length_m, bool vertical) {
  const double h = 0.5 * length_m;
  const double x1 = x_front_m + 0.035;
  if (vertical) {
    p.Box(x_front_m - 0.003, y_m - 0.008, z_m - h + 0.01, x1, y_m + 0.008, z_m - h + 0.03);
    p.Box(x_front_m - 0.003, y_m - 0.008, z_m + h - 0.03, x1, y_m + 0.008, z_m + h - 0.01);
    p.Box(x1 - 0.012, y_m - 0.01, z_m - h, x1, y_m + 0.01, z_m + h);
  } else {
    p.Box(x_front_m - 0.003, y_m - h + 0.01, z_m - 0.008, x1, y_m - h + 0.03, z_m + 0.008);
    p.Box(x_front_m - 0.003, y_m + h - 0.03, z_m - 0.008, x1, y_m + h - 0.01, z_m + 0.008);
    p.Box(x1 - 0.012, y_m - h, z_m - 0.01, x1, y_m + h, z_m + 0.01);
  }
}

void DrawerFront(PartBuilder& p, double x_front_m, double y0, double y1, double z0, double z1, bool bar) {
  const double gap = 0.006;
  p.Box(x_front_m - 0.004, y0 + gap, z0 + gap, x_front_m + 0.018, y1 - gap, z1 - gap);
  const double zc = 0.5 * (z0 + z1), yc = 0.5 * (y0 + y1);
  if (bar) {
    BarHandle(p, x_front_m + 0.018, yc, zc, std::min(0.6 * (y1 - y0), 0.22), false);
  } else {
    Knob(p, x_front_m + 0.018, yc, zc);
  }
}

}  // namespace objscan::world::procedural::internal
