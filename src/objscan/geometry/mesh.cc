#include "objscan/geometry/mesh.h"

#include <cmath>

namespace objscan::geometry {

Aabb3 Bounds(const TriangleMesh& mesh) {
  Aabb3 box;
  for (const auto& v : mesh.vertices) box.Extend(v.cast<double>());
  return box;
}

Aabb3 Bounds(const TriangleMesh& mesh, const Eigen::Isometry3d& T) {
  Aabb3 box;
  for (const auto& v : mesh.vertices) box.Extend(T * v.cast<double>());
  return box;
}

TriangleMesh Transformed(const TriangleMesh& mesh, const Eigen::Affine3d& T) {
  TriangleMesh out = mesh;
  for (auto& v : out.vertices) v = (T * v.cast<double>()).cast<float>();
  // A reflection flips the winding; keep faces outward.
  if (T.linear().determinant() < 0.0) {
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
  }
  return out;
}

void Append(const TriangleMesh& other, TriangleMesh* mesh) {
  const int offset = static_cast<int>(mesh->vertices.size());
  mesh->vertices.insert(mesh->vertices.end(), other.vertices.begin(), other.vertices.end());
  mesh->triangles.reserve(mesh->triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) mesh->triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

double SurfaceArea(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

std::size_t RemoveDegenerateTriangles(TriangleMesh* mesh) {
  const int n = static_cast<int>(mesh->vertices.size());
  std::vector<Eigen::Vector3i> kept;
  kept.reserve(mesh->triangles.size());
  for (const auto& t : mesh->triangles) {
    if ((t.array() < 0).any() || (t.array() >= n).any()) continue;
    const Eigen::Vector3f a = mesh->vertices[t[0]], b = mesh->vertices[t[1]], c = mesh->vertices[t[2]];
    if (!a.allFinite() || !b.allFinite() || !c.allFinite()) continue;
    if ((b - a).cross(c - a).squaredNorm() <= 1e-20f) continue;
    kept.push_back(t);
  }
  const std::size_t removed = mesh->triangles.size() - kept.size();
  mesh->triangles.swap(kept);
  return removed;
}

TriangleMesh MakeBox(const Eigen::Vector3d& size_m) { return MakeBox(-0.5 * size_m, 0.5 * size_m); }

TriangleMesh MakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back(static_cast<float>((i & 1) ? hi.x() : lo.x()), static_cast<float>((i & 2) ? hi.y() : lo.y()),
                            static_cast<float>((i & 4) ? hi.z() : lo.z()));
  }
  // Each face as two triangles with outward normals (counter-clockwise seen from outside).
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return m;
}

TriangleMesh MakeCylinder(double radius_m, double length_m, int segments) {
  TriangleMesh m;
  const float h = static_cast<float>(0.5 * length_m);
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * M_PI * i / segments;
    const float x = static_cast<float>(radius_m * std::cos(a)), y = static_cast<float>(radius_m * std::sin(a));
    m.vertices.emplace_back(x, y, -h);
    m.vertices.emplace_back(x, y, h);
  }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0.f, 0.f, -h);
  m.vertices.emplace_back(0.f, 0.f, h);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    const int b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * j, t1 = 2 * j + 1;
    m.triangles.emplace_back(b0, b1, t1);
    m.triangles.emplace_back(b0, t1, t0);
    m.triangles.emplace_back(bottom, b1, b0);
    m.triangles.emplace_back(bottom + 1, t0, t1);
  }
  return m;
}

TriangleMesh MakeSphere(double radius_m, int segments) {
  TriangleMesh m;
  const int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    const double phi = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double th = 2.0 * M_PI * s / segments;
      m.vertices.emplace_back(static_cast<float>(radius_m * std::sin(phi) * std::cos(th)),
                              static_cast<float>(radius_m * std::sin(phi) * std::sin(th)),
                              static_cast<float>(radius_m * std::cos(phi)));
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      if (r > 0) m.triangles.emplace_back(a, c, b);
      if (r < rings - 1) m.triangles.emplace_back(b, c, d);
    }
  }
  return m;
}

TriangleMesh MakeQuadXY(double x0, double y0, double x1, double y1) {
  TriangleMesh m;
  m.vertices = {Eigen::Vector3f(x0, y0, 0), Eigen::Vector3f(x1, y0, 0), Eigen::Vector3f(x1, y1, 0),
                Eigen::Vector3f(x0, y1, 0)};
  m.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 2, 3)};
  return m;
}

}  // namespace objscan::geometry
