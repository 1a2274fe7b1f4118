// Chairs, sofas and beds.
#include <cmath>

#include "objscan/world/procedural/furniture_generators.h"

namespace objscan::world::procedural::internal {

using Eigen::Vector3d;

std::string BuildChair(Rng& rng, PartBuilder& p) {
  const int base = Pick(rng, 3);  // four legs, swivel pedestal, sled runners
  const int back = Pick(rng, 4);  // solid panel, vertical slats, horizontal rails, tall panel
  const bool arms = rng.Bernoulli(0.45);
  const double w = rng.Uniform(0.42, 0.50) + (arms ? 0.08 : 0.0), d = rng.Uniform(0.40, 0.50);
  const double seat_h = rng.Uniform(0.42, 0.48), seat_t = rng.Uniform(0.04, 0.08);
  const double back_h = back == 3 ? rng.Uniform(0.60, 0.75) : rng.Uniform(0.35, 0.48);
  const double xf = 0.5 * d, xb = -0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const double seat_z0 = seat_h - seat_t;
  p.Box(xb, yl, seat_z0, xf, yr, seat_h);

  static const char* kBase[] = {"legs", "pedestal", "sled"};
  if (base == 0) {
    const double t = rng.Uniform(0.03, 0.045);
    FourLegs(p, xb + 0.01, xf - 0.01, yl + 0.01, yr - 0.01, seat_z0 + 0.01, t,
             static_cast<LegStyle>(Pick(rng, 3)));
  } else if (base == 1) {
    const double spoke = rng.Uniform(0.26, 0.32);
    p.CylinderZ(0, 0, 0.07, seat_z0 + 0.01, rng.Uniform(0.025, 0.035), 14);
    p.Box(-0.12, -0.12, seat_z0 - 0.04, 0.12, 0.12, seat_z0 + 0.005);
    for (int k = 0; k < 5; ++k) {
      const double a = 2.0 * M_PI * k / 5.0;
      p.BoxYaw(Vector3d(0.5 * spoke * std::cos(a), 0.5 * spoke * std::sin(a), 0.07), Vector3d(spoke, 0.04, 0.035), a);
      p.Sphere(Vector3d(0.93 * spoke * std::cos(a), 0.93 * spoke * std::sin(a), 0.03), 0.03, 10);
    }
  } else {
    const double r = 0.012;
    for (double y : {yl + 0.02, yr - 0.02}) {
      p.Rod(Vector3d(xb - 0.02, y, r), Vector3d(xf + 0.02, y, r), r);
      p.Rod(Vector3d(xf - 0.03, y, 0.0), Vector3d(xf - 0.03, y, seat_z0 + 0.01), r);
      p.Rod(Vector3d(xb + 0.03, y, 0.0), Vector3d(xb + 0.03, y, seat_z0 + 0.01), r);
    }
  }

  static const char* kBack[] = {"solid", "slats", "rails", "tall"};
  const double top = seat_h + back_h;
  if (back == 0 || back == 3) {
    const double recline = rng.Uniform(0.04, 0.18);
    const double t = rng.Uniform(0.03, 0.06);
    const double len = back_h + 0.03;
    p.BoxPitch(Vector3d(xb + 0.5 * t - 0.5 * len * std::sin(recline), 0.0, seat_h - 0.03 + 0.5 * len * std::cos(recline)),
               Vector3d(t, w, len), -recline);
  } else {
    const double post = 0.035;
    for (double y : {yl, yr - post}) p.Box(xb, y, seat_z0, xb + post, y + post, top);
    p.Box(xb, yl, top - 0.07, xb + post, yr, top);
    if (back == 1) {
      const int n = rng.UniformInt(3, 5);
      for (int k = 0; k < n; ++k) {
        const double y = yl + post + (w - 2 * post) * (k + 0.5) / n;
        p.Box(xb + 0.005, y - 0.015, seat_h - 0.01, xb + post - 0.005, y + 0.015, top - 0.06);
      }
    } else {
      const int n = rng.UniformInt(1, 3);
      for (int k = 0; k < n; ++k) {
        const double z = seat_h + (back_h - 0.07) * (k + 1) / (n + 1);
        p.Box(xb + 0.005, yl, z - 0.025, xb + post - 0.005, yr, z + 0.025);
      }
    }
  }
  if (arms) {
    const double arm_z = seat_h + rng.Uniform(0.18, 0.24);
    for (double y : {yl, yr - 0.05}) {
      p.Box(xb + 0.01, y, arm_z - 0.035, xf - 0.01, y + 0.05, arm_z);
      p.Box(xf - 0.07, y + 0.01, seat_h - 0.01, xf - 0.03, y + 0.04, arm_z - 0.03);
    }
  }
  return std::string(kBase[base]) + "_" + kBack[back] + (arms ? "_arms" : "_armless");
}

std::string BuildSofa(Rng& rng, PartBuilder& p) {
  const int seats = rng.UniformInt(2, 3);
  const int arm_style = Pick(rng, 3);  // none, box, rolled
  const bool on_legs = rng.Bernoulli(0.5);
  const bool l_shape = rng.Bernoulli(0.3);
  const double seat_w = rng.Uniform(0.55, 0.68);
  const double arm_w = arm_style == 0 ? 0.0 : rng.Uniform(0.12, 0.24);
  const double w = seats * seat_w + 2 * arm_w;
  const double d = rng.Uniform(0.82, 0.98);
  const double seat_h = rng.Uniform(0.40, 0.46), cushion_t = rng.Uniform(0.10, 0.16);
  const double back_top = rng.Uniform(0.75, 0.92), back_t = rng.Uniform(0.16, 0.24);
  const double arm_h = rng.Uniform(0.55, 0.66);
  const double leg_h = on_legs ? rng.Uniform(0.08, 0.15) : 0.0;
  const double chaise = l_shape ? rng.Uniform(0.55, 0.85) : 0.0;
  const double xb = -0.5 * d, xf = 0.5 * d, yl = -0.5 * w, yr = 0.5 * w;
  const double base_top = seat_h - cushion_t;

  // Frame, with the chaise (on the +Y side) extending towards +X.
  p.Box(xb, yl, leg_h, xf, yr, base_top);
  if (l_shape) p.Box(xf - 0.05, yr - arm_w - seat_w, leg_h, xf + chaise, yr - arm_w, base_top);
  if (on_legs) {
    const LegStyle style = rng.Bernoulli(0.5) ? LegStyle::kTapered : LegStyle::kSquare;
    FourLegs(p, xb + 0.02, xf - 0.02, yl + 0.02, yr - 0.02, leg_h + 0.01, 0.05, style);
    if (l_shape) {
      FourLegs(p, xf + chaise - 0.3, xf + chaise - 0.02, yr - arm_w - seat_w + 0.02, yr - arm_w - 0.02, leg_h + 0.01,
               0.05, style);
    }
  }
  // Seat cushions (touching the frame, small gaps between them).
  for (int k = 0; k < seats; ++k) {
    const double y0 = yl + arm_w + k * seat_w, y1 = y0 + seat_w;
    const bool chaise_seat = l_shape && k == seats - 1;
    p.Box(xb + back_t, y0 + 0.005, base_top - 0.005, xf + (chaise_seat ? chaise : 0.0) + 0.01, y1 - 0.005, seat_h);
  }
  // Back and back cushions.
  p.Box(xb, yl, base_top - 0.01, xb + back_t, yr, back_top);
  if (rng.Bernoulli(0.6)) {
    for (int k = 0; k < seats; ++k) {
      const double y0 = yl + arm_w + k * seat_w;
      p.BoxPitch(Vector3d(xb + back_t + 0.06, y0 + 0.5 * seat_w, seat_h + 0.5 * (back_top - seat_h) - 0.03),
                 Vector3d(0.14, seat_w - 0.03, back_top - seat_h - 0.04), -0.12);
    }
  }
  // Arms.
  if (arm_style != 0) {
    for (int side = 0; side < 2; ++side) {
      const double y0 = side == 0 ? yl : yr - arm_w, y1 = y0 + arm_w;
      const double x1 = (side == 1 && l_shape) ? xf + chaise : xf;
      if (arm_style == 1) {
        p.Box(xb, y0, leg_h, x1, y1, arm_h);
      } else {
        const double r = 0.5 * arm_w + 0.02;
        p.Box(xb, y0, leg_h, x1, y1, arm_h - 0.5 * r);
        p.Rod(Vector3d(xb, 0.5 * (y0 + y1), arm_h - r), Vector3d(x1 + 0.01, 0.5 * (y0 + y1), arm_h - r), r, 16);
      }
    }
  }
  static const char* kArms[] = {"noarms", "boxarms", "rolledarms"};
  return std::string(l_shape ? "lshape" : "straight") + "_" + std::to_string(seats) + "seat_" + kArms[arm_style] +
         (on_legs ? "_legs" : "_skirt");
}

std::string BuildBed(Rng& rng, PartBuilder& p) {
  const bool dbl = rng.Bernoulli(0.6);
  const int head = Pick(rng, 4);  // none, panel, upholstered tall, slatted
  const bool foot = rng.Bernoulli(0.45);
  const bool platform = rng.Bernoulli(0.5);
  const double w = dbl ? rng.Uniform(1.40, 1.80) : rng.Uniform(0.90, 1.05);
  const double len = rng.Uniform(2.00, 2.15);
  const double frame_top = rng.Uniform(0.25, 0.38), mattress_t = rng.Uniform(0.18, 0.28);
  const double xb = -0.5 * len, xf = 0.5 * len, yl = -0.5 * w, yr = 0.5 * w;
  if (platform) {
    p.Box(xb + 0.02, yl + 0.03, 0.0, xf - 0.02, yr - 0.03, 0.08);
    p.Box(xb, yl, 0.07, xf, yr, frame_top);
  } else {
    p.Box(xb, yl, frame_top - 0.15, xf, yr, frame_top);
    FourLegs(p, xb, xf, yl, yr, frame_top - 0.14, 0.06, rng.Bernoulli(0.5) ? LegStyle::kSquare : LegStyle::kRound);
  }
  const double mtop = frame_top + mattress_t;
  p.Box(xb + 0.03, yl + 0.02, frame_top - 0.01, xf - 0.03, yr - 0.02, mtop);
  // Blanket over the foot two thirds, draping slightly over the sides.
  const double blanket_x0 = xb + rng.Uniform(0.55, 0.8);
  p.Box(blanket_x0, yl, mtop - 0.12, xf - 0.01, yr, mtop + 0.03);
  // Pillows.
  const int pillows = dbl ? 2 : 1;
  for (int k = 0; k < pillows; ++k) {
    const double y = yl + w * (k + 0.5) / pillows;
    p.Ellipsoid(Vector3d(xb + 0.28, y, mtop + 0.04), Vector3d(0.2, std::min(0.33, 0.42 * w / pillows), 0.07), 14);
  }
  const double ht = head == 2 ? rng.Uniform(0.08, 0.14) : 0.05;
  const double hh = head == 2 ? rng.Uniform(1.10, 1.35) : rng.Uniform(0.85, 1.05);
  if (head == 1 || head == 2) {
    p.Box(xb - ht + 0.01, yl - 0.02, 0.0, xb + 0.01, yr + 0.02, hh);
  } else if (head == 3) {
    for (double y : {yl - 0.02, yr - 0.04}) p.Box(xb - 0.05, y, 0.0, xb + 0.01, y + 0.06, hh);
    p.Box(xb - 0.045, yl - 0.02, hh - 0.08, xb + 0.005, yr + 0.02, hh);
    const int n = static_cast<int>(w / 0.15);
    for (int k = 1; k < n; ++k) {
      const double y = yl + w * k / n;
      p.Box(xb - 0.04, y - 0.02, frame_top - 0.02, xb, y + 0.02, hh - 0.07);
    }
  }
  if (foot) {
    const double fh = rng.Uniform(0.45, 0.65);
    p.Box(xf - 0.01, yl - 0.02, 0.0, xf + 0.05, yr + 0.02, fh);
  }
  static const char* kHead[] = {"nohead", "panelhead", "tallhead", "slathead"};
  return std::string(dbl ? "double" : "single") + "_" + kHead[head] + (foot ? "_foot" : "_nofoot") +
         (platform ? "_platform" : "_legs");
}

}  // namespace objscan::world::procedural::internal
