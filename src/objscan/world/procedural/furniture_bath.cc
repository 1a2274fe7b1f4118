// Bathtubs, sinks and toilets.
#include <algorithm>
#include <cmath>

#include "objscan/world/procedural/furniture_generators.h"

namespace objscan::world::procedural::internal {

using Eigen::Vector3d;

namespace {

// An open-topped basin: bottom plus four walls of thickness t.
void HollowBox(PartBuilder& p, double x0, double y0, double z0, double x1, double y1, double z1, double t) {
  p.Box(x0, y0, z0, x1, y1, z0 + t);
  p.Box(x0, y0, z0, x0 + t, y1, z1);
  p.Box(x1 - t, y0, z0, x1, y1, z1);
  p.Box(x0, y0, z0, x1, y0 + t, z1);
  p.Box(x0, y1 - t, z0, x1, y1, z1);
}

// The wall of an open elliptic vessel (semi-axes rx, ry) made of `n` slightly overlapping boxes.
void EllipseWall(PartBuilder& p, double cx, double cy, double rx, double ry, double z0, double z1, double t, int n) {
  for (int k = 0; k < n; ++k) {
    const double a0 = 2.0 * M_PI * k / n, a1 = 2.0 * M_PI * (k + 1) / n;
    const Vector3d q0(cx + rx * std::cos(a0), cy + ry * std::sin(a0), 0.0);
    const Vector3d q1(cx + rx * std::cos(a1), cy + ry * std::sin(a1), 0.0);
    const Vector3d mid = 0.5 * (q0 + q1);
    const Vector3d dir = q1 - q0;
    const double yaw = std::atan2(dir.y(), dir.x());
    // Box along the chord, pushed inward by half the thickness so the outside stays on the ellipse.
    const Vector3d inward = Vector3d(-(mid.x() - cx) / (rx * rx), -(mid.y() - cy) / (ry * ry), 0.0).normalized();
    p.BoxYaw(Vector3d(mid.x() + 0.5 * t * inward.x(), mid.y() + 0.5 * t * inward.y(), 0.5 * (z0 + z1)),
             Vector3d(dir.norm() + 0.6 * t, t, z1 - z0), yaw);
  }
}

void Faucet(PartBuilder& p, double x, double y, double z, double height, double reach) {
  p.CylinderZ(x, y, z - 0.005, z + height, 0.015, 12);
  p.Rod(Vector3d(x - 0.005, y, z + height - 0.015), Vector3d(x + reach, y, z + height - 0.015), 0.012, 10);
  p.Box(x - 0.05, y - 0.012, z + 0.05, x - 0.005, y + 0.012, z + 0.07);
}

}  // namespace

std::string BuildBathtub(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // built-in, clawfoot, freestanding oval, with screen, with shower pole, on a step
  const double len = rng.Uniform(1.5, 1.8), w = rng.Uniform(0.7, 0.85), h = rng.Uniform(0.5, 0.6);
  const double xb = -0.5 * w, xf = 0.5 * w, yl = -0.5 * len, yr = 0.5 * len;
  const double t = rng.Uniform(0.06, 0.1);
  if (style == 1 || style == 2) {
    const double z0 = style == 1 ? 0.12 : 0.0;
    EllipseWall(p, 0, 0, 0.5 * w, 0.5 * len, z0 + 0.05, h + z0 * 0.5, 0.05, 28);
    p.EllipticCylinderZ(0, 0, z0, z0 + 0.08, 0.5 * w - 0.06, 0.5 * len - 0.08, 28);
    p.EllipticCylinderZ(0, 0, z0 + 0.02, z0 + 0.06, 0.5 * w - 0.02, 0.5 * len - 0.03, 28);
    if (style == 1) {
      for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
          const Vector3d foot(sx * 0.22 * w, sy * 0.33 * len, 0.06);
          p.Sphere(foot, 0.06, 10);
          p.Rod(foot, Vector3d(foot.x() * 0.9, foot.y() * 0.9, z0 + 0.05), 0.03, 8);
        }
      }
    } else {
      p.EllipticCylinderZ(0, 0, 0.0, 0.03, 0.5 * w - 0.01, 0.5 * len - 0.01, 28);
    }
    Faucet(p, 0.0, yr - 0.06, h + z0 * 0.5 - 0.01, 0.2, -0.12);
  } else {
    const double step = style == 5 ? rng.Uniform(0.12, 0.2) : 0.0;
    if (step > 0.0) p.Box(xb - 0.1, yl - 0.05, 0.0, xf + 0.25, yr + 0.05, step);
    const double z0 = step > 0 ? step - 0.005 : 0.0;
    HollowBox(p, xb, yl, z0, xf, yr, z0 + h, t);
    p.Box(xb + t, yl + t, z0, xf - t, yr - t, z0 + 0.12);  // basin floor
    p.Box(xf - 0.005, yl, z0, xf + 0.01, yr, z0 + h - 0.04);  // front apron
    Faucet(p, xb + 0.5 * t, yr - t - 0.1, z0 + h - 0.01, 0.15, 0.12);
    if (style == 3) p.Box(-0.01, yr - 0.8, z0 + h - 0.01, 0.01, yr - 0.05, z0 + h + 1.35);
    if (style == 4) {
      p.Rod(Vector3d(xb + 0.5 * t, yr - 0.5 * t, z0 + h - 0.01), Vector3d(xb + 0.5 * t, yr - 0.5 * t, z0 + h + 1.4), 0.015, 10);
      p.Rod(Vector3d(xb + 0.5 * t, yr - 0.5 * t, z0 + h + 1.38), Vector3d(xb + 0.25, yr - 0.5 * t, z0 + h + 1.38), 0.012, 8);
      p.CylinderZ(xb + 0.25, yr - 0.5 * t, z0 + h + 1.33, z0 + h + 1.375, 0.08, 16);
    }
  }
  static const char* kStyle[] = {"builtin", "clawfoot", "oval", "screen", "shower", "step"};
  return kStyle[style];
}

std::string BuildSink(Rng& rng, PartBuilder& p) {
  const int style = Pick(rng, 6);  // pedestal, vanity, vessel, console, kitchen double bowl, trough on legs
  const double h = rng.Uniform(0.8, 0.9);
  switch (style) {
    case 0: {
      const double w = rng.Uniform(0.5, 0.65), d = rng.Uniform(0.4, 0.5);
      p.FrustumZ(0, 0, 0.0, h - 0.15, 0.12, 0.08, 20);
      EllipseWall(p, 0, 0, 0.5 * d, 0.5 * w, h - 0.2, h, 0.04, 24);
      p.EllipticCylinderZ(0, 0, h - 0.2, h - 0.15, 0.5 * d - 0.02, 0.5 * w - 0.02, 24);
      p.Box(-0.5 * d, -0.5 * w + 0.05, h - 0.2, -0.5 * d + 0.1, 0.5 * w - 0.05, h);
      Faucet(p, -0.5 * d + 0.05, 0, h, 0.15, 0.1);
      break;
    }
    case 1:
    case 4: {
      const bool kitchen = style == 4;
      const double w = kitchen ? rng.Uniform(0.8, 1.2) : rng.Uniform(0.6, 1.0);
      const double d = kitchen ? rng.Uniform(0.55, 0.62) : rng.Uniform(0.42, 0.55);
      const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w, top = 0.03;
      p.Box(xb, yl, 0.0, xf - 0.02, yr, h - top + 0.002);
      const int doors = w > 0.7 ? 2 : 1;
      for (int k = 0; k < doors; ++k) {
        const double y0 = yl + w * k / doors, y1 = yl + w * (k + 1) / doors;
        p.Box(xf - 0.025, y0 + 0.004, 0.1, xf, y1 - 0.004, h - top - 0.01);
        Knob(p, xf, k == 0 && doors == 2 ? y1 - 0.05 : y0 + 0.05, h - top - 0.1);
      }
      // Counter top with one or two basin openings, the basins hanging below.
      const int bowls = kitchen && w > 0.95 ? 2 : 1;
      const double bx0 = xb + 0.12, bx1 = xf - 0.08;
      const double margin = 0.08, gap = 0.06;
      const double bw = (w - 2 * margin - (bowls - 1) * gap) / bowls;
      p.Box(xb, yl, h - top, bx0, yr, h);
      p.Box(bx1, yl, h - top, xf + 0.01, yr, h);
      double y = yl;
      for (int k = 0; k < bowls; ++k) {
        const double y0 = yl + margin + k * (bw + gap);
        p.Box(bx0, y, h - top, bx1, y0, h);
        HollowBox(p, bx0, y0, h - 0.2, bx1, y0 + bw, h - top + 0.002, 0.015);
        y = y0 + bw;
      }
      p.Box(bx0, y, h - top, bx1, yr, h);
      if (kitchen) {
        p.CylinderZ(xb + 0.06, 0, h - 0.005, h + 0.35, 0.018, 12);
        p.Rod(Vector3d(xb + 0.06, 0, h + 0.34), Vector3d(xb + 0.3, 0, h + 0.34), 0.016, 10);
        p.Rod(Vector3d(xb + 0.3, 0, h + 0.35), Vector3d(xb + 0.3, 0, h + 0.22), 0.014, 10);
      } else {
        Faucet(p, xb + 0.06, 0, h, 0.14, 0.1);
      }
      break;
    }
    case 2: {
      const double w = rng.Uniform(0.6, 1.0), d = rng.Uniform(0.42, 0.52);
      const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w, ch = h - 0.14;
      const double leg_h = 0.15;
      p.Box(xb, yl, leg_h, xf, yr, ch);
      FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yr - 0.02, leg_h + 0.005, 0.04, LegStyle::kSquare);
      DrawerFront(p, xf, yl, yr, leg_h, ch, true);
      const double r = rng.Uniform(0.17, 0.22);
      EllipseWall(p, 0.03, 0, r, r * rng.Uniform(1.0, 1.4), ch - 0.005, h, 0.025, 24);
      p.EllipticCylinderZ(0.03, 0, ch - 0.005, ch + 0.02, r - 0.01, r - 0.01, 24);
      p.CylinderZ(xb + 0.05, 0, ch - 0.005, h + 0.18, 0.015, 12);
      p.Rod(Vector3d(xb + 0.05, 0, h + 0.17), Vector3d(xb + 0.16, 0, h + 0.17), 0.012, 10);
      break;
    }
    case 3: {
      const double w = rng.Uniform(0.55, 0.8), d = rng.Uniform(0.42, 0.5);
      const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
      HollowBox(p, xb, yl, h - 0.16, xf, yr, h, 0.03);
      for (double y : {yl + 0.05, yr - 0.05}) {
        p.CylinderZ(xf - 0.05, y, 0.0, h - 0.155, 0.018, 12);
        p.CylinderZ(xb + 0.05, y, 0.0, h - 0.155, 0.018, 12);
      }
      p.Rod(Vector3d(xf - 0.05, yl + 0.05, 0.2), Vector3d(xf - 0.05, yr - 0.05, 0.2), 0.012, 8);
      p.Box(xb, yl, h - 0.005, xb + 0.02, yr, h + 0.15);
      Faucet(p, xb + 0.05, 0, h, 0.12, 0.1);
      break;
    }
    default: {
      const double w = rng.Uniform(1.0, 1.5), d = rng.Uniform(0.42, 0.5);
      const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
      HollowBox(p, xb, yl, h - 0.18, xf, yr, h, 0.035);
      FourLegs(p, xb + 0.03, xf - 0.03, yl + 0.05, yr - 0.05, h - 0.175, 0.045, LegStyle::kSquare);
      p.Box(xb + 0.03, yl + 0.05, 0.15, xf - 0.03, yr - 0.05, 0.18);
      for (double y : {-0.25 * w, 0.25 * w}) Faucet(p, xb + 0.04, y, h, 0.15, 0.12);
      break;
    }
  }
  static const char* kStyle[] = {"pedestal", "vanity", "vessel", "console", "kitchen", "trough"};
  return kStyle[style];
}

std::string BuildToilet(Rng& rng, PartBuilder& p) {
  const int tank = Pick(rng, 3);  // close-coupled tank, concealed (back-to-wall box), high tank with pipe
  const bool elongated = rng.Bernoulli(0.5);
  const bool lid_open = rng.Bernoulli(0.4);
  const double seat_h = rng.Uniform(0.39, 0.44);
  const double brx = elongated ? rng.Uniform(0.23, 0.26) : rng.Uniform(0.19, 0.21);
  const double bry = rng.Uniform(0.17, 0.19);
  const double bx = 0.0;  // bowl centre; the back is at -X
  const double back_x = bx - brx + 0.02;
  p.EllipticCylinderZ(bx - 0.04, 0, 0.0, 0.2, 0.6 * brx, 0.55 * bry, 20);
  p.EllipticCylinderZ(bx - 0.03, 0, 0.02, 0.06, 0.7 * brx, 0.65 * bry, 20);
  EllipseWall(p, bx, 0, brx, bry, 0.18, seat_h - 0.03, 0.035, 24);
  p.EllipticCylinderZ(bx, 0, 0.18, 0.24, brx - 0.02, bry - 0.02, 24);
  p.EllipticCylinderZ(bx, 0, seat_h - 0.035, seat_h - 0.01, brx + 0.005, bry + 0.005, 24);  // seat
  p.Box(back_x - 0.06, -0.1, seat_h - 0.06, back_x + 0.04, 0.1, seat_h - 0.01);           // seat hinge block
  const double tank_d = rng.Uniform(0.16, 0.22), tank_w = rng.Uniform(0.38, 0.5);
  const double tx1 = back_x - 0.02, tx0 = tx1 - tank_d;
  if (tank == 0) {
    const double tank_top = seat_h + rng.Uniform(0.3, 0.42);
    p.Box(tx0, -0.5 * tank_w, seat_h - 0.12, tx1 + 0.02, 0.5 * tank_w, tank_top);
    p.Box(tx0 - 0.01, -0.5 * tank_w - 0.01, tank_top - 0.005, tx1 + 0.03, 0.5 * tank_w + 0.01, tank_top + 0.03);
    p.CylinderZ(tx0 + 0.5 * tank_d, 0, tank_top + 0.02, tank_top + 0.04, 0.025, 12);
  } else if (tank == 1) {
    p.Box(tx0, -0.5 * tank_w + 0.03, 0.0, tx1 + 0.03, 0.5 * tank_w - 0.03, seat_h - 0.02);
  } else {
    const double tank_z = rng.Uniform(1.7, 1.85);
    p.Rod(Vector3d(tx1 - 0.04, 0, seat_h - 0.1), Vector3d(tx1 - 0.04, 0, tank_z + 0.01), 0.02, 10);
    p.Box(tx1 - 0.12, -0.5 * tank_w + 0.05, tank_z, tx1, 0.5 * tank_w - 0.05, tank_z + 0.25);
    p.Rod(Vector3d(tx1 - 0.01, 0.15, tank_z + 0.18), Vector3d(tx1 + 0.1, 0.18, tank_z + 0.1), 0.008, 6);
  }
  if (lid_open) {
    p.BoxPitch(Vector3d(back_x - 0.005, 0, seat_h + 0.5 * 2 * brx - 0.04), Vector3d(0.025, 2 * bry, 2 * brx), -0.12);
  } else {
    p.EllipticCylinderZ(bx, 0, seat_h - 0.012, seat_h + 0.01, brx, bry + 0.005, 24);
  }
  static const char* kTank[] = {"tank", "concealed", "hightank"};
  return std::string(kTank[tank]) + (elongated ? "_elongated" : "_round") + (lid_open ? "_open" : "_closed");
}

}  // namespace objscan::world::procedural::internal
