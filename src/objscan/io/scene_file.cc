#include "objscan/io/scene_file.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "objscan/common/error.h"
#include "objscan/geometry/pose.h"
#include "objscan/io/gazebo_world.h"
#include "objscan/io/mesh_io.h"

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

class SceneFileParser {
 public:
  explicit SceneFileParser(std::string path) : path_(std::move(path)) {
    base_dir_ = fs::path(path_).parent_path();
  }

  world::Scene Parse() {
    std::error_code ec;
    if (!fs::is_regular_file(path_, ec)) throw InputError(path_ + ": scene file not found");
    YAML::Node root;
    try {
      root = YAML::LoadFile(path_);
    } catch (const YAML::Exception& e) {
      throw InputError(path_ + ": malformed YAML/JSON: " + std::string(e.what()));
    }
    if (!root.IsMap()) throw InputError(path_ + ": expected a mapping with 'objects'");
    CheckKeys(root, "top level", {"name", "floor", "walls", "objects"});

    world::Scene scene(root["name"] ? Scalar(root["name"], "name") : fs::path(path_).filename().string());
    const bool floor = root["floor"] ? Bool(root["floor"], "floor") : true;

    std::vector<world::SceneObject> walls, objects;
    if (const YAML::Node w = root["walls"]) {
      if (!w.IsSequence()) throw InputError(path_ + ": walls: expected a list");
      for (std::size_t i = 0; i < w.size(); ++i) walls.push_back(ParseWall(w[i], "walls[" + std::to_string(i) + "]"));
    }
    const YAML::Node list = root["objects"];
    if (!list || !list.IsSequence()) throw InputError(path_ + ": objects: expected a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      objects.push_back(ParseObject(list[i], i, "objects[" + std::to_string(i) + "]"));
    }

    if (floor) {
      geometry::Aabb3 extent;
      for (const auto* group : {&walls, &objects}) {
        if (!extent.Empty()) break;
        for (const auto& o : *group) extent.Extend(geometry::Bounds(o.mesh, o.T_world_object));
      }
      double x0 = -5, y0 = -5, x1 = 5, y1 = 5;
      if (!extent.Empty()) {
        x0 = extent.min_m.x() - kFloorMarginM;
        y0 = extent.min_m.y() - kFloorMarginM;
        x1 = extent.max_m.x() + kFloorMarginM;
        y1 = extent.max_m.y() + kFloorMarginM;
      }
      world::SceneObject f;
      f.category = world::Category::kFloor;
      f.name = "floor";
      f.model_name = "floor";
      f.mesh = geometry::MakeQuadXY(x0, y0, x1, y1);
      scene.Add(std::move(f));
    }
    for (auto& w : walls) scene.Add(std::move(w));
    for (auto& o : objects) scene.Add(std::move(o));
    return scene;
  }

 private:
  std::string Where(const std::string& element) const { return path_ + ": " + element; }

  void CheckKeys(const YAML::Node& node, const std::string& element, const std::set<std::string>& allowed) const {
    for (const auto& kv : node) {
      if (!kv.first.IsScalar()) throw InputError(Where(element) + ": a key is not a name (a list or a mapping)");
      const std::string key = kv.first.Scalar();
      if (!allowed.count(key)) throw InputError(Where(element) + ": unknown key '" + key + "'");
    }
  }

  std::string Scalar(const YAML::Node& node, const std::string& element) const {
    if (!node.IsScalar()) throw InputError(Where(element) + ": expected a single value");
    return node.Scalar();
  }

  bool Bool(const YAML::Node& node, const std::string& element) const {
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
      throw InputError(Where(element) + ": expected true or false");
    }
  }

  double Number(const YAML::Node& node, const std::string& element) const {
    double v = 0;
    try {
      v = node.as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(Where(element) + ": '" + (node.IsScalar() ? node.Scalar() : "?") + "' is not a number");
    }
    if (!std::isfinite(v)) throw InputError(Where(element) + ": not a finite number");
    return v;
  }

  std::vector<double> Numbers(const YAML::Node& node, std::size_t count, const std::string& element) const {
    if (!node.IsSequence() || node.size() != count) {
      throw InputError(Where(element) + ": expected a list of " + std::to_string(count) + " numbers");
    }
    std::vector<double> v;
    for (std::size_t i = 0; i < count; ++i) v.push_back(Number(node[i], element + "[" + std::to_string(i) + "]"));
    return v;
  }

  world::SceneObject ParseWall(const YAML::Node& node, const std::string& element) const {
    if (!node.IsMap()) throw InputError(Where(element) + ": expected {min: [x,y,z], max: [x,y,z]}");
    CheckKeys(node, element, {"min", "max"});
    if (!node["min"] || !node["max"]) throw InputError(Where(element) + ": needs min and max");
    const std::vector<double> lo = Numbers(node["min"], 3, element + ".min");
    const std::vector<double> hi = Numbers(node["max"], 3, element + ".max");
    for (int k = 0; k < 3; ++k) {
      if (!(hi[k] > lo[k])) throw InputError(Where(element) + ": max must exceed min on every axis");
    }
    world::SceneObject wall;
    wall.category = world::Category::kWall;
    wall.name = "wall_" + element.substr(element.find('[') + 1, element.find(']') - element.find('[') - 1);
    wall.model_name = "box_wall";
    wall.mesh = geometry::MakeBox(Eigen::Vector3d(lo[0], lo[1], lo[2]), Eigen::Vector3d(hi[0], hi[1], hi[2]));
    return wall;
  }

  world::SceneObject ParseObject(const YAML::Node& node, std::size_t index, const std::string& element) {
    if (!node.IsMap()) throw InputError(Where(element) + ": expected a mapping");
    CheckKeys(node, element, {"mesh", "box", "category", "pose", "scale", "up_axis", "name", "model"});
    world::SceneObject object;
    if (node["category"]) {
      const std::string name = Scalar(node["category"], element + ".category");
      const std::optional<world::Category> c = world::ParseCategory(name);
      if (!c || world::IsStructural(*c)) {
        throw InputError(Where(element) + ": unknown category '" + name + "'");
      }
      object.category = *c;
    }
    if (node["pose"]) {
      const std::vector<double> p = Numbers(node["pose"], 6, element + ".pose");
      object.T_world_object = geometry::PoseFromXyzRpy(p[0], p[1], p[2], p[3], p[4], p[5]);
    }
    if (node["mesh"] && node["box"]) throw InputError(Where(element) + ": give either mesh or box, not both");
    if (node["mesh"]) {
      const std::string mesh = Scalar(node["mesh"], element + ".mesh");
      fs::path mesh_path(mesh);
      if (mesh_path.is_relative()) mesh_path = base_dir_ / mesh_path;
      MeshLoadOptions mesh_options;
      if (node["up_axis"]) mesh_options.up_axis = Scalar(node["up_axis"], element + ".up_axis");
      if (mesh_options.up_axis != "auto" && mesh_options.up_axis != "z" && mesh_options.up_axis != "y") {
        throw InputError(Where(element) + ": up_axis '" + mesh_options.up_axis + "' is not one of auto, z, y");
      }
      try {
        object.mesh = CachedMesh(mesh_path.lexically_normal().string(), mesh_options);
      } catch (const InputError& e) {
        throw InputError(Where(element) + ": " + e.what());
      }
      object.model_name = fs::path(mesh).stem().string();
    } else if (node["box"]) {
      const std::vector<double> s = Numbers(node["box"], 3, element + ".box");
      if (!(s[0] > 0 && s[1] > 0 && s[2] > 0)) throw InputError(Where(element) + ": box sizes must be positive");
      object.mesh = geometry::MakeBox(Eigen::Vector3d(-s[0] / 2, -s[1] / 2, 0), Eigen::Vector3d(s[0] / 2, s[1] / 2, s[2]));
      object.model_name = "box";
      if (node["up_axis"]) throw InputError(Where(element) + ": up_axis applies to meshes only");
    } else {
      throw InputError(Where(element) + ": needs mesh or box");
    }
    if (node["scale"]) {
      Eigen::Vector3d scale;
      if (node["scale"].IsSequence()) {
        const std::vector<double> s = Numbers(node["scale"], 3, element + ".scale");
        scale = Eigen::Vector3d(s[0], s[1], s[2]);
      } else {
        scale = Eigen::Vector3d::Constant(Number(node["scale"], element + ".scale"));
      }
      if (!(scale.minCoeff() > 0)) throw InputError(Where(element) + ": scale must be positive");
      object.mesh = geometry::Transformed(object.mesh, Eigen::Affine3d(Eigen::Scaling(scale)));
    }
    if (node["model"]) object.model_name = Scalar(node["model"], element + ".model");
    object.name = node["name"] ? Scalar(node["name"], element + ".name") : object.model_name + "_" + std::to_string(index);
    return object;
  }

  // A mesh file is imported once per scene file, whatever the number of objects naming it: a room
  // of twelve identical chairs costs one Assimp import, not twelve.
  const geometry::TriangleMesh& CachedMesh(const std::string& path, const MeshLoadOptions& options) {
    const std::pair<std::string, std::string> key(path, options.up_axis);
    auto it = mesh_cache_.find(key);
    if (it == mesh_cache_.end()) it = mesh_cache_.emplace(key, LoadMesh(path, options)).first;
    return it->second;
  }

  std::string path_;
  fs::path base_dir_;
  std::map<std::pair<std::string, std::string>, geometry::TriangleMesh> mesh_cache_;
};

}  // namespace

world::Scene LoadSceneFile(const std::string& path) {
  try {
    return SceneFileParser(path).Parse();
  } catch (const YAML::Exception& e) {
    // The parser checks each node's type before converting it; this is the net for the rest.
    throw InputError(path + ": malformed scene file: " + e.what());
  }
}

}  // namespace objscan::io
