// `objscan render`: render one depth frame of a scene from a camera pose and write depth.png (16-bit
// millimetres), instance.png (16-bit instance ids) and cloud.ply (world-frame points with instance
// ids); prints {"valid_pixels": ..., "ms": ...} on stdout.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_util.h"
#include "commands.h"
#include "objscan/common/error.h"
#include "objscan/common/timer.h"
#include "objscan/io/ply.h"
#include "objscan/io/png.h"
#include "objscan/io/scene_spec.h"
#include "objscan/render/depth_camera.h"

namespace objscan::app {
namespace {

struct RenderArgs {
  std::string scene;
  std::string pose;
  std::string out;
  std::string noise = "on";
  std::uint64_t seed = 1;
  int threads = 0;
  int allow_missing = 0;  // times given
  std::vector<std::string> model_path;
  bool doors_open = false;
  std::string category_map;
};

// A camera this close to a surface sees nothing sensible (and is most likely inside furniture).
constexpr double kMinClearanceM = 0.05;
// How far above the scene's top the camera may go.
constexpr double kHeadroomM = 0.5;

std::string Xyz(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.3f, %.3f, %.3f)", p.x(), p.y(), p.z());
  return text;
}

// The room's extent: walls and furniture when there are any (a loader's floor may reach far beyond).
geometry::Aabb3 SceneExtent(const world::Scene& scene) {
  geometry::Aabb3 extent;
  for (const auto& o : scene.objects()) {
    if (o.category != world::Category::kFloor) extent.Extend(scene.ObjectBounds(o));
  }
  return extent.Empty() ? scene.Bounds() : extent;
}

// Throws InputError when the camera is outside the scene, inside an object or touching a surface.
void CheckCameraPosition(const world::Scene& scene, const render::DepthCamera& camera, const Eigen::Vector3d& p,
                         const std::string& pose_text) {
  const geometry::Aabb3 extent = SceneExtent(scene);
  const geometry::Aabb3 all = scene.Bounds();
  const bool inside_xy = p.x() >= extent.min_m.x() && p.x() <= extent.max_m.x() && p.y() >= extent.min_m.y() &&
                         p.y() <= extent.max_m.y();
  const bool inside_z = p.z() >= all.min_m.z() && p.z() <= all.max_m.z() + kHeadroomM;
  if (!inside_xy || !inside_z) {
    throw InputError("--pose '" + pose_text + "': camera " + Xyz(p) + " is outside the scene (x " +
                     std::to_string(extent.min_m.x()) + ".." + std::to_string(extent.max_m.x()) + ", y " +
                     std::to_string(extent.min_m.y()) + ".." + std::to_string(extent.max_m.y()) + ", z " +
                     std::to_string(all.min_m.z()) + ".." + std::to_string(all.max_m.z() + kHeadroomM) + ")");
  }
  const render::PointProbe probe = camera.raycaster().Probe(p);
  if (probe.inside || probe.clearance_m < kMinClearanceM) {
    // Name the object: the nearest one along a few axis directions.
    std::string what = "geometry";
    float nearest = std::numeric_limits<float>::infinity();
    for (int axis = 0; axis < 6; ++axis) {
      const Eigen::Vector3d d = (axis % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(axis / 2);
      const render::RayHit hit = camera.raycaster().CastRay(p, d);
      if (hit.Hit() && hit.distance < nearest) {
        nearest = hit.distance;
        const world::SceneObject* o = scene.Find(hit.instance_id);
        what = o ? "object " + std::to_string(o->instance_id) + " '" + o->name + "' (" +
                       world::CategoryName(o->category) + ")"
                 : "geometry";
      }
    }
    throw InputError("--pose '" + pose_text + "': camera " + Xyz(p) +
                     (probe.inside ? " is inside " : " is within 5 cm of ") + what);
  }
}

int RunRender(const RenderArgs& args) {
  // Everything is checked before DIR or any file in it is created.
  const PoseArg pose = ParsePoseArg(args.pose, "--pose");
  if (args.noise != "on" && args.noise != "off") {
    throw InputError("--noise '" + args.noise + "': expected on or off");
  }
  if (args.threads < 0) throw InputError("--threads must be >= 0");
  if (std::filesystem::exists(args.out) && !std::filesystem::is_directory(args.out)) {
    throw InputError("--out '" + args.out + "': exists and is not a folder");
  }
  io::SceneLoadOptions load_options;
  const AllowMissing allow_missing = AllowMissingFromCount(args.allow_missing);
  load_options.allow_missing = allow_missing.allow;
  if (allow_missing.insist) load_options.min_loaded_model_fraction = 0.0;
  load_options.model_path = JoinModelPath(args.model_path);
  load_options.doors_open = args.doors_open;
  if (!args.category_map.empty()) load_options.category_map = args.category_map;
  const world::Scene scene = io::LoadScene(args.scene, load_options);

  render::SensorOptions sensor;
  sensor.noise = args.noise == "on";
  sensor.threads = args.threads;
  const render::DepthCamera camera(scene, sensor);
  const Eigen::Vector3d position(pose.x, pose.y, pose.z);
  CheckCameraPosition(scene, camera, position, args.pose);
  if (std::abs(pose.pitch_deg) >= 90.0) {
    throw InputError("--pose '" + args.pose + "': pitch_deg must be within (-90, 90)");
  }
  const geometry::Pose3 T_world_camera =
      geometry::CameraPoseFromYawPitch(position, geometry::DegToRad(pose.yaw_deg), geometry::DegToRad(pose.pitch_deg));

  Rng rng(args.seed);
  const Stopwatch render_time;
  const platform::DepthFrame frame = camera.Render(T_world_camera, &rng);
  const double ms = render_time.ElapsedMs();

  const int w = frame.width(), h = frame.height();
  std::vector<std::uint16_t> depth_mm(frame.depth_m.size()), instance(frame.gt_instance.size());
  io::PlyData cloud;
  std::vector<std::int32_t> cloud_instance;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const float d = frame.depth_m[i];
      depth_mm[i] = static_cast<std::uint16_t>(std::clamp(std::lround(1000.0 * d), 0l, 65535l));
      instance[i] = static_cast<std::uint16_t>(std::clamp(frame.gt_instance[i], 0, 65535));
      if (d > 0.f) {
        cloud.points.push_back(frame.PointWorld(u, v).cast<float>());
        cloud_instance.push_back(frame.gt_instance[i]);
      }
    }
  }
  cloud.int_properties.emplace_back("instance_id", std::move(cloud_instance));

  std::filesystem::create_directories(args.out);
  const std::filesystem::path dir(args.out);
  io::WritePng16((dir / "depth.png").string(), w, h, depth_mm);
  io::WritePng16((dir / "instance.png").string(), w, h, instance);
  io::WritePly((dir / "cloud.ply").string(), cloud);
  if (!scene.missing_meshes().empty()) {
    std::fprintf(stderr, "objscan render: warning: %zu meshes could not be loaded\n", scene.missing_meshes().size());
  }
  nlohmann::json result;
  result["valid_pixels"] = frame.NumValid();
  result["ms"] = std::round(ms * 1000.0) / 1000.0;
  std::printf("%s\n", result.dump().c_str());
  return 0;
}

}  // namespace

void AddRenderCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = root.add_subcommand("render", "Render one depth frame of a scene from a camera pose");
  cmd->add_option("--scene", args->scene, "scene SPEC: .world, .yaml/.json scene file, mesh, or procedural:CATEGORY:SEED")
      ->required();
  cmd->add_option("--pose", args->pose, "camera pose x,y,z,yaw_deg,pitch_deg (world frame, pitch > 0 looks up)")
      ->required();
  cmd->add_option("--out", args->out, "output folder for depth.png, instance.png, cloud.ply")->required();
  cmd->add_option("--noise", args->noise, "Kinect-style sensor noise: on or off")->default_str("on");
  cmd->add_option("--seed", args->seed, "noise seed")->default_str("1");
  cmd->add_option("--threads", args->threads, "render threads (0 = all cores; the image does not depend on it)")
      ->default_str("0");
  AddAllowMissingFlag(cmd, &args->allow_missing, "render what can be loaded when meshes are missing");
  AddModelPathOption(cmd, &args->model_path, "");
  cmd->add_flag("--doors-open", args->doors_open, "treat doors as open: remove every object of category door");
  cmd->add_option("--category-map", args->category_map, "category map YAML (instance categories of the render)");
  cmd->callback([run, args] { *run = [args] { return RunRender(*args); }; });
}

}  // namespace objscan::app
