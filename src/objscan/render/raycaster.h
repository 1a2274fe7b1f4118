#pragma once
// Ray casting against a static triangle soup (Embree 3, hidden behind a pImpl). The scene is built
// once in the constructor; queries are const and thread-safe. Rays are traced in packets of 16
// consecutive rays, so callers get the best speed by putting coherent rays next to each other
// (e.g. 4x4 pixel tiles). Every ray's result depends on that ray alone.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "objscan/world/scene.h"

namespace objscan::render {

struct RayHit {
  float distance = std::numeric_limits<float>::infinity();  // ray parameter t (metres for unit directions)
  std::int32_t instance_id = world::kNoInstance;             // 0 = miss
  std::uint32_t triangle = 0;                                // index into the soup's triangles (valid on a hit)
  Eigen::Vector3f normal_world = Eigen::Vector3f::Zero();    // unit geometric normal by the triangle's winding
                                                             // (counter-clockwise = front); zero on a miss
  bool Hit() const { return instance_id != world::kNoInstance; }
};

// Rays as flat arrays. Directions need not be unit length: a hit's distance is the ray parameter t,
// so with camera-frame directions (x, y, 1) it is the depth z.
struct RayBatch {
  std::vector<float> origins_xyz;     // 3 per ray, or exactly 3 when all rays share one origin
  std::vector<float> directions_xyz;  // 3 per ray
  float t_min = 0.f;
  float t_max = std::numeric_limits<float>::infinity();
  std::size_t size() const { return directions_xyz.size() / 3; }
};

// What the rays shot from a point in all directions see: used to reject camera poses inside
// objects or touching a surface.
struct PointProbe {
  double clearance_m = std::numeric_limits<double>::infinity();  // nearest hit over the probe directions
  double hit_fraction = 0.0;        // share of directions that hit anything
  double back_face_fraction = 0.0;  // share of directions whose first hit is a back face
  // Enclosed: (nearly) every direction hits, and most first hits are back faces (seen from inside).
  bool inside = false;
};

// `n` evenly spread, deterministic unit directions (Fibonacci sphere), from +z towards -z.
std::vector<Eigen::Vector3f> FibonacciDirections(int n);

class Raycaster {
 public:
  // Commits the soup once. Throws InputError when an index is out of range or a vertex is not
  // finite, std::runtime_error on an Embree device error. An empty soup is valid (every ray misses).
  explicit Raycaster(const world::TriangleSoup& soup);
  ~Raycaster();
  Raycaster(const Raycaster&) = delete;
  Raycaster& operator=(const Raycaster&) = delete;

  std::size_t NumTriangles() const;
  // Instance id of a soup triangle.
  std::int32_t TriangleInstance(std::uint32_t triangle) const;

  // Casts every ray of the batch; hits are resized to batch.size(). Blocks of rays are spread over
  // `threads` threads (0 = hardware concurrency) with results independent of the thread count.
  // Throws InputError on a malformed batch or a non-finite origin/direction.
  void Cast(const RayBatch& batch, std::vector<RayHit>* hits, int threads = 1) const;

  // Low-level form for callers with their own buffers (no allocation, one thread): `count` rays,
  // origins either one per ray or one shared (shared_origin). Same checks as above.
  void Cast(const float* origins_xyz, bool shared_origin, const float* directions_xyz, std::size_t count,
            float t_min, float t_max, RayHit* hits) const;

  // One ray (direction need not be unit).
  RayHit CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min = 0.0,
                 double t_max = std::numeric_limits<double>::infinity()) const;

  // Line of sight: true when geometry blocks the segment from `from` to `to`, ignoring hits within
  // end_margin_m of either end (so a segment ending on a surface is not blocked by that surface).
  bool SegmentBlocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double end_margin_m = 1e-3) const;
  // Batched form: `count` segments as flat xyz arrays; blocked[i] is 1 or 0.
  void SegmentsBlocked(const float* from_xyz, const float* to_xyz, std::size_t count, double end_margin_m,
                       std::uint8_t* blocked) const;

  // Shoots `num_directions` rays (Fibonacci sphere) from `point` up to max_distance_m.
  PointProbe Probe(const Eigen::Vector3d& point, int num_directions = 128, double max_distance_m = 100.0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace objscan::render
