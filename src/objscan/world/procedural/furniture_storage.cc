// Cabinets, dressers, shelves and refrigerators.
#include <algorithm>
#include <cmath>

#include "objscan/world/procedural/furniture_generators.h"

namespace objscan::world::procedural::internal {

using Eigen::Vector3d;

namespace {

void FrontDoor(PartBuilder& p, double x_front, double y0, double y1, double z0, double z1, bool handle_left,
               double handle_z) {
  p.Box(x_front - 0.004, y0 + 0.004, z0 + 0.004, x_front + 0.02, y1 - 0.004, z1 - 0.004);
  const double y = handle_left ? y0 + 0.045 : y1 - 0.045;
  BarHandle(p, x_front + 0.02, y, std::clamp(handle_z, z0 + 0.08, z1 - 0.08), std::min(0.16, 0.4 * (z1 - z0)), true);
}

}  // namespace

std::string BuildCabinet(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // kitchen base, tall pantry, wardrobe, sideboard on legs, glass display, filing
  double w = 0.0, h = 0.0, d = 0.0;
  switch (style) {
    case 0: w = rng.Uniform(0.5, 1.0); h = rng.Uniform(0.86, 0.92); d = rng.Uniform(0.55, 0.62); break;
    case 1: w = rng.Uniform(0.5, 0.8); h = rng.Uniform(1.8, 2.1); d = rng.Uniform(0.45, 0.6); break;
    case 2: w = rng.Uniform(1.0, 1.6); h = rng.Uniform(1.9, 2.15); d = rng.Uniform(0.55, 0.62); break;
    case 3: w = rng.Uniform(1.0, 1.6); h = rng.Uniform(0.75, 0.9); d = rng.Uniform(0.4, 0.5); break;
    case 4: w = rng.Uniform(0.7, 1.1); h = rng.Uniform(1.6, 1.95); d = rng.Uniform(0.38, 0.48); break;
    default: w = rng.Uniform(0.4, 0.5); h = rng.Uniform(0.7, 1.35); d = rng.Uniform(0.5, 0.62); break;
  }
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  switch (style) {
    case 0: {
      const double top_t = 0.035, plinth = 0.1;
      p.Box(xb, yl + 0.01, 0.0, xf - 0.06, yr - 0.01, plinth + 0.01);
      p.Box(xb, yl, plinth, xf - 0.03, yr, h - top_t + 0.002);
      p.Box(xb, yl, h - top_t, xf + 0.01, yr, h);
      const int doors = w > 0.7 ? 2 : 1;
      const double drawer_z = h - top_t - 0.15;
      for (int k = 0; k < doors; ++k) {
        const double y0 = yl + w * k / doors, y1 = yl + w * (k + 1) / doors;
        FrontDoor(p, xf - 0.03, y0, y1, plinth, drawer_z, k == 1 || doors == 1, drawer_z - 0.1);
        DrawerFront(p, xf - 0.03, y0, y1, drawer_z, h - top_t, true);
      }
      break;
    }
    case 1:
    case 2: {
      const double plinth = 0.08;
      p.Box(xb, yl + 0.02, 0.0, xf - 0.04, yr - 0.02, plinth + 0.01);
      p.Box(xb, yl, plinth, xf - 0.02, yr, h - 0.04);
      p.Box(xb - 0.01, yl - 0.02, h - 0.045, xf + 0.01, yr + 0.02, h);
      const int doors = style == 1 ? 2 : rng.UniformInt(2, 3);
      if (style == 1) {
        const double split = plinth + rng.Uniform(0.55, 0.7) * (h - plinth);
        FrontDoor(p, xf - 0.02, yl, yr, plinth, split, false, split - 0.2);
        FrontDoor(p, xf - 0.02, yl, yr, split, h - 0.045, false, split + 0.15);
      } else {
        for (int k = 0; k < doors; ++k) {
          FrontDoor(p, xf - 0.02, yl + w * k / doors, yl + w * (k + 1) / doors, plinth, h - 0.045, k % 2 == 1,
                    0.5 * h + 0.1);
        }
      }
      break;
    }
    case 3: {
      const double leg_h = rng.Uniform(0.15, 0.25);
      p.Box(xb, yl, leg_h, xf, yr, h);
      FourLegs(p, xb + 0.03, xf - 0.03, yl + 0.03, yr - 0.03, leg_h + 0.005, 0.04,
               rng.Bernoulli(0.5) ? LegStyle::kTapered : LegStyle::kRound);
      const int doors = rng.UniformInt(2, 3);
      for (int k = 0; k < doors; ++k) {
        FrontDoor(p, xf, yl + w * k / doors, yl + w * (k + 1) / doors, leg_h, h - 0.005, k % 2 == 1, 0.5 * (leg_h + h));
      }
      break;
    }
    case 4: {
      // Display cabinet: frame, recessed glass, visible shelves.
      const double t = 0.03;
      p.Box(xb, yl, 0.0, xf, yr, 0.12);
      p.Box(xb, yl, h - 0.06, xf, yr, h);
      p.Box(xb, yl, 0.0, xf, yl + t, h);
      p.Box(xb, yr - t, 0.0, xf, yr, h);
      p.Box(xb, yl, 0.0, xb + 0.015, yr, h);
      const int shelves = rng.UniformInt(2, 4);
      for (int k = 1; k <= shelves; ++k) {
        const double z = 0.12 + (h - 0.18) * k / (shelves + 1);
        p.Box(xb, yl, z - 0.01, xf - 0.05, yr, z + 0.01);
      }
      p.Box(xf - 0.035, yl + t, 0.12, xf - 0.03, yr - t, h - 0.06);  // glass, set back from the frame
      p.Box(xf - 0.04, -0.01, 0.12, xf, 0.01, h - 0.06);
      break;
    }
    default: {
      p.Box(xb, yl, 0.0, xf, yr, h);
      const int drawers = std::max(2, static_cast<int>(std::round(h / 0.33)));
      for (int k = 0; k < drawers; ++k) DrawerFront(p, xf, yl, yr, 0.02 + (h - 0.02) * k / drawers, 0.02 + (h - 0.02) * (k + 1) / drawers, true);
      break;
    }
  }
  static const char* kStyle[] = {"kitchenbase", "pantry", "wardrobe", "sideboard", "display", "filing"};
  return kStyle[style];
}

std::string BuildDresser(Rng& rng, PartBuilder& p) {
  const double w = rng.Uniform(0.8, 1.6), h = rng.Uniform(0.75, 1.3), d = rng.Uniform(0.42, 0.55);
  const int cols = w < 1.0 ? rng.UniformInt(1, 2) : rng.UniformInt(2, 3);
  const int rows = rng.UniformInt(3, 5);
  const int base = Pick(rng, 3);  // plinth, legs, bun feet
  const bool mirror = rng.Bernoulli(0.3) && h < 1.0;
  const bool bar = rng.Bernoulli(0.5);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const double foot_h = base == 0 ? 0.08 : (base == 1 ? rng.Uniform(0.12, 0.22) : 0.07);
  if (base == 0) {
    p.Box(xb, yl + 0.02, 0.0, xf - 0.03, yr - 0.02, foot_h + 0.01);
  } else if (base == 1) {
    FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yr - 0.02, foot_h + 0.005, 0.045, LegStyle::kTapered);
  } else {
    for (double x : {xb + 0.06, xf - 0.06}) {
      for (double y : {yl + 0.06, yr - 0.06}) p.Sphere(Vector3d(x, y, 0.04), 0.04, 12);
    }
  }
  p.Box(xb, yl, foot_h, xf, yr, h - 0.03);
  p.Box(xb, yl - 0.015, h - 0.03, xf + 0.02, yr + 0.015, h);
  for (int r = 0; r < rows; ++r) {
    // The top row may be split into more, smaller drawers.
    const int c_here = (r == rows - 1 && cols == 1 && rng.Bernoulli(0.5)) ? 2 : cols;
    for (int c = 0; c < c_here; ++c) {
      DrawerFront(p, xf, yl + w * c / c_here, yl + w * (c + 1) / c_here, foot_h + (h - 0.03 - foot_h) * r / rows,
                  foot_h + (h - 0.03 - foot_h) * (r + 1) / rows, bar);
    }
  }
  if (mirror) {
    const double mh = rng.Uniform(0.6, 0.9), mw = std::min(w - 0.1, rng.Uniform(0.6, 1.0));
    p.Box(xb + 0.02, -0.5 * mw, h - 0.005, xb + 0.06, 0.5 * mw, h + mh);
    p.Box(xb + 0.06, -0.5 * mw + 0.04, h + 0.04, xb + 0.065, 0.5 * mw - 0.04, h + mh - 0.04);
  }
  static const char* kBase[] = {"plinth", "legs", "feet"};
  return std::to_string(rows) + "x" + std::to_string(cols) + "_" + kBase[base] + (mirror ? "_mirror" : "");
}

std::string BuildShelves(Rng& rng, PartBuilder& p) {
  const double h = rng.Uniform(0.8, 2.0), w = rng.Uniform(0.6, 1.2), d = rng.Uniform(0.25, 0.4);
  const bool closed = rng.Bernoulli(0.55);
  const bool back = rng.Bernoulli(0.5);
  const bool grid = closed && rng.Bernoulli(0.3);
  const int levels = std::clamp(static_cast<int>(std::round(h / rng.Uniform(0.3, 0.4))), 2, 6);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const double t = closed ? 0.02 : 0.025;
  if (closed) {
    p.Box(xb, yl, 0.0, xf, yl + t, h);
    p.Box(xb, yr - t, 0.0, xf, yr, h);
    p.Box(xb, yl, 0.0, xf, yr, 0.06);
  } else {
    // Open frame: four corner posts, shelves resting on them, cross-braces at the back.
    for (double x : {xb, xf - t}) {
      for (double y : {yl, yr - t}) p.Box(x, y, 0.0, x + t, y + t, h);
    }
    p.Rod(Vector3d(xb + 0.5 * t, yl + t, 0.1), Vector3d(xb + 0.5 * t, yr - t, h - 0.1), 0.006, 6);
    p.Rod(Vector3d(xb + 0.5 * t, yl + t, h - 0.1), Vector3d(xb + 0.5 * t, yr - t, 0.1), 0.006, 6);
  }
  if (back) p.Box(xb, yl, 0.0, xb + 0.012, yr, h);
  // Shelf boards: bottom board (open frames only), `levels - 1` intermediate ones, the top.
  for (int k = closed ? 1 : 0; k <= levels; ++k) {
    const double z = k == 0 ? 0.08 : (k == levels ? h - 0.02 : 0.06 + (h - 0.08) * k / levels);
    p.Box(xb, yl, z - 0.01, xf - (closed ? 0.01 : 0.0), yr, std::min(h, z + 0.02));
  }
  if (grid) {
    const int cols = std::max(2, static_cast<int>(std::round(w / 0.35)));
    for (int c = 1; c < cols; ++c) {
      const double y = yl + w * c / cols;
      p.Box(xb, y - 0.01, 0.05, xf - 0.01, y + 0.01, h - 0.01);
    }
  }
  return std::to_string(levels) + "level_" + (closed ? "closed" : "open") + (back ? "_back" : "_noback") +
         (grid ? "_grid" : "");
}

std::string BuildRefrigerator(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // single door, top freezer, bottom freezer, side by side, french door, mini
  double w = rng.Uniform(0.55, 0.72), h = rng.Uniform(1.5, 1.95);
  const double d = rng.Uniform(0.6, 0.75);
  if (style == 3 || style == 4) w = rng.Uniform(0.8, 0.92), h = rng.Uniform(1.72, 1.9);
  if (style == 5) w = rng.Uniform(0.45, 0.55), h = rng.Uniform(0.8, 0.9);
  const double xb = -0.5 * d, xf = 0.5 * d - 0.05, yl = -0.5 * w, yr = 0.5 * w;
  const double base = 0.04;
  p.Box(xb + 0.02, yl + 0.03, 0.0, xf - 0.03, yr - 0.03, base + 0.01);
  p.Box(xb, yl, base, xf, yr, h);
  auto door = [&](double y0, double y1, double z0, double z1, int handle /*0 left 1 right 2 top*/) {
    p.Box(xf - 0.003, y0 + 0.004, z0 + 0.004, xf + 0.045, y1 - 0.004, z1 - 0.004);
    if (handle == 2) {
      BarHandle(p, xf + 0.045, 0.5 * (y0 + y1), z1 - 0.06, std::min(0.5, 0.6 * (y1 - y0)), false);
    } else {
      const double len = std::min(0.7, 0.6 * (z1 - z0));
      const double zc = z1 - z0 > 0.8 ? z0 + 0.45 * (z1 - z0) + 0.25 : 0.5 * (z0 + z1);
      BarHandle(p, xf + 0.045, handle == 0 ? y0 + 0.05 : y1 - 0.05, std::min(zc, z1 - 0.5 * len - 0.02), len, true);
    }
  };
  switch (style) {
    case 0: door(yl, yr, base, h, 1); break;
    case 1: {
      const double split = h - rng.Uniform(0.38, 0.5);
      door(yl, yr, base, split, 1);
      door(yl, yr, split, h, 1);
      break;
    }
    case 2: {
      const double split = base + rng.Uniform(0.55, 0.7);
      door(yl, yr, base, split, 2);
      door(yl, yr, split, h, 1);
      break;
    }
    case 3: {
      const double ys = -0.06 * w;
      door(yl, ys, base, h, 1);
      door(ys, yr, base, h, 0);
      p.Box(xf + 0.04, yl + 0.1, 1.0, xf + 0.05, ys - 0.08, 1.3);  // dispenser niche frame
      break;
    }
    case 4: {
      const double split = base + rng.Uniform(0.6, 0.75);
      door(yl, 0.0, split, h, 1);
      door(0.0, yr, split, h, 0);
      door(yl, yr, base, split, 2);
      break;
    }
    default: door(yl, yr, base, h, 1); break;
  }
  static const char* kStyle[] = {"single", "topfreezer", "bottomfreezer", "sidebyside", "french", "mini"};
  return kStyle[style];
}

}  // namespace objscan::world::procedural::internal
