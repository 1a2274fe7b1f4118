#pragma once
// Point sets with known geometry for the recognition tests (header-only, test use).
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "objscan/common/rng.h"

namespace objscan::recognition::testing {

// Uniform random points on the axis-aligned rectangle [0,w]x[0,h] at z = 0.
inline std::vector<Eigen::Vector3f> UniformPlane(double w, double h, int n, Rng* rng) {
  std::vector<Eigen::Vector3f> pts(n);
  for (auto& p : pts) p = Eigen::Vector3f(rng->Uniform(0, w), rng->Uniform(0, h), 0.f);
  return pts;
}

// Points on the surface of a box [min,max] (5 faces: no bottom), uniform by area, with normals.
inline void BoxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing_m,
                       std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  auto face = [&](int a, int b, int fixed_axis, double fixed_value, double sign) {
    const int na = std::max(1, static_cast<int>(std::round((hi[a] - lo[a]) / spacing_m)));
    const int nb = std::max(1, static_cast<int>(std::round((hi[b] - lo[b]) / spacing_m)));
    for (int i = 0; i <= na; ++i) {
      for (int j = 0; j <= nb; ++j) {
        Eigen::Vector3d p;
        p[a] = lo[a] + (hi[a] - lo[a]) * i / na;
        p[b] = lo[b] + (hi[b] - lo[b]) * j / nb;
        p[fixed_axis] = fixed_value;
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        n[fixed_axis] = sign;
        pts->push_back(p.cast<float>());
        normals->push_back(n.cast<float>());
      }
    }
  };
  face(0, 1, 2, hi.z(), 1.0);
  face(1, 2, 0, lo.x(), -1.0);
  face(1, 2, 0, hi.x(), 1.0);
  face(0, 2, 1, lo.y(), -1.0);
  face(0, 2, 1, hi.y(), 1.0);
}

// An asymmetric "chair": seat box, a back on one side, four legs; points with normals.
inline void ChairLike(double spacing_m, std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  BoxSurface({-0.25, -0.22, 0.40}, {0.25, 0.22, 0.46}, spacing_m, pts, normals);      // seat
  BoxSurface({-0.25, -0.22, 0.46}, {-0.20, 0.22, 0.95}, spacing_m, pts, normals);     // back (at -x)
  for (double x : {-0.22, 0.19}) {
    for (double y : {-0.19, 0.16}) BoxSurface({x, y, 0.0}, {x + 0.03, y + 0.03, 0.40}, spacing_m, pts, normals);
  }
}

// A table: a thin top on four legs.
inline void TableLike(double spacing_m, std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  BoxSurface({-0.6, -0.4, 0.70}, {0.6, 0.4, 0.75}, spacing_m, pts, normals);
  for (double x : {-0.55, 0.5}) {
    for (double y : {-0.35, 0.3}) BoxSurface({x, y, 0.0}, {x + 0.05, y + 0.05, 0.70}, spacing_m, pts, normals);
  }
}

// Shelves: two sides and four boards.
inline void ShelfLike(double spacing_m, std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  BoxSurface({-0.4, -0.15, 0.0}, {-0.38, 0.15, 1.6}, spacing_m, pts, normals);
  BoxSurface({0.38, -0.15, 0.0}, {0.4, 0.15, 1.6}, spacing_m, pts, normals);
  for (double z : {0.1, 0.6, 1.1, 1.58}) BoxSurface({-0.38, -0.15, z - 0.02}, {0.38, 0.15, z}, spacing_m, pts, normals);
}

// A sofa: a long seat block, a back block and two arm blocks.
inline void SofaLike(double spacing_m, std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  BoxSurface({-0.9, -0.4, 0.0}, {0.9, 0.4, 0.42}, spacing_m, pts, normals);
  BoxSurface({-0.9, -0.4, 0.42}, {0.9, -0.2, 0.85}, spacing_m, pts, normals);
  BoxSurface({-0.9, -0.2, 0.42}, {-0.75, 0.4, 0.62}, spacing_m, pts, normals);
  BoxSurface({0.75, -0.2, 0.42}, {0.9, 0.4, 0.62}, spacing_m, pts, normals);
}

// A cabinet: one closed box.
inline void CabinetLike(double spacing_m, std::vector<Eigen::Vector3f>* pts, std::vector<Eigen::Vector3f>* normals) {
  BoxSurface({-0.3, -0.25, 0.0}, {0.3, 0.25, 1.2}, spacing_m, pts, normals);
}

}  // namespace objscan::recognition::testing
