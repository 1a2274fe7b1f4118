// Tables, desks, TV stands and night stands.
#include <cmath>

#include "objscan/world/procedural/furniture_generators.h"

namespace objscan::world::procedural::internal {

using Eigen::Vector3d;

namespace {

// An open-fronted box carcass (sides, top, bottom, back) spanning the given extents.
void Carcass(PartBuilder& p, double xb, double xf, double yl, double yr, double z0, double z1, double t) {
  p.Box(xb, yl, z0, xf, yl + t, z1);
  p.Box(xb, yr - t, z0, xf, yr, z1);
  p.Box(xb, yl, z1 - t, xf, yr, z1);
  p.Box(xb, yl, z0, xf, yr, z0 + t);
  p.Box(xb, yl, z0, xb + t, yr, z1);
}

void Door(PartBuilder& p, double x_front, double y0, double y1, double z0, double z1, bool handle_left) {
  p.Box(x_front - 0.004, y0 + 0.004, z0 + 0.004, x_front + 0.018, y1 - 0.004, z1 - 0.004);
  const double y = handle_left ? y0 + 0.05 : y1 - 0.05;
  BarHandle(p, x_front + 0.018, y, z1 - std::min(0.12, 0.3 * (z1 - z0)), std::min(0.12, 0.4 * (z1 - z0)), true);
}

}  // namespace

std::string BuildTable(Rng& rng, PartBuilder& p) {
  const bool coffee = rng.Bernoulli(0.3);
  const int shape = Pick(rng, 4);  // rectangular, round, oval, square
  int base = Pick(rng, 3);         // four legs, pedestal, trestle
  if (base == 2 && (shape == 1 || shape == 3)) base = 1;
  const double h = coffee ? rng.Uniform(0.38, 0.48) : rng.Uniform(0.72, 0.78);
  const double top_t = rng.Uniform(0.03, 0.06);
  double w = 0.0, d = 0.0;  // w along Y, d along X
  switch (shape) {
    case 0: w = coffee ? rng.Uniform(0.9, 1.3) : rng.Uniform(1.2, 1.9); d = coffee ? rng.Uniform(0.5, 0.7) : rng.Uniform(0.75, 1.0); break;
    case 1: w = d = coffee ? rng.Uniform(0.6, 0.9) : rng.Uniform(0.85, 1.2); break;
    case 2: w = coffee ? rng.Uniform(1.0, 1.3) : rng.Uniform(1.4, 1.9); d = coffee ? rng.Uniform(0.55, 0.7) : rng.Uniform(0.85, 1.05); break;
    default: w = d = coffee ? rng.Uniform(0.6, 0.85) : rng.Uniform(0.8, 1.0); break;
  }
  const bool curved = shape == 1 || shape == 2;
  if (curved) {
    p.EllipticCylinderZ(0, 0, h - top_t, h, 0.5 * d, 0.5 * w, 40);
  } else {
    p.Box(-0.5 * d, -0.5 * w, h - top_t, 0.5 * d, 0.5 * w, h);
  }
  const double leg_top = h - top_t + 0.005;
  if (base == 0) {
    const double t = rng.Uniform(0.04, 0.07);
    // Legs inside the top's outline (a circle's inscribed square for round tops).
    const double inset = curved ? 0.5 * (1.0 - std::sqrt(0.5)) + 0.03 : rng.Uniform(0.02, 0.08);
    const double x0 = -0.5 * d + inset * (curved ? d : 1.0), y0 = -0.5 * w + inset * (curved ? w : 1.0);
    const LegStyle style = static_cast<LegStyle>(Pick(rng, 3));
    FourLegs(p, x0, -x0, y0, -y0, leg_top, t, style);
    if (!curved && rng.Bernoulli(0.6)) {
      const double a = rng.Uniform(0.06, 0.12);
      p.Box(x0, y0, leg_top - a, -x0, y0 + 0.02, leg_top);
      p.Box(x0, -y0 - 0.02, leg_top - a, -x0, -y0, leg_top);
      p.Box(x0, y0, leg_top - a, x0 + 0.02, -y0, leg_top);
      p.Box(-x0 - 0.02, y0, leg_top - a, -x0, -y0, leg_top);
    }
  } else if (base == 1) {
    const int columns = (w > 1.3) ? 2 : 1;
    const bool disk_foot = rng.Bernoulli(0.5);
    const double r = rng.Uniform(0.04, 0.08);
    for (int k = 0; k < columns; ++k) {
      const double y = columns == 1 ? 0.0 : (k == 0 ? -0.25 : 0.25) * w;
      p.CylinderZ(0, y, 0.02, leg_top, r, 16);
      p.Box(-0.12, y - 0.12, leg_top - 0.04, 0.12, y + 0.12, leg_top);
      if (disk_foot) {
        p.FrustumZ(0, y, 0.0, 0.05, std::min(0.35, 0.38 * d), r + 0.02, 24);
      } else {
        const double foot = std::min(0.6, 0.7 * d);
        p.Box(-0.5 * foot, y - 0.03, 0.0, 0.5 * foot, y + 0.03, 0.05);
        p.Box(-0.03, y - 0.5 * foot, 0.0, 0.03, y + 0.5 * foot, 0.05);
      }
    }
  } else {
    const double panel_d = 0.6 * d;
    for (double s : {-1.0, 1.0}) {
      const double y = s * (0.5 * w - 0.18);
      p.Box(-0.04, y - 0.03, 0.04, 0.04, y + 0.03, leg_top);
      p.Box(-0.5 * panel_d, y - 0.04, 0.0, 0.5 * panel_d, y + 0.04, 0.06);
      p.Box(-0.5 * panel_d + 0.05, y - 0.04, leg_top - 0.05, 0.5 * panel_d - 0.05, y + 0.04, leg_top);
    }
    p.Box(-0.03, -0.5 * w + 0.18, 0.25 * h, 0.03, 0.5 * w - 0.18, 0.25 * h + 0.06);
  }
  static const char* kShape[] = {"rect", "round", "oval", "square"};
  static const char* kBase[] = {"legs", "pedestal", "trestle"};
  return std::string(coffee ? "coffee" : "dining") + "_" + kShape[shape] + "_" + kBase[base];
}

std::string BuildDesk(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // legs, panels, pedestal, twin pedestal, L-shaped, hutch
  const double h = rng.Uniform(0.72, 0.77), w = rng.Uniform(1.0, 1.6), d = rng.Uniform(0.55, 0.78);
  const double top_t = rng.Uniform(0.025, 0.045);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const double z_under = h - top_t;
  p.Box(xb, yl, z_under, xf, yr, h);
  const bool bar = rng.Bernoulli(0.5);
  auto pedestal = [&](double y0, double y1) {
    p.Box(xb + 0.02, y0, 0.0, xf - 0.03, y1, z_under + 0.005);
    const int drawers = rng.UniformInt(2, 4);
    for (int k = 0; k < drawers; ++k) {
      const double z0 = 0.05 + (z_under - 0.05) * k / drawers, z1 = 0.05 + (z_under - 0.05) * (k + 1) / drawers;
      DrawerFront(p, xf - 0.03, y0, y1, z0, z1, bar);
    }
  };
  const double t = 0.045;
  switch (style) {
    case 0:
      FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yr - 0.02, z_under + 0.005, t, static_cast<LegStyle>(Pick(rng, 3)));
      break;
    case 1:
      p.Box(xb, yl, 0.0, xf, yl + 0.03, z_under + 0.005);
      p.Box(xb, yr - 0.03, 0.0, xf, yr, z_under + 0.005);
      p.Box(xb + 0.02, yl, 0.3, xb + 0.04, yr, z_under + 0.005);
      break;
    case 2:
      pedestal(yr - 0.42, yr);
      FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yl + 0.3, z_under + 0.005, t, LegStyle::kSquare);
      break;
    case 3:
      pedestal(yl, yl + 0.4);
      pedestal(yr - 0.4, yr);
      p.Box(xb + 0.02, yl + 0.4, 0.35, xb + 0.04, yr - 0.4, z_under + 0.005);
      break;
    case 4: {
      // Return on the +Y side, reaching forward (+X).
      const double ret = rng.Uniform(0.6, 1.0), rw = rng.Uniform(0.45, 0.6);
      p.Box(xf - 0.01, yr - rw, z_under, xf + ret, yr, h);
      p.Box(xb, yl, 0.0, xf, yl + 0.03, z_under + 0.005);
      p.Box(xb + 0.02, yr - rw, 0.0, xf + ret - 0.02, yr, 0.04);
      p.Box(xf + ret - 0.45, yr - rw + 0.02, 0.0, xf + ret - 0.02, yr - 0.02, z_under + 0.005);
      for (int k = 0; k < 3; ++k) {
        const double z0 = 0.05 + (z_under - 0.05) * k / 3, z1 = 0.05 + (z_under - 0.05) * (k + 1) / 3;
        DrawerFront(p, xf + ret - 0.02, yr - rw + 0.02, yr - 0.02, z0, z1, bar);
      }
      p.Box(xb, yr - 0.03, 0.0, xf, yr, z_under + 0.005);
      break;
    }
    default: {
      FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yr - 0.02, z_under + 0.005, t, LegStyle::kSquare);
      const double hut = rng.Uniform(0.3, 0.5), hd = rng.Uniform(0.2, 0.28);
      p.Box(xb, yl, h - 0.005, xb + hd, yl + 0.02, h + hut);
      p.Box(xb, yr - 0.02, h - 0.005, xb + hd, yr, h + hut);
      p.Box(xb, yl, h + hut - 0.02, xb + hd, yr, h + hut);
      p.Box(xb, yl, h + 0.5 * hut - 0.01, xb + hd, yr, h + 0.5 * hut + 0.01);
      p.Box(xb, yl, h - 0.005, xb + 0.015, yr, h + hut);
      break;
    }
  }
  static const char* kStyle[] = {"legs", "panels", "pedestal", "twinpedestal", "lshape", "hutch"};
  return kStyle[style];
}

std::string BuildTvStand(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // open shelves, doors, drawers, on legs, centre niche, plinth with drawers
  const double h = rng.Uniform(0.38, 0.6), w = rng.Uniform(1.0, 1.9), d = rng.Uniform(0.35, 0.5);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w, t = 0.025;
  const bool bar = rng.Bernoulli(0.5);
  switch (style) {
    case 0: {
      Carcass(p, xb, xf, yl, yr, 0.0, h, t);
      const int shelves = rng.UniformInt(1, 2);
      for (int k = 1; k <= shelves; ++k) p.Box(xb, yl, h * k / (shelves + 1), xf - 0.01, yr, h * k / (shelves + 1) + t);
      const int dividers = rng.UniformInt(1, 3);
      for (int k = 1; k <= dividers; ++k) {
        const double y = yl + w * k / (dividers + 1);
        p.Box(xb, y - 0.5 * t, 0.0, xf - 0.01, y + 0.5 * t, h);
      }
      break;
    }
    case 1: {
      p.Box(xb, yl, 0.0, xf, yr, h);
      const int doors = rng.UniformInt(2, 4);
      for (int k = 0; k < doors; ++k) Door(p, xf, yl + w * k / doors, yl + w * (k + 1) / doors, 0.03, h - 0.01, k % 2 == 1);
      break;
    }
    case 2: {
      p.Box(xb, yl, 0.05, xf, yr, h);
      p.Box(xb + 0.03, yl + 0.03, 0.0, xf - 0.04, yr - 0.03, 0.055);
      const int cols = rng.UniformInt(2, 4), rows = rng.UniformInt(1, 2);
      for (int c = 0; c < cols; ++c) {
        for (int r = 0; r < rows; ++r) {
          DrawerFront(p, xf, yl + w * c / cols, yl + w * (c + 1) / cols, 0.05 + (h - 0.05) * r / rows,
                      0.05 + (h - 0.05) * (r + 1) / rows, bar);
        }
      }
      break;
    }
    case 3: {
      const double leg_h = rng.Uniform(0.12, 0.22);
      p.Box(xb, yl, leg_h, xf, yr, h);
      FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.03, yr - 0.03, leg_h + 0.005, 0.04, LegStyle::kTapered);
      Door(p, xf, yl, 0.0, leg_h + 0.01, h - 0.01, false);
      Door(p, xf, 0.0, yr, leg_h + 0.01, h - 0.01, true);
      break;
    }
    case 4: {
      const double niche = rng.Uniform(0.35, 0.5) * w;
      p.Box(xb, yl, 0.0, xf, -0.5 * niche, h);
      p.Box(xb, 0.5 * niche, 0.0, xf, yr, h);
      Carcass(p, xb, xf, -0.5 * niche - 0.01, 0.5 * niche + 0.01, 0.0, h, t);
      p.Box(xb, -0.5 * niche, 0.5 * h, xf - 0.02, 0.5 * niche, 0.5 * h + t);
      Door(p, xf, yl, -0.5 * niche, 0.02, h - 0.01, false);
      Door(p, xf, 0.5 * niche, yr, 0.02, h - 0.01, true);
      break;
    }
    default: {
      p.Box(xb + 0.05, yl + 0.05, 0.0, xf - 0.06, yr - 0.05, 0.1);
      p.Box(xb, yl, 0.095, xf, yr, h);
      const int cols = rng.UniformInt(2, 3);
      for (int c = 0; c < cols; ++c) DrawerFront(p, xf, yl + w * c / cols, yl + w * (c + 1) / cols, 0.1, h, bar);
      break;
    }
  }
  static const char* kStyle[] = {"open", "doors", "drawers", "legs", "niche", "plinth"};
  return kStyle[style];
}

std::string BuildNightStand(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // drawers on plinth, drawers on legs, drawer + niche, round, door, open shelves
  const double h = rng.Uniform(0.45, 0.65), w = rng.Uniform(0.38, 0.55), d = rng.Uniform(0.33, 0.45);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const bool bar = rng.Bernoulli(0.4);
  int drawers = 0;
  switch (style) {
    case 0: {
      drawers = rng.UniformInt(2, 3);
      p.Box(xb, yl, 0.0, xf, yr, h);
      for (int k = 0; k < drawers; ++k) DrawerFront(p, xf, yl, yr, 0.04 + (h - 0.04) * k / drawers, 0.04 + (h - 0.04) * (k + 1) / drawers, bar);
      break;
    }
    case 1: {
      const double leg_h = rng.Uniform(0.18, 0.28);
      drawers = rng.UniformInt(1, 2);
      p.Box(xb, yl, leg_h, xf, yr, h);
      FourLegs(p, xb + 0.01, xf - 0.01, yl + 0.01, yr - 0.01, leg_h + 0.005, 0.035, LegStyle::kTapered);
      for (int k = 0; k < drawers; ++k) DrawerFront(p, xf, yl, yr, leg_h + (h - leg_h) * k / drawers, leg_h + (h - leg_h) * (k + 1) / drawers, bar);
      break;
    }
    case 2: {
      drawers = 1;
      const double t = 0.02, z_d = h - rng.Uniform(0.12, 0.18);
      p.Box(xb, yl, 0.0, xf, yl + t, h);
      p.Box(xb, yr - t, 0.0, xf, yr, h);
      p.Box(xb, yl, 0.0, xb + t, yr, h);
      p.Box(xb, yl, 0.0, xf, yr, 0.06);
      p.Box(xb, yl, 0.5 * (0.06 + z_d) - 0.01, xf - 0.01, yr, 0.5 * (0.06 + z_d) + 0.01);
      p.Box(xb, yl, z_d, xf, yr, h);
      DrawerFront(p, xf, yl, yr, z_d, h, bar);
      break;
    }
    case 3: {
      const double r = 0.5 * std::min(w, d) + 0.03;
      p.CylinderZ(0, 0, h - 0.03, h, r, 32);
      p.CylinderZ(0, 0, 0.02, h - 0.025, rng.Uniform(0.03, 0.05), 16);
      p.CylinderZ(0, 0, 0.0, 0.025, 0.7 * r, 24);
      p.CylinderZ(0, 0, 0.45 * h, 0.45 * h + 0.02, 0.8 * r, 24);
      break;
    }
    case 4: {
      p.Box(xb, yl, 0.0, xf, yr, h);
      Door(p, xf, yl, yr, 0.05, h - 0.01, rng.Bernoulli(0.5));
      break;
    }
    default: {
      const double t = 0.02;
      Carcass(p, xb, xf, yl, yr, 0.0, h, t);
      p.Box(xb, yl, 0.5 * h - 0.5 * t, xf - 0.01, yr, 0.5 * h + 0.5 * t);
      break;
    }
  }
  static const char* kStyle[] = {"drawers", "legs", "niche", "round", "door", "open"};
  return std::string(kStyle[style]) + (drawers > 0 ? std::to_string(drawers) : "");
}

}  // namespace objscan::world::procedural::internal
