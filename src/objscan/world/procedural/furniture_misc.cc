// Lamps, monitors, radios, doors, windows and curtains.
#include <algorithm>
#include <cmath>

#include "objscan/world/procedural/furniture_generators.h"

namespace objscan::world::procedural::internal {

using Eigen::Vector3d;

namespace {

// A lamp shade with its bottom at z0: 0 cone, 1 drum, 2 globe, 3 square.
void Shade(PartBuilder& p, int shade, double x, double y, double z0, double r, double h) {
  switch (shade) {
    case 0: p.FrustumZ(x, y, z0, z0 + h, r, 0.55 * r, 24); break;
    case 1: p.CylinderZ(x, y, z0, z0 + h, r, 24); break;
    case 2: p.Sphere(Vector3d(x, y, z0 + 0.8 * r), 0.8 * r, 18); break;
    default: p.Box(x - 0.8 * r, y - 0.8 * r, z0, x + 0.8 * r, y + 0.8 * r, z0 + h); break;
  }
}

void LampBase(PartBuilder& p, int base, double r, double top_z, double pole_r) {
  switch (base) {
    case 0: p.FrustumZ(0, 0, 0, top_z, r, 0.7 * r, 24); break;
    case 1: p.Box(-r, -r, 0, r, r, top_z); break;
    default:
      for (int k = 0; k < 3; ++k) {
        const double a = 2.0 * M_PI * k / 3.0;
        p.Rod(Vector3d(r * std::cos(a), r * std::sin(a), 0.008), Vector3d(0, 0, top_z + 0.1), 0.008, 6);
        p.Sphere(Vector3d(r * std::cos(a), r * std::sin(a), 0.008), 0.008, 6);
      }
      p.CylinderZ(0, 0, top_z + 0.05, top_z + 0.12, pole_r + 0.008, 10);
      break;
  }
}

}  // namespace

std::string BuildLamp(Rng& rng, PartBuilder& p) {
  const int kind = Pick(rng, 4);   // floor, arc floor, table, desk (articulated)
  const int base = Pick(rng, 3);   // round, square, tripod
  const int shade = Pick(rng, 4);  // cone, drum, globe, square
  static const char* kKind[] = {"floor", "arc", "table", "desk"};
  static const char* kBase[] = {"round", "square", "tripod"};
  static const char* kShade[] = {"cone", "drum", "globe", "square"};
  std::string name = kKind[kind];
  if (kind == 0) {
    const double h = rng.Uniform(1.4, 1.8), r = rng.Uniform(0.12, 0.18), sr = rng.Uniform(0.15, 0.24);
    const double sh = rng.Uniform(0.22, 0.35);
    LampBase(p, base, base == 2 ? 0.25 : r, 0.03, 0.012);
    p.CylinderZ(0, 0, 0.02, h - sh + 0.05, 0.012, 10);
    Shade(p, shade, 0, 0, h - sh, sr, sh);
    name += std::string("_") + kBase[base] + "_" + kShade[shade];
  } else if (kind == 1) {
    const double h = rng.Uniform(1.7, 2.0), reach = rng.Uniform(0.8, 1.2), sr = rng.Uniform(0.15, 0.22);
    p.Box(-0.2, -0.2, 0.0, 0.2, 0.2, 0.06);
    const int n = 6;
    Vector3d prev(0, 0, 0.05);
    for (int k = 1; k <= n; ++k) {
      const double a = 0.5 * M_PI * k / n;
      const Vector3d q(reach * (1.0 - std::cos(a)), 0.0, 0.05 + (h - 0.05) * std::sin(a));
      p.Rod(prev, q, 0.014, 8);
      p.Sphere(q, 0.014, 6);
      prev = q;
    }
    p.Rod(prev, prev - Vector3d(0, 0, 0.12), 0.01, 6);
    p.FrustumZ(prev.x(), 0, prev.z() - 0.12 - 0.2, prev.z() - 0.1, sr, 0.04, 24);
    name += std::string("_") + (shade == 2 ? "globe" : "dome");
    if (shade == 2) p.Sphere(Vector3d(prev.x(), 0, prev.z() - 0.35), 0.09, 12);
  } else if (kind == 2) {
    const double h = rng.Uniform(0.35, 0.65), sr = rng.Uniform(0.1, 0.2), sh = rng.Uniform(0.15, 0.25);
    const bool vase = rng.Bernoulli(0.5);
    if (vase) {
      const double vr = rng.Uniform(0.07, 0.11);
      p.Ellipsoid(Vector3d(0, 0, 0.4 * (h - sh)), Vector3d(vr, vr, 0.4 * (h - sh)), 16);
      p.CylinderZ(0, 0, 0.7 * (h - sh), h - sh + 0.03, 0.012, 8);
    } else {
      LampBase(p, base, rng.Uniform(0.06, 0.1), 0.025, 0.01);
      p.CylinderZ(0, 0, 0.02, h - sh + 0.03, rng.Uniform(0.01, 0.03), 10);
    }
    Shade(p, shade, 0, 0, h - sh, sr, sh);
    name += std::string("_") + (vase ? "vase" : kBase[base]) + "_" + kShade[shade];
  } else {
    const double r = rng.Uniform(0.07, 0.1), a1 = rng.Uniform(0.3, 0.4), a2 = rng.Uniform(0.3, 0.4);
    const bool square = base == 1;
    if (square) {
      p.Box(-r, -r, 0, r, r, 0.03);
    } else {
      p.CylinderZ(0, 0, 0, 0.03, r, 20);
    }
    const Vector3d j0(-0.03, 0, 0.03), j1 = j0 + Vector3d(-0.35 * a1, 0, 0.94 * a1);
    const Vector3d j2 = j1 + Vector3d(0.9 * a2, 0, 0.1 * a2);
    p.Rod(j0, j1, 0.01, 8);
    p.Sphere(j1, 0.018, 8);
    p.Rod(j1, j2, 0.01, 8);
    p.FrustumZ(j2.x(), 0, j2.z() - 0.14, j2.z() + 0.01, shade == 1 ? 0.06 : 0.08, 0.03, 18);
    name += std::string("_") + (square ? "square" : "round") + (shade == 1 ? "_narrow" : "_wide");
  }
  return name;
}

std::string BuildMonitor(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // neck+disc, neck+plate, CRT, TV on feet, TV on pedestal, arm stand
  const bool tv = style == 3 || style == 4;
  const double sw = tv ? rng.Uniform(0.8, 1.3) : rng.Uniform(0.45, 0.7);
  const double sh = style == 2 ? 0.8 * sw : sw * rng.Uniform(0.56, 0.63);
  const double pt = rng.Uniform(0.02, 0.04);
  const double lift = tv ? rng.Uniform(0.06, 0.12) : rng.Uniform(0.08, 0.18);
  const double z0 = lift, z1 = lift + sh;
  // Panel (screen facing +X) and a back housing.
  if (style == 2) {
    const double depth = 0.85 * sw;
    p.Box(-0.02, -0.5 * sw, z0, 0.02, 0.5 * sw, z1);
    p.Box(-0.5 * depth, -0.4 * sw, z0 + 0.05 * sh, 0.0, 0.4 * sw, z1 - 0.08 * sh);
    p.Box(-depth, -0.25 * sw, z0 + 0.15 * sh, -0.5 * depth + 0.01, 0.25 * sw, z1 - 0.25 * sh);
    p.CylinderZ(-0.3 * depth, 0, 0.0, z0 + 0.06 * sh, 0.12, 20);
    return "crt";
  }
  p.Box(-0.5 * pt, -0.5 * sw, z0, 0.5 * pt, 0.5 * sw, z1);
  p.Box(-0.5 * pt - 0.03, -0.3 * sw, z0 + 0.2 * sh, -0.5 * pt + 0.005, 0.3 * sw, z1 - 0.2 * sh);
  const double neck_x = -0.5 * pt - 0.04;
  switch (style) {
    case 0:
      p.Box(neck_x - 0.015, -0.025, 0.01, neck_x + 0.015, 0.025, z0 + 0.45 * sh);
      p.EllipticCylinderZ(neck_x + 0.03, 0, 0.0, 0.015, 0.1, 0.12, 24);
      break;
    case 1:
      p.BoxPitch(Vector3d(neck_x, 0, 0.5 * (z0 + 0.45 * sh) + 0.01), Vector3d(0.03, 0.06, z0 + 0.45 * sh - 0.01), 0.1);
      p.Box(neck_x - 0.1, -0.13, 0.0, neck_x + 0.12, 0.13, 0.015);
      break;
    case 3: {
      const double foot = rng.Uniform(0.2, 0.3);
      for (double s : {-1.0, 1.0}) {
        const double y = s * (0.5 * sw - 0.12);
        p.Rod(Vector3d(-0.05, y, 0.005), Vector3d(0.0, y, z0 + 0.05), 0.012, 8);
        p.Box(-0.5 * foot, y - 0.02, 0.0, 0.5 * foot, y + 0.02, 0.015);
      }
      break;
    }
    case 4:
      p.Box(neck_x - 0.03, -0.05, 0.01, neck_x + 0.01, 0.05, z0 + 0.35 * sh);
      p.Box(-0.16, -0.3 * sw, 0.0, 0.12, 0.3 * sw, 0.02);
      break;
    default: {
      const double back = neck_x - 0.16;
      p.Box(back - 0.06, -0.11, 0.0, back + 0.18, 0.11, 0.02);
      p.Box(back - 0.015, -0.02, 0.01, back + 0.015, 0.02, z0 + 0.5 * sh + 0.02);
      p.Box(back - 0.015, -0.02, z0 + 0.5 * sh - 0.02, neck_x + 0.02, 0.02, z0 + 0.5 * sh + 0.02);
      break;
    }
  }
  static const char* kStyle[] = {"disc", "plate", "crt", "tv_feet", "tv_pedestal", "arm"};
  return kStyle[style];
}

std::string BuildRadio(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // boombox, retro, clock radio, portable with antenna, hifi, cube
  double w = rng.Uniform(0.2, 0.45), h = rng.Uniform(0.12, 0.26), d = rng.Uniform(0.08, 0.16);
  if (style == 2) w = rng.Uniform(0.15, 0.25), h = rng.Uniform(0.07, 0.1), d = rng.Uniform(0.1, 0.14);
  if (style == 5) w = h = d = rng.Uniform(0.12, 0.18);
  if (style == 4) w = rng.Uniform(0.35, 0.45), h = rng.Uniform(0.08, 0.12), d = rng.Uniform(0.25, 0.35);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  auto speaker = [&](double y, double z, double r) {
    p.Rod(Vector3d(xf - 0.005, y, z), Vector3d(xf + 0.012, y, z), r, 18);
  };
  auto knob = [&](double y, double z) { p.Rod(Vector3d(xf - 0.005, y, z), Vector3d(xf + 0.02, y, z), 0.012, 10); };
  p.Box(xb, yl, 0.0, xf, yr, h);
  switch (style) {
    case 0: {
      const double r = std::min(0.2 * w, 0.38 * h);
      speaker(yl + 0.25 * w, 0.45 * h, r);
      speaker(yr - 0.25 * w, 0.45 * h, r);
      p.Box(xf - 0.005, -0.1 * w, 0.6 * h, xf + 0.01, 0.1 * w, 0.85 * h);
      for (double y : {yl + 0.12 * w, yr - 0.12 * w}) p.Box(-0.01, y - 0.01, h - 0.005, 0.01, y + 0.01, h + 0.06);
      p.Box(-0.01, yl + 0.12 * w - 0.01, h + 0.05, 0.01, yr - 0.12 * w + 0.01, h + 0.07);
      break;
    }
    case 1: {
      p.Rod(Vector3d(0, yl, h - 0.01), Vector3d(0, yr, h - 0.01), 0.5 * d, 20);
      p.Box(xf - 0.005, yl + 0.08 * w, 0.2 * h, xf + 0.008, 0.1 * w, 0.9 * h);
      speaker(0.3 * w, 0.6 * h, 0.08 * w + 0.02);
      knob(0.3 * w - 0.06, 0.2 * h);
      knob(0.3 * w + 0.06, 0.2 * h);
      break;
    }
    case 2: {
      p.Box(xf - 0.005, yl + 0.1 * w, 0.25 * h, xf + 0.006, 0.3 * w, 0.85 * h);
      p.Box(xb + 0.02, -0.45 * w, h - 0.005, xb + 0.6 * d, 0.1 * w, h + 0.012);
      for (int k = 0; k < 3; ++k) p.Box(xb + 0.02, 0.15 * w + 0.05 * w * k, h - 0.005, xb + 0.05, 0.18 * w + 0.05 * w * k, h + 0.015);
      break;
    }
    case 3: {
      speaker(yl + 0.3 * w, 0.5 * h, 0.3 * std::min(w, 1.5 * h));
      p.Box(xf - 0.005, 0.05 * w, 0.55 * h, xf + 0.008, 0.45 * w, 0.85 * h);
      knob(0.15 * w, 0.25 * h);
      knob(0.35 * w, 0.25 * h);
      p.Rod(Vector3d(xb + 0.02, yr - 0.02, h - 0.01), Vector3d(xb - 0.05, yr + 0.1, h + 0.45), 0.005, 6);
      p.Box(-0.01, yl + 0.05, h - 0.005, 0.01, yl + 0.07, h + 0.03);
      break;
    }
    case 4: {
      p.Box(xf - 0.005, yl + 0.05, 0.3 * h, xf + 0.006, 0.1 * w, 0.8 * h);
      knob(0.25 * w, 0.5 * h);
      knob(0.4 * w, 0.5 * h);
      for (double y : {yl + 0.03, yr - 0.03}) p.Box(xf - 0.04, y - 0.015, -0.0, xf - 0.01, y + 0.015, 0.01);
      break;
    }
    default: {
      speaker(0, 0.45 * h, 0.35 * w);
      knob(0.35 * w, 0.88 * h);
      break;
    }
  }
  static const char* kStyle[] = {"boombox", "retro", "clock", "portable", "hifi", "cube"};
  return kStyle[style];
}

std::string BuildDoor(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // flat, two panels, four panels, glazed, half glazed, louvred
  const bool lever = rng.Bernoulli(0.6);
  const double w = rng.Uniform(0.78, 0.92), h = rng.Uniform(1.98, 2.1), t = rng.Uniform(0.035, 0.045);
  const double yl = -0.5 * w, yr = 0.5 * w, hx = 0.5 * t;
  auto slab = [&](double z0, double z1) { p.Box(-hx, yl, z0, hx, yr, z1); };
  // Raised panels on both faces.
  auto panels = [&](int rows, int cols, double z0, double z1) {
    const double m = 0.1;
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const double y0 = yl + m + (w - 2 * m) * c / cols + 0.03, y1 = yl + m + (w - 2 * m) * (c + 1) / cols - 0.03;
        const double za = z0 + m + (z1 - z0 - 2 * m) * r / rows + 0.03, zb = z0 + m + (z1 - z0 - 2 * m) * (r + 1) / rows - 0.03;
        p.Box(hx - 0.002, y0, za, hx + 0.012, y1, zb);
        p.Box(-hx - 0.012, y0, za, -hx + 0.002, y1, zb);
      }
    }
  };
  // Frame rails around a thin glass pane.
  auto glazed = [&](double z0, double z1, int bars) {
    const double f = 0.1;
    p.Box(-hx, yl, z0, hx, yl + f, z1);
    p.Box(-hx, yr - f, z0, hx, yr, z1);
    p.Box(-hx, yl, z1 - f, hx, yr, z1);
    p.Box(-hx, yl, z0, hx, yr, z0 + f);
    p.Box(-0.004, yl + f - 0.01, z0 + f - 0.01, 0.004, yr - f + 0.01, z1 - f + 0.01);
    for (int k = 1; k <= bars; ++k) {
      const double z = z0 + f + (z1 - z0 - 2 * f) * k / (bars + 1);
      p.Box(-0.012, yl + f, z - 0.015, 0.012, yr - f, z + 0.015);
    }
  };
  switch (style) {
    case 0: slab(0.0, h); break;
    case 1: slab(0.0, h); panels(2, 1, 0.0, h); break;
    case 2: slab(0.0, h); panels(rng.UniformInt(2, 3), 2, 0.0, h); break;
    case 3: glazed(0.0, h, rng.UniformInt(0, 3)); break;
    case 4: slab(0.0, 0.5 * h + 0.05); panels(1, 1, 0.0, 0.5 * h + 0.05); glazed(0.5 * h, h, 0); break;
    default: {
      const double f = 0.1;
      p.Box(-hx, yl, 0.0, hx, yl + f, h);
      p.Box(-hx, yr - f, 0.0, hx, yr, h);
      p.Box(-hx, yl, h - f, hx, yr, h);
      p.Box(-hx, yl, 0.0, hx, yr, f);
      p.Box(-hx, yl, 0.5 * h - 0.05, hx, yr, 0.5 * h + 0.05);
      const int n = static_cast<int>((h - 2 * f) / 0.05);
      for (int k = 0; k < n; ++k) {
        const double z = f + (h - 2 * f) * (k + 0.5) / n;
        if (std::abs(z - 0.5 * h) < 0.06) continue;
        p.BoxPitch(Vector3d(0, 0, z), Vector3d(0.008, w - 2 * f + 0.01, 0.05), 0.6);
      }
      break;
    }
  }
  // Handle on both faces near the +Y edge.
  const double hy = yr - 0.07, hz = rng.Uniform(0.95, 1.05);
  for (double s : {-1.0, 1.0}) {
    const double x = s * hx;
    p.Rod(Vector3d(x - s * 0.002, hy, hz), Vector3d(x + s * 0.05, hy, hz), 0.008, 8);
    if (lever) {
      p.Rod(Vector3d(x + s * 0.05, hy + 0.008, hz), Vector3d(x + s * 0.05, hy - 0.12, hz), 0.009, 8);
    } else {
      p.Sphere(Vector3d(x + s * 0.055, hy, hz), 0.027, 10);
    }
  }
  static const char* kStyle[] = {"flat", "panel2", "panel4", "glazed", "halfglazed", "louvred"};
  return std::string(kStyle[style]) + (lever ? "_lever" : "_knob");
}

std::string BuildWindow(Rng& rng, PartBuilder& p) {
  const int cols = rng.UniformInt(1, 3), rows = rng.UniformInt(1, 2);
  const bool transom = rng.Bernoulli(0.35);
  const bool sill = rng.Bernoulli(0.5);
  const double w = rng.Uniform(0.6, 0.55 * cols + 0.55), h = rng.Uniform(0.9, 1.5), d = rng.Uniform(0.06, 0.1);
  const double f = rng.Uniform(0.045, 0.07);
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  p.Box(xb, yl, 0.0, xf, yl + f, h);
  p.Box(xb, yr - f, 0.0, xf, yr, h);
  p.Box(xb, yl, h - f, xf, yr, h);
  p.Box(xb, yl, 0.0, xf, yr, f);
  p.Box(-0.004, yl + f - 0.005, f - 0.005, 0.004, yr - f + 0.005, h - f + 0.005);  // glass
  const double zt = transom ? h - f - rng.Uniform(0.2, 0.3) : h - f;
  if (transom) p.Box(xb + 0.01, yl, zt - 0.5 * f, xf - 0.01, yr, zt + 0.5 * f);
  const double mull = 0.6 * f;
  for (int c = 1; c < cols; ++c) {
    const double y = yl + f + (w - 2 * f) * c / cols;
    p.Box(xb + 0.01, y - 0.5 * mull, f - 0.005, xf - 0.01, y + 0.5 * mull, zt + 0.005);
  }
  for (int r = 1; r < rows; ++r) {
    const double z = f + (zt - f) * r / rows;
    p.Box(xb + 0.01, yl + f - 0.005, z - 0.5 * mull, xf - 0.01, yr - f + 0.005, z + 0.5 * mull);
  }
  if (sill) p.Box(xb, yl - 0.04, 0.0, xf + 0.06, yr + 0.04, 0.03);
  return std::to_string(cols) + "x" + std::to_string(rows) + (transom ? "_transom" : "") + (sill ? "_sill" : "");
}

std::string BuildCurtain(Rng& rng, PartBuilder& p) {
  const bool two = rng.Bernoulli(0.6);
  const bool long_drop = rng.Bernoulli(0.6);
  const bool valance = rng.Bernoulli(0.3);
  const double w = rng.Uniform(0.9, 2.0);
  const double h = long_drop ? rng.Uniform(2.0, 2.3) : rng.Uniform(1.1, 1.5);
  const double pleat = rng.Uniform(0.08, 0.14), amp = rng.Uniform(0.025, 0.045);
  const double yl = -0.5 * w, yr = 0.5 * w;
  // Panels hang from a rod (or behind a valance box) at the top; pleats are a zig-zag of slats.
  const double panel_w = two ? rng.Uniform(0.25, 0.45) * w : rng.Uniform(0.6, 1.0) * w;
  const double drop = h - 0.035;  // slats reach into the rod
  auto panel = [&](double y0, double y1) {
    const int n = std::max(2, static_cast<int>(std::round((y1 - y0) / pleat)));
    const double step = (y1 - y0) / n;
    for (int k = 0; k < n; ++k) {
      const double x0 = (k % 2 == 0) ? -amp : amp;
      const double ya = y0 + step * k;
      const double len = std::hypot(step, 2 * amp);
      p.BoxYaw(Vector3d(0.0, ya + 0.5 * step, 0.5 * drop), Vector3d(0.012, len + 0.006, drop),
               std::atan2(step, -2 * x0) - 0.5 * M_PI);
    }
  };
  if (two) {
    panel(yl + 0.04, yl + 0.04 + panel_w);
    panel(yr - 0.04 - panel_w, yr - 0.04);
  } else {
    panel(yl + 0.04, yl + 0.04 + panel_w);
  }
  if (valance) {
    p.Box(-amp - 0.04, yl, drop - 0.25, amp + 0.04, yr, h);
  } else {
    p.Rod(Vector3d(0, yl, h - 0.03), Vector3d(0, yr, h - 0.03), 0.015, 10);
    p.Sphere(Vector3d(0, yl, h - 0.03), 0.03, 10);
    p.Sphere(Vector3d(0, yr, h - 0.03), 0.03, 10);
    for (double y : {yl + 0.1, yr - 0.1}) p.Box(-0.12, y - 0.01, h - 0.05, 0.0, y + 0.01, h - 0.01);
  }
  return std::string(two ? "pair" : "single") + (long_drop ? "_long" : "_short") + (valance ? "_valance" : "_rod");
}

}  // namespace objscan::world::procedural::internal
