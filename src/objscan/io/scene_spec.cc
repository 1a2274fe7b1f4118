#include "objscan/io/scene_spec.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "objscan/common/error.h"
#include "objscan/io/category_map.h"
#include "objscan/io/gazebo_world.h"
#include "objscan/io/mesh_io.h"
#include "objscan/io/scannet.h"
#include "objscan/io/scene_file.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

constexpr double kMeshFloorMarginM = 1.0;

world::Scene LoadProcedural(const std::string& spec) {
  // procedural:CATEGORY:SEED
  const std::string rest = spec.substr(std::string("procedural:").size());
  const auto colon = rest.find(':');
  if (colon == std::string::npos) {
    throw InputError("scene '" + spec + "': expected procedural:CATEGORY:SEED (e.g. procedural:bedroom:1)");
  }
  const std::string category = rest.substr(0, colon);
  const std::string seed_text = rest.substr(colon + 1);
  if (seed_text.empty() || seed_text.size() > 19 ||
      !std::all_of(seed_text.begin(), seed_text.end(), [](unsigned char c) { return std::isdigit(c); })) {
    throw InputError("scene '" + spec + "': seed '" + seed_text + "' is not a non-negative integer");
  }
  const auto& categories = world::procedural::RoomCategories();
  if (std::find(categories.begin(), categories.end(), category) == categories.end()) {
    std::string known;
    for (const auto& c : categories) known += (known.empty() ? "" : ", ") + c;
    throw InputError("scene '" + spec + "': unknown room category '" + category + "' (one of " + known + ")");
  }
  world::Scene scene = world::procedural::GenerateRoom(category, std::stoull(seed_text));
  if (scene.name().empty()) scene.set_name(spec);
  return scene;
}

world::Scene LoadMeshScene(const std::string& path) {
  world::SceneObject object;
  object.category = world::Category::kOther;
  object.mesh = LoadMesh(path);
  object.model_name = fs::path(path).stem().string();
  object.name = object.model_name;
  const geometry::Aabb3 box = geometry::Bounds(object.mesh);
  // The floor goes under the mesh's lowest point so that it rests on it.
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.name = "floor";
  floor.model_name = "floor";
  floor.mesh = geometry::MakeQuadXY(box.min_m.x() - kMeshFloorMarginM, box.min_m.y() - kMeshFloorMarginM,
                                    box.max_m.x() + kMeshFloorMarginM, box.max_m.y() + kMeshFloorMarginM);
  for (auto& v : floor.mesh.vertices) v.z() = static_cast<float>(box.min_m.z());
  world::Scene scene(fs::path(path).filename().string());
  scene.Add(std::move(floor));
  scene.Add(std::move(object));
  return scene;
}

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

world::Scene LoadSceneFormat(const std::string& spec, const SceneLoadOptions& options) {
  options.Validate();
  if (spec.rfind("procedural:", 0) == 0) return LoadProcedural(spec);
  const std::string ext = LowerExtension(spec);
  std::error_code ec;
  if (!fs::exists(spec, ec)) {
    throw InputError(spec + ": no such file (a scene is a .world, .yaml/.json, ScanNet scan, mesh file or procedural:CATEGORY:SEED)");
  }
  if (ext == ".world" || ext == ".sdf") return LoadGazeboWorld(spec, options);
  if (ext == ".yaml" || ext == ".yml" || ext == ".json") return LoadSceneFile(spec);
  if (IsScanNetSpec(spec)) {
    const CategoryMap categories = CategoryMap::Load(ResolveCategoryMapPath(options.category_map));
    return LoadScanNetScan(spec, options, categories);
  }
  if (IsMeshFile(spec)) return LoadMeshScene(spec);
  throw InputError(spec + ": unsupported scene format '" + ext +
                   "' (expected .world, .yaml/.json, a ScanNet scan folder or *_vh_clean_2.ply, "
                   "obj/ply/off/dae/stl/gltf/glb or procedural:CATEGORY:SEED)");
}

// Every loader's result passes here: a scene beyond kMaxSceneCoordinate_m is refused, naming the object
// (furniture first: a generated floor or wall only follows it).
world::Scene WithinReach(world::Scene scene, const std::string& spec) {
  for (const bool structural : {false, true}) {
    for (const world::SceneObject& object : scene.objects()) {
      if (object.IsStructural() != structural) continue;
      const geometry::Aabb3 box = scene.ObjectBounds(object);
      if (box.Empty()) continue;
      const double reach = std::max(box.min_m.cwiseAbs().maxCoeff(), box.max_m.cwiseAbs().maxCoeff());
      if (!(reach <= world::kMaxSceneCoordinate_m)) {
        throw InputError(spec + ": object '" + object.name + "' lies beyond " +
                         std::to_string(static_cast<int>(world::kMaxSceneCoordinate_m)) +
                         " m of the origin (not a room or a house)");
      }
    }
  }
  return scene;
}

}  // namespace

void SceneLoadOptions::Validate() const {
  if (category_map.empty()) throw ConfigError("scene.category_map: must name a category map file");
  config::RequirePositive("scene.max_extent_m", max_extent_m);
  config::Require(max_triangles >= 1, "scene.max_triangles", "must be at least 1");
  config::RequireInRange("scene.min_loaded_model_fraction", min_loaded_model_fraction, 0.0, 1.0);
}

void OpenDoors(world::Scene* scene) {
  std::vector<world::SceneObject>& objects = scene->mutable_objects();
  std::string names;
  std::size_t removed = 0;
  for (const auto& o : objects) {
    if (o.category != world::Category::kDoor) continue;
    names += (removed++ == 0 ? "" : ", ") + o.name;
  }
  if (removed == 0) {
    scene->load_notes().push_back("doors open: the scene has no door");
    return;
  }
  objects.erase(std::remove_if(objects.begin(), objects.end(),
                               [](const world::SceneObject& o) { return o.category == world::Category::kDoor; }),
                objects.end());
  scene->load_notes().push_back("doors open: " + std::to_string(removed) + " door" + (removed == 1 ? "" : "s") +
                                " removed (" + names + ")");
}

world::Scene LoadScene(const std::string& spec, const SceneLoadOptions& options) {
  world::Scene scene = LoadSceneAsWritten(spec, options);
  if (options.doors_open) OpenDoors(&scene);
  return scene;
}

world::Scene LoadSceneAsWritten(const std::string& spec, const SceneLoadOptions& options) {
  return WithinReach(LoadSceneFormat(spec, options), spec);
}

}  // namespace objscan::io
