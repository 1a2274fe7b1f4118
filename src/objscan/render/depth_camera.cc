#include "objscan/render/depth_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "objscan/common/error.h"
#include "objscan/render/depth_noise.h"
#include "objscan/common/parallel_for.h"

namespace objscan::render {
namespace {

// Rays are traced in 4x4 pixel tiles (one 16-ray packet each) over bands of this many rows.
constexpr int kTile = 4;
// Rows per block of the noise pass.
constexpr int kNoiseRows = 8;

bool PoseFinite(const geometry::Pose3& T) { return T.matrix().allFinite(); }

}  // namespace

platform::CameraIntrinsics SensorOptions::Intrinsics() const {
  platform::CameraIntrinsics k;
  k.width_px = width_px;
  k.height_px = height_px;
  k.fx_px = fx_px;
  k.fy_px = fy_px;
  k.cx_px = cx_px;
  k.cy_px = cy_px;
  k.min_range_m = min_range_m;
  k.max_range_m = max_range_m;
  return k;
}

void SensorOptions::Validate() const {
  config::RequireInRange("width_px", width_px, 1, 16384);
  config::RequireInRange("height_px", height_px, 1, 16384);
  config::RequirePositive("fx_px", fx_px);
  config::RequirePositive("fy_px", fy_px);
  config::Require(std::isfinite(cx_px), "cx_px", "must be finite");
  config::Require(std::isfinite(cy_px), "cy_px", "must be finite");
  config::RequirePositive("min_range_m", min_range_m);
  config::Require(max_range_m > min_range_m, "max_range_m", "must be greater than min_range_m");
  config::RequireNonNegative("noise_sigma_base_m", noise_sigma_base_m);
  config::RequireNonNegative("noise_sigma_quadratic_per_m", noise_sigma_quadratic_per_m);
  config::Require(std::isfinite(noise_sigma_offset_m), "noise_sigma_offset_m", "must be finite");
  config::RequirePositive("baseline_m", baseline_m);
  config::RequireNonNegative("disparity_step_px", disparity_step_px);
  config::RequireInRange("grazing_dropout_deg", grazing_dropout_deg, 0.0, 90.0);
  config::RequireNonNegative("edge_dropout_jump_m", edge_dropout_jump_m);
  config::RequireNonNegative("threads", threads);
}

struct DepthCamera::Impl {
  Impl(const world::Scene& scene, const SensorOptions& options)
      : raycaster(scene.BuildTriangleSoup()), noise(options) {
    column_x.resize(options.width_px);
    row_y.resize(options.height_px);
    for (int u = 0; u < options.width_px; ++u) column_x[u] = (u - options.cx_px) / options.fx_px;
    for (int v = 0; v < options.height_px; ++v) row_y[v] = (v - options.cy_px) / options.fy_px;
    const std::size_t n = static_cast<std::size_t>(options.width_px) * options.height_px;
    pixel_phase.resize(n);
    for (std::size_t i = 0; i < n; ++i) pixel_phase[i] = static_cast<float>(DepthNoiseModel::PixelPhase(i));
  }

  Raycaster raycaster;
  DepthNoiseModel noise;
  // Cached inverse intrinsics: the camera-frame ray of pixel (u, v) is (column_x[u], row_y[v], 1).
  std::vector<double> column_x, row_y;
  std::vector<float> pixel_phase;  // fixed disparity-grid phase per pixel (see depth_noise.h)
};

DepthCamera::DepthCamera(const world::Scene& scene, const SensorOptions& options) : options_(options) {
  options_.Validate();
  if (scene.NumTriangles() == 0) {
    throw InputError("scene '" + scene.name() + "': no triangles to render");
  }
  impl_ = std::make_unique<Impl>(scene, options_);
}

DepthCamera::~DepthCamera() = default;

const Raycaster& DepthCamera::raycaster() const { return impl_->raycaster; }

platform::DepthFrame DepthCamera::Render(const geometry::Pose3& T_world_camera, Rng* rng) const {
  if (!PoseFinite(T_world_camera)) throw InputError("depth camera: T_world_camera is not finite");
  if (options_.noise && rng == nullptr) throw InputError("depth camera: noise is on but no Rng was given");
  const int width = options_.width_px;
  const int height = options_.height_px;
  const std::size_t num_pixels = static_cast<std::size_t>(width) * height;

  platform::DepthFrame frame;
  frame.intrinsics = options_.Intrinsics();
  frame.T_world_camera = T_world_camera;
  frame.depth_m.assign(num_pixels, 0.f);
  frame.gt_instance.assign(num_pixels, world::kNoInstance);
  frame.gt_normal_world.assign(num_pixels, Eigen::Vector3f::Zero());

  const Eigen::Matrix3d R = T_world_camera.linear();
  const Eigen::Vector3d origin = T_world_camera.translation();
  const float origin_xyz[3] = {float(origin.x()), float(origin.y()), float(origin.z())};
  const Impl& impl = *impl_;
  // World direction of pixel (u, v) with camera-frame z = 1, so the hit distance is the depth z.
  auto direction = [&](int u, int v) -> Eigen::Vector3d {
    return R.col(0) * impl.column_x[u] + R.col(1) * impl.row_y[v] + R.col(2);
  };

  // Pass 1: ray cast bands of kTile rows, 4x4 tiles per packet.
  std::vector<float> hit_distance(num_pixels, std::numeric_limits<float>::infinity());
  const int num_bands = (height + kTile - 1) / kTile;
  ParallelForBlocks(num_bands, options_.threads, [&](int band) {
    const int v0 = band * kTile;
    const int rows = std::min(kTile, height - v0);
    std::vector<float> directions;
    std::vector<std::uint32_t> pixels;
    directions.reserve(3 * static_cast<std::size_t>(kTile) * (width + kTile));
    pixels.reserve(static_cast<std::size_t>(kTile) * (width + kTile));
    for (int u0 = 0; u0 < width; u0 += kTile) {
      for (int dv = 0; dv < rows; ++dv) {
        for (int du = 0; du < kTile && u0 + du < width; ++du) {
          const Eigen::Vector3d d = direction(u0 + du, v0 + dv);
          directions.push_back(static_cast<float>(d.x()));
          directions.push_back(static_cast<float>(d.y()));
          directions.push_back(static_cast<float>(d.z()));
          pixels.push_back(static_cast<std::uint32_t>((v0 + dv) * width + u0 + du));
        }
      }
    }
    std::vector<RayHit> hits(pixels.size());
    impl.raycaster.Cast(origin_xyz, true, directions.data(), pixels.size(), 0.f,
                        std::numeric_limits<float>::infinity(), hits.data());
    for (std::size_t k = 0; k < pixels.size(); ++k) {
      const std::uint32_t i = pixels[k];
      if (!hits[k].Hit()) continue;
      hit_distance[i] = hits[k].distance;
      frame.gt_instance[i] = hits[k].instance_id;
      frame.gt_normal_world[i] = hits[k].normal_world;
    }
  });

  // Pass 2: range, dropouts and noise per row; each row draws from its own stream so the result does
  // not depend on how rows are spread over threads.
  const std::uint64_t frame_seed = options_.noise ? (*rng)() : 0;
  const double min_range = options_.min_range_m;
  const double max_range = options_.max_range_m;
  const double cos_grazing = std::cos(geometry::DegToRad(options_.grazing_dropout_deg));
  const double cos2_grazing = cos_grazing * cos_grazing;
  const double edge_jump = options_.edge_dropout_jump_m;
  const int num_noise_blocks = (height + kNoiseRows - 1) / kNoiseRows;
  ParallelForBlocks(num_noise_blocks, options_.threads, [&](int block) {
    const int v_end = std::min(height, (block + 1) * kNoiseRows);
    for (int v = block * kNoiseRows; v < v_end; ++v) {
      Rng row_rng(DeriveSeed(frame_seed, static_cast<std::uint64_t>(v)));
      for (int u = 0; u < width; ++u) {
        const std::size_t i = static_cast<std::size_t>(v) * width + u;
        const double t = hit_distance[i];
        bool valid = frame.gt_instance[i] != world::kNoInstance && t >= min_range && t <= max_range;
        double z = t;
        if (valid) {
          const Eigen::Vector3d d = direction(u, v);
          Eigen::Vector3f& n = frame.gt_normal_world[i];
          const double n_dot_d = n.cast<double>().dot(d);
          // The ground-truth normal faces the camera (mesh windings are not reliable).
          if (n_dot_d > 0.0) n = -n;
          if (options_.noise) {
            // Grazing incidence: the projected pattern is too stretched to match (compared squared:
            // no square root per pixel).
            if (n_dot_d * n_dot_d < cos2_grazing * d.squaredNorm()) valid = false;
            // Depth discontinuity to any 4-neighbour (misses count as infinitely far).
            if (valid && edge_jump > 0.0) {
              const double jump = edge_jump * t;
              const float neighbours[4] = {u > 0 ? hit_distance[i - 1] : hit_distance[i],
                                           u + 1 < width ? hit_distance[i + 1] : hit_distance[i],
                                           v > 0 ? hit_distance[i - width] : hit_distance[i],
                                           v + 1 < height ? hit_distance[i + width] : hit_distance[i]};
              for (float tn : neighbours) {
                if (!(std::abs(static_cast<double>(tn) - t) <= jump)) valid = false;
              }
            }
            if (valid) {
              z = impl.noise.Measure(t, impl.pixel_phase[i], row_rng);
              if (!(z >= min_range && z <= max_range)) valid = false;
            }
          }
        }
        if (valid) {
          frame.depth_m[i] = static_cast<float>(z);
        } else {
          frame.gt_instance[i] = world::kNoInstance;
          frame.gt_normal_world[i].setZero();
        }
      }
    }
  });
  return frame;
}

}  // namespace objscan::render
