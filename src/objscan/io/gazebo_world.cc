#include "objscan/io/gazebo_world.h"

#include <tinyxml2.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/geometry/pose.h"
#include "objscan/io/mesh_io.h"
#include "objscan/io/model_path.h"
#include "objscan/io/suncg_categories.h"

namespace objscan::io {
namespace fs = std::filesystem;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

namespace {

const char* kWallModel = "drc_practice_valve_wall";

bool StartsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string ElementText(const XMLElement* e) {
  const char* text = e != nullptr ? e->GetText() : nullptr;
  return text != nullptr ? text : "";
}

// Parses whitespace-separated numbers; false unless exactly `count` finite numbers.
bool ParseNumbers(const std::string& text, std::size_t count, std::vector<double>* out) {
  out->clear();
  const char* p = text.c_str();
  while (true) {
    while (*p != '\0' && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (*p == '\0') break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v)) return false;
    out->push_back(v);
    p = end;
  }
  return out->size() == count;
}

// The model id behind a mesh URI: model://403/403.dae -> "403".
std::string ModelIdOfUri(const std::string& uri) {
  if (!StartsWith(uri, "model://")) return "";
  const std::string rest = uri.substr(8);
  return rest.substr(0, rest.find('/'));
}

struct StatePoses {
  geometry::Pose3 T_world_model = geometry::Pose3::Identity();
  std::map<std::string, geometry::Pose3> T_world_link;
};

// One model being assembled.
struct ModelBuild {
  std::string name;
  geometry::Pose3 T_world_model = geometry::Pose3::Identity();
  geometry::TriangleMesh mesh;  // model frame
  std::vector<std::string> mesh_uris;
  bool has_plane = false;
  double plane_z_m = 0.0;
};

class WorldLoader {
 public:
  WorldLoader(std::string path, const SceneLoadOptions& options)
      : path_(std::move(path)), options_(options) {
    world_dir_ = fs::path(path_).parent_path().string();
    if (world_dir_.empty()) world_dir_ = ".";
    search_path_ = ModelSearchPath(world_dir_, options_.model_path);
  }

  world::Scene Load() {
    std::error_code ec;
    if (!fs::is_regular_file(path_, ec)) throw InputError(path_ + ": world file not found");
    XMLDocument doc;
    if (doc.LoadFile(path_.c_str()) != tinyxml2::XML_SUCCESS) {
      std::string reason = doc.ErrorStr() != nullptr ? doc.ErrorStr() : "unknown error";
      for (char& c : reason) {
        if (c == '\n' || c == '\r') c = ' ';
      }
      throw InputError(path_ + ": malformed XML: " + reason);
    }
    const XMLElement* sdf = doc.RootElement();
    if (sdf == nullptr || std::string(sdf->Name()) != "sdf") throw InputError(path_ + ": root element is not <sdf>");
    const XMLElement* world_elem = sdf->FirstChildElement("world");
    if (world_elem == nullptr) throw InputError(path_ + ": <sdf> has no <world>");

    // The last <state> holds the poses Gazebo applies on load, plus insertions and deletions.
    const XMLElement* state = nullptr;
    for (const XMLElement* s = world_elem->FirstChildElement("state"); s; s = s->NextSiblingElement("state")) state = s;
    std::set<std::string> deleted;
    std::vector<const XMLElement*> model_elems;
    for (const XMLElement* e = world_elem->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "model" || tag == "include") model_elems.push_back(e);
    }
    if (state != nullptr) {
      ReadState(*state);
      if (const XMLElement* ins = state->FirstChildElement("insertions")) {
        for (const XMLElement* m = ins->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
          model_elems.push_back(m);
        }
      }
      if (const XMLElement* del = state->FirstChildElement("deletions")) {
        for (const XMLElement* n = del->FirstChildElement("name"); n; n = n->NextSiblingElement("name")) {
          deleted.insert(ElementText(n));
        }
      }
    }

    world::Scene scene(path_);
    std::vector<world::SceneObject> objects;
    double plane_z_m = 0.0;
    std::set<std::string> seen_names;
    for (const XMLElement* e : model_elems) {
      ModelBuild build;
      if (std::string(e->Name()) == "include") {
        if (!BuildInclude(*e, &build)) continue;
      } else {
        build.name = ModelName(*e);
        if (deleted.count(build.name)) continue;
        build.T_world_model = ModelPose(*e, build.name);
        AddModelContent(*e, build.name, geometry::Pose3::Identity(), StateOf(build.name), &build);
      }
      if (deleted.count(build.name)) continue;
      if (!seen_names.insert(build.name).second) {
        throw InputError(Where(build.name) + ": duplicate model name");
      }
      if (build.has_plane) plane_z_m = build.plane_z_m;
      if (build.mesh.Empty()) continue;  // ground_plane, collision-only or fully missing models
      world::SceneObject object;
      object.name = build.name;
      object.T_world_object = build.T_world_model;
      object.mesh = std::move(build.mesh);
      Classify(build, &object);
      objects.push_back(std::move(object));
    }

    // The floor first (structure), then the models in file order.
    world::SceneObject floor;
    floor.category = world::Category::kFloor;
    floor.name = "floor";
    floor.model_name = "ground_plane";
    floor.mesh = FloorMesh(objects, plane_z_m);
    scene.Add(std::move(floor));
    for (auto& object : objects) scene.Add(std::move(object));
    scene.missing_meshes() = missing_;
    return scene;
  }

 private:
  std::string Where(const std::string& model_name) const { return path_ + ": model '" + model_name + "'"; }

  std::string ModelName(const XMLElement& e) const {
    const char* name = e.Attribute("name");
    if (name == nullptr || *name == '\0') {
      throw InputError(path_ + ": <model> without a name (line " + std::to_string(e.GetLineNum()) + ")");
    }
    return name;
  }

  geometry::Pose3 ParsePose(const XMLElement& parent, const std::string& where) const {
    const XMLElement* pose = parent.FirstChildElement("pose");
    if (pose == nullptr) return geometry::Pose3::Identity();
    std::vector<double> v;
    if (!ParseNumbers(ElementText(pose), 6, &v)) {
      throw InputError(where + ": <pose> '" + ElementText(pose) + "' is not 6 numbers (x y z roll pitch yaw)");
    }
    return geometry::PoseFromXyzRpy(v[0], v[1], v[2], v[3], v[4], v[5]);
  }

  void ReadState(const XMLElement& state) {
    for (const XMLElement* m = state.FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
      const std::string name = ModelName(*m);
      const std::string where = path_ + ": <state> model '" + name + "'";
      StatePoses poses;
      poses.T_world_model = ParsePose(*m, where);
      for (const XMLElement* l = m->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
        const char* link_name = l->Attribute("name");
        if (link_name != nullptr && l->FirstChildElement("pose") != nullptr) {
          poses.T_world_link[link_name] = ParsePose(*l, where + " link '" + link_name + "'");
        }
      }
      state_[name] = poses;
    }
  }

  const StatePoses* StateOf(const std::string& model_name) const {
    const auto it = state_.find(model_name);
    return it == state_.end() ? nullptr : &it->second;
  }

  geometry::Pose3 ModelPose(const XMLElement& e, const std::string& name) const {
    if (const StatePoses* s = StateOf(name)) return s->T_world_model;
    return ParsePose(e, Where(name));
  }

  // Adds links, visuals and nested models of `model` to `build`; T_root_model places this model in
  // the frame of the top-level model being built.
  void AddModelContent(const XMLElement& model, const std::string& top_name, const geometry::Pose3& T_root_model,
                       const StatePoses* state, ModelBuild* build) {
    for (const XMLElement* link = model.FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
      const char* link_name_attr = link->Attribute("name");
      const std::string link_name = link_name_attr != nullptr ? link_name_attr : "";
      geometry::Pose3 T_model_link = ParsePose(*link, Where(top_name) + " link '" + link_name + "'");
      if (state != nullptr) {
        const auto it = state->T_world_link.find(link_name);
        // State link poses are in the world frame.
        if (it != state->T_world_link.end()) T_model_link = state->T_world_model.inverse() * it->second;
      }
      for (const XMLElement* visual = link->FirstChildElement("visual"); visual;
           visual = visual->NextSiblingElement("visual")) {
        const char* visual_name = visual->Attribute("name");
        const std::string where =
            Where(top_name) + " visual '" + std::string(visual_name != nullptr ? visual_name : "") + "'";
        const geometry::Pose3 T_model_visual = T_root_model * T_model_link * ParsePose(*visual, where);
        AddGeometry(*visual, where, T_model_visual, top_name, build);
      }
    }
    for (const XMLElement* nested = model.FirstChildElement("model"); nested;
         nested = nested->NextSiblingElement("model")) {
      AddModelContent(*nested, top_name, T_root_model * ParsePose(*nested, Where(top_name)), nullptr, build);
    }
  }

  void AddGeometry(const XMLElement& visual, const std::string& where, const geometry::Pose3& T_model_visual,
                   const std::string& top_name, ModelBuild* build) {
    const XMLElement* geometry = visual.FirstChildElement("geometry");
    if (geometry == nullptr) throw InputError(where + ": no <geometry>");
    const XMLElement* shape = geometry->FirstChildElement();
    if (shape == nullptr) throw InputError(where + ": empty <geometry>");
    const std::string kind = shape->Name();
    std::vector<double> v;
    geometry::TriangleMesh part;
    Eigen::Affine3d T = T_model_visual;
    if (kind == "plane") {
      // The ground plane: replaced by a bounded floor quad once the room's extent is known.
      build->has_plane = true;
      build->plane_z_m = (build->T_world_model * T_model_visual).translation().z();
      return;
    } else if (kind == "box") {
      if (!ParseNumbers(ElementText(shape->FirstChildElement("size")), 3, &v) || v[0] < 0 || v[1] < 0 || v[2] < 0) {
        throw InputError(where + ": <box><size> must be 3 non-negative numbers");
      }
      if (v[0] * v[1] * v[2] == 0.0) return;
      part = geometry::MakeBox(Eigen::Vector3d(v[0], v[1], v[2]));
    } else if (kind == "cylinder") {
      std::vector<double> r, l;
      if (!ParseNumbers(ElementText(shape->FirstChildElement("radius")), 1, &r) ||
          !ParseNumbers(ElementText(shape->FirstChildElement("length")), 1, &l) || !(r[0] > 0) || !(l[0] > 0)) {
        throw InputError(where + ": <cylinder> needs positive <radius> and <length>");
      }
      part = geometry::MakeCylinder(r[0], l[0]);
    } else if (kind == "sphere") {
      if (!ParseNumbers(ElementText(shape->FirstChildElement("radius")), 1, &v) || !(v[0] > 0)) {
        throw InputError(where + ": <sphere> needs a positive <radius>");
      }
      part = geometry::MakeSphere(v[0]);
    } else if (kind == "mesh") {
      const std::string uri = ElementText(shape->FirstChildElement("uri"));
      if (uri.empty()) throw InputError(where + ": <mesh> without <uri>");
      build->mesh_uris.push_back(uri);
      Eigen::Vector3d scale(1, 1, 1);
      if (const XMLElement* s = shape->FirstChildElement("scale")) {
        if (!ParseNumbers(ElementText(s), 3, &v) || !(v[0] > 0 && v[1] > 0 && v[2] > 0)) {
          throw InputError(where + ": <scale> '" + ElementText(s) + "' must be 3 positive numbers");
        }
        scale = Eigen::Vector3d(v[0], v[1], v[2]);
      }
      const geometry::TriangleMesh* mesh = MeshFor(uri, where, top_name);
      if (mesh == nullptr) return;  // recorded as missing
      T = T * Eigen::Scaling(scale);
      geometry::Append(geometry::Transformed(*mesh, T), &build->mesh);
      return;
    } else {
      const std::string message = where + ": unsupported geometry <" + kind + ">";
      if (!options_.allow_missing) throw InputError(message);
      missing_.push_back("<" + kind + "> (model '" + top_name + "')");
      return;
    }
    geometry::Append(geometry::Transformed(part, T), &build->mesh);
  }

  // The mesh behind a URI (cached: walls and repeated furniture share files). nullptr when missing
  // and allow_missing is set.
  const geometry::TriangleMesh* MeshFor(const std::string& uri, const std::string& where, const std::string& model) {
    const std::optional<std::string> resolved = ResolveModelUri(uri, world_dir_, search_path_);
    if (!resolved) {
      const std::string message = where + ": cannot resolve " + uri +
                                  " (searched the world's folder, the model path, $OBJSCAN_MODEL_PATH, $GAZEBO_MODEL_PATH)";
      if (!options_.allow_missing) throw InputError(message);
      missing_.push_back(uri + " (model '" + model + "')");
      return nullptr;
    }
    auto it = mesh_cache_.find(*resolved);
    if (it == mesh_cache_.end()) {
      std::unique_ptr<geometry::TriangleMesh> mesh;
      try {
        mesh = std::make_unique<geometry::TriangleMesh>(LoadMesh(*resolved));
      } catch (const InputError& e) {
        if (!options_.allow_missing) throw InputError(where + ": " + e.what());
        mesh.reset();
      }
      it = mesh_cache_.emplace(*resolved, std::move(mesh)).first;
    }
    if (it->second == nullptr) {
      missing_.push_back(uri + " (model '" + model + "', unreadable)");
      return nullptr;
    }
    return it->second.get();
  }

  // <include><uri>model://NAME</uri><name>..</name><pose>..</pose></include>
  bool BuildInclude(const XMLElement& include, ModelBuild* build) {
    const std::string uri = ElementText(include.FirstChildElement("uri"));
    const std::string where = path_ + ": <include> '" + uri + "'";
    const std::optional<std::string> folder = ResolveModelFolder(uri, search_path_);
    if (!folder) {
      if (!options_.allow_missing) throw InputError(where + ": cannot resolve " + uri);
      missing_.push_back(uri + " (<include>)");
      return false;
    }
    const std::string sdf_path = ModelSdfOf(*folder, where);
    auto doc = std::make_unique<XMLDocument>();
    if (doc->LoadFile(sdf_path.c_str()) != tinyxml2::XML_SUCCESS) {
      throw InputError(sdf_path + ": malformed XML: " + std::string(doc->ErrorStr() ? doc->ErrorStr() : ""));
    }
    const XMLElement* root = doc->RootElement();
    const XMLElement* model = root != nullptr ? root->FirstChildElement("model") : nullptr;
    if (model == nullptr) throw InputError(sdf_path + ": no <model>");
    const XMLElement* name_elem = include.FirstChildElement("name");
    build->name = name_elem != nullptr ? ElementText(name_elem) : ModelName(*model);
    // Mesh URIs of the included model resolve against the model path like any other.
    if (const StatePoses* s = StateOf(build->name)) {
      build->T_world_model = s->T_world_model;
    } else if (include.FirstChildElement("pose") != nullptr) {
      build->T_world_model = ParsePose(include, where);
    } else {
      build->T_world_model = ParsePose(*model, where);
    }
    AddModelContent(*model, build->name, geometry::Pose3::Identity(), StateOf(build->name), build);
    included_docs_.push_back(std::move(doc));
    return true;
  }

  // model.config's <sdf> entry (the last listed), else model.sdf.
  std::string ModelSdfOf(const std::string& folder, const std::string& where) const {
    XMLDocument config;
    const fs::path config_path = fs::path(folder) / "model.config";
    std::string sdf_name = "model.sdf";
    if (config.LoadFile(config_path.string().c_str()) == tinyxml2::XML_SUCCESS && config.RootElement() != nullptr) {
      for (const XMLElement* s = config.RootElement()->FirstChildElement("sdf"); s; s = s->NextSiblingElement("sdf")) {
        if (!ElementText(s).empty()) sdf_name = ElementText(s);
      }
    }
    const fs::path sdf = fs::path(folder) / sdf_name;
    std::error_code ec;
    if (!fs::is_regular_file(sdf, ec)) throw InputError(where + ": no " + sdf.string());
    return sdf.string();
  }

  void Classify(const ModelBuild& build, world::SceneObject* object) {
    bool wall = StartsWith(build.name, "valve_wall");
    for (const std::string& uri : build.mesh_uris) wall = wall || uri.find(kWallModel) != std::string::npos;
    if (wall) {
      object->category = world::Category::kWall;
      object->model_name = kWallModel;
      return;
    }
    std::string id = build.mesh_uris.empty() ? "" : ModelIdOfUri(build.mesh_uris.front());
    if (id.empty()) id = StripInstanceSuffix(build.name);
    object->model_name = id;
    if (const SuncgModelMapping* mapping = Mapping()) {
      if (const SuncgClasses* classes = mapping->Lookup(id)) {
        const SuncgCategoryTable& table = Table();
        const std::optional<world::Category> category = table.Lookup(*classes);
        if (!category) {
          throw InputError(Where(build.name) + ": SUNCG class '" + classes->fine_grained + "' of model id '" + id +
                           "' has no objscan category in " + table.path());
        }
        object->category = *category;
        return;
      }
    }
    // Not a SUNCG model: a model named after a category ("chair_2") keeps it.
    std::optional<world::Category> category = world::ParseCategory(StripInstanceSuffix(build.name));
    if (!category) category = world::ParseCategory(id);
    object->category = (category && !world::IsStructural(*category)) ? *category : world::Category::kOther;
  }

  const SuncgModelMapping* Mapping() {
    if (!mapping_searched_) {
      mapping_searched_ = true;
      const std::string csv = SuncgModelMapping::Find(world_dir_);
      if (!csv.empty()) mapping_ = std::make_unique<SuncgModelMapping>(SuncgModelMapping::Load(csv));
    }
    return mapping_.get();
  }

  const SuncgCategoryTable& Table() {
    if (!table_) {
      table_ = std::make_unique<SuncgCategoryTable>(
          SuncgCategoryTable::Load(ResolveConfigPath(options_.suncg_category_table)));
    }
    return *table_;
  }

  static geometry::TriangleMesh FloorMesh(const std::vector<world::SceneObject>& objects, double z_m) {
    geometry::Aabb3 walls, furniture;
    for (const auto& o : objects) {
      (o.category == world::Category::kWall ? walls : furniture).Extend(geometry::Bounds(o.mesh, o.T_world_object));
    }
    const geometry::Aabb3& extent = !walls.Empty() ? walls : furniture;
    double x0 = -5, y0 = -5, x1 = 5, y1 = 5;
    if (!extent.Empty()) {
      x0 = extent.min_m.x() - kFloorMarginM;
      y0 = extent.min_m.y() - kFloorMarginM;
      x1 = extent.max_m.x() + kFloorMarginM;
      y1 = extent.max_m.y() + kFloorMarginM;
    }
    geometry::TriangleMesh quad = geometry::MakeQuadXY(x0, y0, x1, y1);
    for (auto& v : quad.vertices) v.z() = static_cast<float>(z_m);
    return quad;
  }

  std::string path_;
  const SceneLoadOptions& options_;
  std::string world_dir_;
  std::vector<std::string> search_path_;
  std::map<std::string, StatePoses> state_;
  std::map<std::string, std::unique_ptr<geometry::TriangleMesh>> mesh_cache_;
  std::vector<std::unique_ptr<XMLDocument>> included_docs_;
  std::vector<std::string> missing_;
  bool mapping_searched_ = false;
  std::unique_ptr<SuncgModelMapping> mapping_;
  std::unique_ptr<SuncgCategoryTable> table_;
};

}  // namespace

world::Scene LoadGazeboWorld(const std::string& path, const SceneLoadOptions& options) {
  options.Validate();
  return WorldLoader(path, options).Load();
}

}  // namespace objscan::io
