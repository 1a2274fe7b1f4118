#include "objscan/render/raycaster.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "objscan/common/error.h"
#include "objscan/common/parallel_for.h"

namespace objscan::render {
namespace {

constexpr int kPacket = 16;
// Rays per work block of the threaded Cast: a multiple of the packet size, large enough to amortise
// the hand-out, small enough to balance.
constexpr std::size_t kBlockRays = 64 * kPacket;

bool Finite3(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void CheckRange(float t_min, float t_max) {
  if (!(t_min >= 0.f) || !(t_max >= t_min)) {
    throw InputError("ray batch: need 0 <= t_min <= t_max (got t_min " + std::to_string(t_min) + ", t_max " +
                     std::to_string(t_max) + ")");
  }
}

}  // namespace

struct Raycaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::int32_t> triangle_instance;
  std::vector<float> triangle_normals;  // 3 per triangle, unit (zero for degenerate triangles)

  std::mutex error_mutex;
  std::string first_error;

  static void OnError(void* user, RTCError code, const char* message) {
    auto* self = static_cast<Impl*>(user);
    std::lock_guard<std::mutex> lock(self->error_mutex);
    if (self->first_error.empty()) {
      self->first_error = "embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
    }
  }
  // Throws when Embree reported an error (from the callback or this thread's error code).
  void ThrowOnDeviceError(const char* where) {
    const RTCError code = rtcGetDeviceError(device);
    std::lock_guard<std::mutex> lock(error_mutex);
    if (!first_error.empty() || code != RTC_ERROR_NONE) {
      std::string message = first_error.empty() ? "embree error " + std::to_string(static_cast<int>(code)) : first_error;
      throw std::runtime_error(std::string("raycaster: ") + where + ": " + message);
    }
  }

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // Packets of 16 consecutive rays; see Raycaster::Cast.
  void CastRange(const float* origins_xyz, bool shared_origin, const float* directions_xyz, std::size_t count,
                 float t_min, float t_max, RayHit* hits) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RTCRayHit16 packet;
    alignas(64) int valid[kPacket];
    for (std::size_t base = 0; base < count; base += kPacket) {
      const int n = static_cast<int>(std::min<std::size_t>(kPacket, count - base));
      for (int i = 0; i < kPacket; ++i) {
        const std::size_t r = base + std::min(i, n - 1);  // padding lanes repeat the last ray, masked off
        const float* o = shared_origin ? origins_xyz : origins_xyz + 3 * r;
        const float* d = directions_xyz + 3 * r;
        if (i < n && !(Finite3(o) && Finite3(d))) {
          throw InputError("ray " + std::to_string(r) + ": origin and direction must be finite");
        }
        valid[i] = i < n ? -1 : 0;
        packet.ray.org_x[i] = o[0];
        packet.ray.org_y[i] = o[1];
        packet.ray.org_z[i] = o[2];
        packet.ray.dir_x[i] = d[0];
        packet.ray.dir_y[i] = d[1];
        packet.ray.dir_z[i] = d[2];
        packet.ray.tnear[i] = t_min;
        packet.ray.tfar[i] = t_max;
        packet.ray.time[i] = 0.f;
        packet.ray.mask[i] = ~0u;
        packet.ray.id[i] = static_cast<unsigned>(i);
        packet.ray.flags[i] = 0;
        packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene, &context, &packet);
      for (int i = 0; i < n; ++i) {
        RayHit& h = hits[base + i];
        if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
          h = RayHit();
          continue;
        }
        const unsigned prim = packet.hit.primID[i];
        h.distance = packet.ray.tfar[i];
        h.instance_id = triangle_instance[prim];
        h.triangle = prim;
        h.normal_world = Eigen::Vector3f(triangle_normals[3 * prim], triangle_normals[3 * prim + 1],
                                         triangle_normals[3 * prim + 2]);
      }
    }
  }

  void OccludedRange(const float* from_xyz, const float* to_xyz, std::size_t count, double end_margin_m,
                     std::uint8_t* blocked) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(64) RTCRay16 packet;
    alignas(64) int valid[kPacket];
    for (std::size_t base = 0; base < count; base += kPacket) {
      const int n = static_cast<int>(std::min<std::size_t>(kPacket, count - base));
      for (int i = 0; i < kPacket; ++i) {
        // Every lane holds a well-formed ray, also the inactive ones: Embree's hybrid kernels may
        // check lanes beyond the valid mask (an assertion in Debian's build).
        valid[i] = 0;
        packet.org_x[i] = packet.org_y[i] = packet.org_z[i] = 0.f;
        packet.dir_x[i] = 1.f;
        packet.dir_y[i] = packet.dir_z[i] = 0.f;
        packet.tnear[i] = 0.f;
        packet.tfar[i] = 0.f;
        packet.time[i] = 0.f;
        packet.mask[i] = ~0u;
        packet.id[i] = static_cast<unsigned>(i);
        packet.flags[i] = 0;
        if (i >= n) continue;
        const float* a = from_xyz + 3 * (base + i);
        const float* b = to_xyz + 3 * (base + i);
        if (!(Finite3(a) && Finite3(b))) {
          throw InputError("segment " + std::to_string(base + i) + ": end points must be finite");
        }
        const double dx = double(b[0]) - a[0], dy = double(b[1]) - a[1], dz = double(b[2]) - a[2];
        const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (length <= 2.0 * end_margin_m) {
          blocked[base + i] = 0;  // nothing left between the margins
          continue;
        }
        valid[i] = -1;
        packet.org_x[i] = a[0];
        packet.org_y[i] = a[1];
        packet.org_z[i] = a[2];
        packet.dir_x[i] = static_cast<float>(dx);
        packet.dir_y[i] = static_cast<float>(dy);
        packet.dir_z[i] = static_cast<float>(dz);
        packet.tnear[i] = static_cast<float>(end_margin_m / length);
        packet.tfar[i] = static_cast<float>(1.0 - end_margin_m / length);
        packet.time[i] = 0.f;
        packet.mask[i] = ~0u;
        packet.id[i] = static_cast<unsigned>(i);
        packet.flags[i] = 0;
      }
      rtcOccluded16(valid, scene, &context, &packet);
      for (int i = 0; i < n; ++i) {
        // Embree sets tfar to -inf for an occluded ray.
        if (valid[i]) blocked[base + i] = packet.tfar[i] < 0.f ? 1 : 0;
      }
    }
  }
};

Raycaster::Raycaster(const world::TriangleSoup& soup) : impl_(std::make_unique<Impl>()) {
  const std::size_t num_vertices = soup.vertices_xyz.size() / 3;
  const std::size_t num_triangles = soup.NumTriangles();
  if (soup.vertices_xyz.size() % 3 != 0 || soup.triangles.size() != 3 * num_triangles) {
    throw InputError("triangle soup: vertex or index array has the wrong length");
  }
  for (std::size_t i = 0; i < num_vertices; ++i) {
    if (!Finite3(&soup.vertices_xyz[3 * i])) {
      throw InputError("triangle soup: vertex " + std::to_string(i) + " is not finite");
    }
  }
  impl_->triangle_instance = soup.triangle_instance;
  impl_->triangle_normals.resize(3 * num_triangles, 0.f);
  for (std::size_t t = 0; t < num_triangles; ++t) {
    std::uint32_t idx[3];
    for (int k = 0; k < 3; ++k) {
      idx[k] = soup.triangles[3 * t + k];
      if (idx[k] >= num_vertices) {
        throw InputError("triangle soup: triangle " + std::to_string(t) + " has vertex index " +
                         std::to_string(idx[k]) + " out of range");
      }
    }
    if (soup.triangle_instance[t] <= world::kNoInstance) {
      throw InputError("triangle soup: triangle " + std::to_string(t) + " has instance id " +
                       std::to_string(soup.triangle_instance[t]) + " (must be > 0)");
    }
    auto vertex = [&](int k) {
      return Eigen::Vector3d(soup.vertices_xyz[3 * idx[k]], soup.vertices_xyz[3 * idx[k] + 1],
                             soup.vertices_xyz[3 * idx[k] + 2]);
    };
    const Eigen::Vector3d n = (vertex(1) - vertex(0)).cross(vertex(2) - vertex(0));
    const double length = n.norm();
    if (length > 0.0) {
      for (int k = 0; k < 3; ++k) impl_->triangle_normals[3 * t + k] = static_cast<float>(n[k] / length);
    }
  }

  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) {
    throw std::runtime_error("raycaster: cannot create the Embree device (error " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(impl_->device, &Impl::OnError, impl_.get());
  impl_->scene = rtcNewScene(impl_->device);
  // Robust traversal: no rays slipping through shared triangle edges (a hole in a depth image is a
  // wrong measurement). High quality BVH: built once, traced millions of times.
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  if (num_triangles > 0) {
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float), num_vertices));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(unsigned), num_triangles));
    impl_->ThrowOnDeviceError("allocating geometry buffers");
    std::copy(soup.vertices_xyz.begin(), soup.vertices_xyz.end(), vertices);
    std::copy(soup.triangles.begin(), soup.triangles.end(), indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(impl_->scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(impl_->scene);
  impl_->ThrowOnDeviceError("building the scene");
}

Raycaster::~Raycaster() = default;

std::size_t Raycaster::NumTriangles() const { return impl_->triangle_instance.size(); }

std::int32_t Raycaster::TriangleInstance(std::uint32_t triangle) const {
  return triangle < impl_->triangle_instance.size() ? impl_->triangle_instance[triangle] : world::kNoInstance;
}

void Raycaster::Cast(const float* origins_xyz, bool shared_origin, const float* directions_xyz, std::size_t count,
                     float t_min, float t_max, RayHit* hits) const {
  CheckRange(t_min, t_max);
  impl_->CastRange(origins_xyz, shared_origin, directions_xyz, count, t_min, t_max, hits);
  impl_->ThrowOnDeviceError("intersecting rays");
}

void Raycaster::Cast(const RayBatch& batch, std::vector<RayHit>* hits, int threads) const {
  const std::size_t count = batch.size();
  if (batch.directions_xyz.size() % 3 != 0) throw InputError("ray batch: directions_xyz length is not a multiple of 3");
  const bool shared_origin = batch.origins_xyz.size() == 3;
  if (!shared_origin && batch.origins_xyz.size() != batch.directions_xyz.size()) {
    throw InputError("ray batch: need 3 origin floats per ray or exactly 3 for a shared origin (got " +
                     std::to_string(batch.origins_xyz.size()) + " for " + std::to_string(count) + " rays)");
  }
  CheckRange(batch.t_min, batch.t_max);
  hits->resize(count);
  if (count == 0) return;
  const int num_blocks = static_cast<int>((count + kBlockRays - 1) / kBlockRays);
  ParallelForBlocks(num_blocks, threads, [&](int block) {
    const std::size_t begin = static_cast<std::size_t>(block) * kBlockRays;
    const std::size_t n = std::min(kBlockRays, count - begin);
    const float* origins = shared_origin ? batch.origins_xyz.data() : batch.origins_xyz.data() + 3 * begin;
    impl_->CastRange(origins, shared_origin, batch.directions_xyz.data() + 3 * begin, n, batch.t_min, batch.t_max,
                     hits->data() + begin);
  });
  impl_->ThrowOnDeviceError("intersecting rays");
}

RayHit Raycaster::CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min,
                          double t_max) const {
  const float o[3] = {float(origin.x()), float(origin.y()), float(origin.z())};
  const float d[3] = {float(direction.x()), float(direction.y()), float(direction.z())};
  RayHit hit;
  Cast(o, true, d, 1, static_cast<float>(t_min), static_cast<float>(t_max), &hit);
  return hit;
}

bool Raycaster::SegmentBlocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double end_margin_m) const {
  const float a[3] = {float(from.x()), float(from.y()), float(from.z())};
  const float b[3] = {float(to.x()), float(to.y()), float(to.z())};
  std::uint8_t blocked = 0;
  SegmentsBlocked(a, b, 1, end_margin_m, &blocked);
  return blocked != 0;
}

void Raycaster::SegmentsBlocked(const float* from_xyz, const float* to_xyz, std::size_t count, double end_margin_m,
                                std::uint8_t* blocked) const {
  if (!(end_margin_m >= 0.0)) throw InputError("segment query: end_margin_m must be >= 0");
  impl_->OccludedRange(from_xyz, to_xyz, count, end_margin_m, blocked);
  impl_->ThrowOnDeviceError("occlusion query");
}

std::vector<Eigen::Vector3f> FibonacciDirections(int n) {
  std::vector<Eigen::Vector3f> directions;
  if (n < 1) return directions;
  directions.reserve(static_cast<std::size_t>(n));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    directions.emplace_back(static_cast<float>(r * std::cos(golden_angle * i)),
                            static_cast<float>(r * std::sin(golden_angle * i)), static_cast<float>(z));
  }
  return directions;
}

PointProbe Raycaster::Probe(const Eigen::Vector3d& point, int num_directions, double max_distance_m) const {
  if (num_directions < 1) throw InputError("probe: num_directions must be >= 1");
  std::vector<float> directions;
  directions.reserve(3 * static_cast<std::size_t>(num_directions));
  for (const Eigen::Vector3f& d : FibonacciDirections(num_directions)) directions.insert(directions.end(), {d.x(), d.y(), d.z()});
  const float origin[3] = {float(point.x()), float(point.y()), float(point.z())};
  std::vector<RayHit> hits(num_directions);
  Cast(origin, true, directions.data(), hits.size(), 0.f, static_cast<float>(max_distance_m), hits.data());
  PointProbe probe;
  int num_hits = 0, num_back = 0;
  for (int i = 0; i < num_directions; ++i) {
    if (!hits[i].Hit()) continue;
    ++num_hits;
    probe.clearance_m = std::min(probe.clearance_m, static_cast<double>(hits[i].distance));
    const Eigen::Vector3f d(directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]);
    if (hits[i].normal_world.dot(d) > 0.f) ++num_back;
  }
  probe.hit_fraction = static_cast<double>(num_hits) / num_directions;
  probe.back_face_fraction = static_cast<double>(num_back) / num_directions;
  probe.inside = probe.hit_fraction >= 0.95 && probe.back_face_fraction > 0.5;
  return probe;
}

}  // namespace objscan::render
