#pragma once
// Loads a scene from a SPEC: a Gazebo .world file, an objscan scene file (.yaml/.json), a ScanNet scan
// (its folder or its *_vh_clean_2.ply; see scannet.h), a mesh file (obj, ply, off, dae, stl, gltf,
// glb: one object of category `other`), or procedural:CATEGORY:SEED.
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/world/scene.h"

namespace objscan::io {

struct SceneLoadOptions {
  // Extra folders searched for model:// URIs after the world's own folder (then $OBJSCAN_MODEL_PATH
  // and $GAZEBO_MODEL_PATH, colon-separated); their parents are searched for relative file:// URIs
  // (model_path.h).
  std::string model_path;
  // Load what can be loaded and list the rest in Scene::missing_meshes() instead of failing.
  bool allow_missing = false;
  // With allow_missing, a Gazebo world that keeps fewer than this share of its models (the others
  // lost all their meshes) is still an error: it is a wrong model path, and a run would scan an
  // empty room. 0 loads whatever is left.
  double min_loaded_model_fraction = 0.5;
  // Doors are open: every object of category `door` is removed (a scan of the whole house when the
  // world has its doors closed). Listed in Scene::load_notes().
  bool doors_open = false;
  // Category map of Gazebo worlds and ScanNet scans (category_map.h): a YAML file, as given when it
  // exists, else relative to the project's config/. The default knows SUNCG/OASC, AWS RoboMaker and
  // ScanNet/NYU40 names.
  std::string category_map = "categories/default.yaml";
  // Limits `objscan run` checks before it starts (scanning/scene_limits.h): the largest side of the
  // scene's bounds (the map grids grow with it; the AWS small house spans 20 m) and its triangles
  // (the ray caster holds them all; a ScanNet scan has a few hundred thousand). A larger scene fails
  // with one line naming the key instead of running out of memory.
  double max_extent_m = 100.0;
  std::int64_t max_triangles = 20'000'000;

  template <class V>
  void Visit(V& v) {
    v("model_path", model_path);
    v("allow_missing", allow_missing);
    v("min_loaded_model_fraction", min_loaded_model_fraction);
    v("doors_open", doors_open);
    v("category_map", category_map);
    v("max_extent_m", max_extent_m);
    v("max_triangles", max_triangles);
  }
  void Validate() const;
};

// Throws InputError with one line naming the file and element on bad input. Applies doors_open.
world::Scene LoadScene(const std::string& spec, const SceneLoadOptions& options);
// The scene as its file has it (doors_open not applied).
world::Scene LoadSceneAsWritten(const std::string& spec, const SceneLoadOptions& options);
// Removes every door of the scene and says so in its load_notes() (SceneLoadOptions::doors_open).
void OpenDoors(world::Scene* scene);

}  // namespace objscan::io
