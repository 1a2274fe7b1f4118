// `objscan scene`: load a scene, print its objects, draw a top view or export its mesh.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_util.h"
#include "commands.h"
#include "objscan/io/category_labels.h"
#include "objscan/io/ply.h"
#include "objscan/io/scene_spec.h"
#include "objscan/io/topview.h"

namespace objscan::app {
namespace {

struct SceneArgs {
  std::string scene;
  bool info = false;
  std::string topview;
  std::string export_ply;
  int allow_missing = 0;  // times given
  std::vector<std::string> model_path;
  std::string category_map;
  bool doors_open = false;
};

using Json = nlohmann::ordered_json;

// Micrometre resolution keeps the JSON readable.
double Round6(double v) { return std::round(v * 1e6) / 1e6; }
Json Vec(const Eigen::Vector3d& v) { return Json::array({Round6(v.x()), Round6(v.y()), Round6(v.z())}); }

Json SceneInfo(const world::Scene& scene) {
  Json objects = Json::array();
  for (const auto& o : scene.objects()) {
    const geometry::Aabb3 box = scene.ObjectBounds(o);
    objects.push_back({{"id", o.instance_id},
                       {"name", o.name},
                       {"category", world::CategoryName(o.category)},
                       {"model", o.model_name},
                       {"aabb_min", Vec(box.min_m)},
                       {"aabb_max", Vec(box.max_m)},
                       {"triangles", o.mesh.NumTriangles()}});
  }
  const geometry::Aabb3 bounds = scene.Bounds();
  const geometry::Aabb3 furniture = scene.FurnitureBounds();
  Json info;
  info["scene"] = scene.name();
  info["objects"] = objects;
  info["bounds"] = {{"min", Vec(bounds.min_m)}, {"max", Vec(bounds.max_m)}};
  if (!furniture.Empty()) info["furniture_bounds"] = {{"min", Vec(furniture.min_m)}, {"max", Vec(furniture.max_m)}};
  info["num_furniture"] = scene.NumFurniture();
  info["num_triangles"] = scene.NumTriangles();
  info["missing_meshes"] = scene.missing_meshes();
  info["unmapped_models"] = scene.unmapped_models();
  // "inferred": the loader grouped the objects itself (a ScanNet scan without its aggregation), so
  // ground truth and every metric rest on that guess.
  info["instances"] = scene.instances_inferred() ? "inferred" : "annotated";
  info["load_notes"] = scene.load_notes();
  return info;
}

// The scene mesh in the world frame; vertices are not shared between objects, so each carries its
// object's instance and category ids (and the category colour, `label` and `instance` for viewers).
io::PlyData SceneMesh(const world::Scene& scene) {
  io::PlyData ply;
  std::vector<std::int32_t> instance_ids, category_ids;
  for (const auto& o : scene.objects()) {
    const int offset = static_cast<int>(ply.points.size());
    for (const auto& v : o.mesh.vertices) {
      ply.points.push_back((o.T_world_object * v.cast<double>()).cast<float>());
      instance_ids.push_back(o.instance_id);
      category_ids.push_back(world::CategoryId(o.category));
    }
    for (const auto& t : o.mesh.triangles) ply.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  ply.int_properties.emplace_back("instance_id", instance_ids);
  ply.int_properties.emplace_back("category_id", category_ids);
  // `label` and `instance` and the category names, as in a run's PLY files.
  io::AddCategoryLabels(category_ids, &instance_ids, /*colour_by_category=*/true, &ply);
  return ply;
}

int RunScene(const SceneArgs& args) {
  io::SceneLoadOptions options;
  const AllowMissing allow_missing = AllowMissingFromCount(args.allow_missing);
  options.allow_missing = allow_missing.allow;
  if (allow_missing.insist) options.min_loaded_model_fraction = 0.0;
  options.model_path = JoinModelPath(args.model_path);
  options.doors_open = args.doors_open;
  if (!args.category_map.empty()) options.category_map = args.category_map;
  const world::Scene scene = io::LoadScene(args.scene, options);
  if (!args.topview.empty()) io::RenderTopView(scene, io::TopViewOptions()).canvas.SavePng(args.topview);
  if (!args.export_ply.empty()) io::WritePly(args.export_ply, SceneMesh(scene));
  if (args.info) {
    std::printf("%s\n", SceneInfo(scene).dump(2).c_str());
  } else if (args.topview.empty() && args.export_ply.empty()) {
    // Nothing asked for: a one-line summary.
    std::printf("%s: %zu objects (%zu furniture), %zu triangles, %zu missing meshes\n", scene.name().c_str(),
                scene.objects().size(), scene.NumFurniture(), scene.NumTriangles(), scene.missing_meshes().size());
  }
  if (!scene.missing_meshes().empty()) {
    std::fprintf(stderr, "objscan scene: warning: %zu meshes could not be loaded (listed in --info)\n",
                 scene.missing_meshes().size());
  }
  if (scene.instances_inferred()) {
    std::fprintf(stderr, "objscan scene: note: object instances were inferred, not read from the scan (see --info)\n");
  }
  if (!scene.unmapped_models().empty()) {
    std::fprintf(stderr, "objscan scene: warning: %zu models have no category in the category map (`other`, listed in --info)\n",
                 scene.unmapped_models().size());
  }
  return 0;
}

}  // namespace

void AddSceneCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<SceneArgs>();
  auto* cmd = root.add_subcommand("scene", "Load a scene, print its objects, draw a top view or export its mesh");
  cmd->add_option("--scene", args->scene,
                  "scene SPEC: .world, .yaml/.json scene file, ScanNet scan folder or *_vh_clean_2.ply, mesh, or procedural:CATEGORY:SEED")
      ->required();
  cmd->add_flag("--info", args->info, "print objects and bounds as JSON on stdout");
  cmd->add_option("--topview", args->topview, "write a top view PNG (objects coloured by category, legend)");
  cmd->add_option("--export", args->export_ply,
                  "write the scene mesh as PLY with per-vertex instance_id and category_id");
  AddAllowMissingFlag(cmd, &args->allow_missing,
                      "load what can be loaded and list unresolved meshes in missing_meshes instead of failing");
  AddModelPathOption(cmd, &args->model_path, "");
  cmd->add_flag("--doors-open", args->doors_open,
                "treat doors as open: remove every object of category door (scene.doors_open)");
  cmd->add_option("--category-map", args->category_map,
                  "category map YAML (default: config/categories/default.yaml; see docs/real-inputs.md)");
  cmd->callback([run, args] { *run = [args] { return RunScene(*args); }; });
}

}  // namespace objscan::app
