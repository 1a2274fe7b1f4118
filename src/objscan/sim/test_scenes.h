#pragma once
// Small analytic scenes shared by the sim tests (test-only, header-only).
#include "objscan/geometry/mesh.h"
#include "objscan/render/depth_camera.h"
#include "objscan/world/scene.h"

namespace objscan::sim::testing {

inline world::SceneObject BoxObject(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                    world::Category category = world::Category::kCabinet) {
  world::SceneObject o;
  o.category = category;
  o.mesh = geometry::MakeBox(lo, hi);
  return o;
}

// A floor quad over [x0, x1] x [y0, y1] at z = 0.
inline world::SceneObject FloorObject(double x0, double y0, double x1, double y1) {
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(x0, y0, x1, y1);
  return floor;
}

// A closed room [0, size_x] x [0, size_y] with a floor and 0.1 m thick, 2.5 m high walls outside it.
inline world::Scene Room(double size_x, double size_y) {
  world::Scene scene("room");
  scene.Add(FloorObject(-0.1, -0.1, size_x + 0.1, size_y + 0.1));
  const double t = 0.1, h = 2.5;
  scene.Add(BoxObject({-t, -t, 0}, {size_x + t, 0, h}, world::Category::kWall));
  scene.Add(BoxObject({-t, size_y, 0}, {size_x + t, size_y + t, h}, world::Category::kWall));
  scene.Add(BoxObject({-t, 0, 0}, {0, size_y, h}, world::Category::kWall));
  scene.Add(BoxObject({size_x, 0, 0}, {size_x + t, size_y, h}, world::Category::kWall));
  return scene;
}

// A 6 m x 4 m room with a cabinet in its far half (the platform contract's room).
inline world::Scene CabinetRoom() {
  world::Scene scene = Room(6, 4);
  scene.Add(BoxObject({4.5, 0.5, 0.0}, {5.5, 1.0, 0.9}));
  return scene;
}

// A quarter-size sensor (160 x 120, the same field of view), one thread: quick frames.
inline render::SensorOptions SmallSensor() {
  render::SensorOptions sensor;
  sensor.width_px = 160;
  sensor.height_px = 120;
  sensor.fx_px = sensor.fy_px = 131.25;
  sensor.cx_px = 79.5;
  sensor.cy_px = 59.5;
  sensor.threads = 1;
  return sensor;
}

}  // namespace objscan::sim::testing
