#pragma once
// Which ground-truth surface voxels the depth camera could return a measurement for from some
// position in the room: the paper's coverage counts "the surface area of an object which is visible
// to robotic views within a valid scanning range" (§6). Face exposure (exposure.h) keeps a voxel
// whenever one of its faces touches the room's air, also when that air is a 5-10 cm slit between a
// bathtub and the wall or between two cabinets of a counter run: no camera fits there, and from
// outside the slit every line of sight is blocked or grazes the face beyond the sensor's dropout
// angle. This test casts rays from the voxel: it is observable when a ray within the dropout angle
// of one of its outward surface normals runs free for at least min_range_m and, between min_range_m
// and max_range_m (or the first hit), passes a height a camera can take. Hits within own_surface_m
// of the centre are the voxel's own surface; a first hit beyond it on a back face (by the triangle's
// winding) means the ray ran inside a solid. Where the camera can be is a RoomAir: the room's air,
// optionally limited to the robot's reach from the free floor.
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace objscan::render {
class Raycaster;
}

namespace objscan::eval {

class RoomAir;

struct ObservabilityOptions {
  double min_range_m = 0.5;             // the sensor's valid range
  double max_range_m = 4.0;
  double max_incidence_deg = 75.0;      // the sensor's grazing dropout: angle to the surface normal
  double min_camera_z_m = -std::numeric_limits<double>::infinity();  // world heights a camera can take
  double max_camera_z_m = std::numeric_limits<double>::infinity();
  // Hits closer than this to the voxel's centre are its own surface (half the voxel's diagonal).
  double own_surface_m = 0.045;
  int num_directions = 256;             // Fibonacci sphere
  int threads = 0;                      // 0 = hardware concurrency; results do not depend on it
};

// The outward surface normals inside one voxel, by the triangles' winding (counter-clockwise seen
// from outside); length = the area behind each, any positive length will do. A voxel on an edge or
// holding both faces of a thin panel has several; a mesh wound both ways gives both signs, which
// errs towards observable.
using NormalLines = std::vector<Eigen::Vector3f>;

// 1 for each voxel (centre, normal lines) a camera could measure under `options`, 0 otherwise. A
// voxel without normal lines is kept (1). With `camera_air`, the camera must also be where it can
// be (RoomAir::CameraCanBeAt: in the room's air, not outside behind a window; within the robot's
// reach when restricted). Throws InputError on sizes that differ or bad
// options.
std::vector<char> ObservableVoxels(const render::Raycaster& caster, const std::vector<Eigen::Vector3d>& centers_world,
                                   const std::vector<NormalLines>& normal_lines, const ObservabilityOptions& options,
                                   const RoomAir* camera_air = nullptr);

// Adds area * normal (unit) to `lines`: into the line within merge_deg of it, else as a new line
// while fewer than max_lines are held, else into the closest line.
void AddNormalLine(NormalLines* lines, const Eigen::Vector3f& normal, float area, double merge_deg = 25.0,
                   std::size_t max_lines = 6);

}  // namespace objscan::eval
