#include "objscan/io/gazebo_world.h"

#include <tinyxml2.h>

#include <algorithm>
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
#include "objscan/io/category_map.h"
#include "objscan/io/mesh_io.h"
#include "objscan/io/model_path.h"
#include "objscan/io/suncg_categories.h"

namespace objscan::io {
namespace fs = std::filesystem;
using geometry::Pose3;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

namespace {

constexpr const char* kModelFrame = "__model__";
constexpr const char* kWorldFrame = "world";
// Includes nest (a model including a model ...); deeper than this is a cycle in practice.
constexpr int kMaxIncludeDepth = 32;

bool StartsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string Trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r\n") - begin + 1);
}

std::string ElementText(const XMLElement* e) {
  const char* text = e != nullptr ? e->GetText() : nullptr;
  return text != nullptr ? Trim(text) : "";
}

std::string Attribute(const XMLElement& e, const char* name) {
  const char* value = e.Attribute(name);
  return value != nullptr ? value : "";
}

std::string Line(const XMLElement& e) { return " (line " + std::to_string(e.GetLineNum()) + ")"; }

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

// Elements we do not read whose content is scene geometry: skipping them silently would lose objects.
bool CarriesGeometry(const XMLElement& e) {
  static const std::set<std::string> kGeometryElements = {"actor", "population", "road", "heightmap", "geometry",
                                                          "mesh",  "skin",       "link", "visual",    "model",
                                                          "include"};
  if (kGeometryElements.count(e.Name())) return true;
  for (const XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (CarriesGeometry(*c)) return true;
  }
  return false;
}

// A <pose> as written: the transform and the frame it is relative to ("" = the element's default).
struct PoseSpec {
  Pose3 pose = Pose3::Identity();
  std::string relative_to;
};

// Frames of one scope (a model, or the world) and their poses in the scope's own frame. SDF 1.7+
// semantics: an element's <pose relative_to='F'> is relative to frame F of the same scope (a link,
// nested model, <frame>, joint, or `__model__`), "A::B" names frame B of nested model A; without
// relative_to, each element has its default (links and models: the scope; frames: attached_to;
// joints: the child link). Worlds in SDF <= 1.6 only use the defaults, which agree.
class FrameGraph {
 public:
  FrameGraph(std::string scope_frame, std::string where) : scope_frame_(std::move(scope_frame)), where_(std::move(where)) {}

  // `placement` is applied after the pose: T_scope_element = T_scope_relative_to * pose * placement.
  void Add(const std::string& name, const PoseSpec& pose, const std::string& default_relative_to,
           const std::string& where, const Pose3& placement = Pose3::Identity()) {
    if (name.empty()) throw InputError(where + ": element without a name");
    if (name == scope_frame_ || name.find("::") != std::string::npos) {
      throw InputError(where + ": '" + name + "' is a reserved frame name");
    }
    Entry entry;
    entry.relative_to = pose.relative_to.empty() ? default_relative_to : pose.relative_to;
    entry.pose = pose.pose * placement;
    entry.where = where;
    if (!entries_.emplace(name, entry).second) throw InputError(where + ": name '" + name + "' is used twice in " + where_);
  }
  void AddScope(const std::string& name, const FrameGraph* child) { children_[name] = child; }
  bool Has(const std::string& name) const { return entries_.count(name) > 0; }

  // T_scope_frame; throws naming the element for an unknown frame or a cycle.
  Pose3 Resolve(const std::string& name, const std::string& where) const {
    if (name.empty() || name == scope_frame_) return Pose3::Identity();
    const auto sep = name.find("::");
    if (sep != std::string::npos) {
      const std::string head = name.substr(0, sep);
      const auto child = children_.find(head);
      if (child == children_.end()) throw InputError(where + ": frame '" + name + "': no nested model '" + head + "' in " + where_);
      return Resolve(head, where) * child->second->Resolve(name.substr(sep + 2), where);
    }
    const auto it = entries_.find(name);
    if (it == entries_.end()) throw InputError(where + ": relative_to/attached_to '" + name + "' names no frame in " + where_);
    Entry& entry = it->second;
    if (entry.resolved) return entry.T_scope_frame;
    if (entry.visiting) throw InputError(entry.where + ": pose frames form a cycle through '" + name + "'");
    entry.visiting = true;
    entry.T_scope_frame = Resolve(entry.relative_to, entry.where) * entry.pose;
    entry.visiting = false;
    entry.resolved = true;
    return entry.T_scope_frame;
  }

 private:
  struct Entry {
    std::string relative_to;
    Pose3 pose = Pose3::Identity();
    std::string where;
    bool visiting = false, resolved = false;
    Pose3 T_scope_frame = Pose3::Identity();
  };
  std::string scope_frame_;
  std::string where_;
  mutable std::map<std::string, Entry> entries_;
  std::map<std::string, const FrameGraph*> children_;
};

// World-frame poses saved by Gazebo in <state>: the model, its links and its nested models.
struct StatePoses {
  Pose3 T_world_model = Pose3::Identity();
  std::map<std::string, Pose3> T_world_link;
  std::map<std::string, StatePoses> nested;
};

// One <model> after <include> expansion, with its links and nested models.
struct ModelNode {
  const XMLElement* elem = nullptr;  // the <model>
  std::string file;                  // the file holding it: relative URIs resolve from its folder
  std::string name;
  PoseSpec pose;                     // in the parent scope (an <include>'s pose wins over the model's)
  std::string placement_frame;       // the frame `pose` places (default: the model frame)
  std::vector<const XMLElement*> links;
  std::vector<std::unique_ptr<ModelNode>> children;
  std::unique_ptr<FrameGraph> frames;
};

// One top-level model being assembled into a scene object.
struct ModelBuild {
  std::string name;
  Pose3 T_world_model = Pose3::Identity();
  geometry::TriangleMesh mesh;  // model frame
  std::vector<std::string> mesh_uris;
  std::vector<std::string> include_uris;
  bool has_plane = false;
  double plane_z_m = 0.0;
};

class WorldLoader {
 public:
  WorldLoader(std::string path, const SceneLoadOptions& options, CategoryMap* category_map)
      : path_(std::move(path)), options_(options), category_map_(category_map) {
    world_dir_ = fs::path(path_).parent_path().string();
    if (world_dir_.empty()) world_dir_ = ".";
    search_ = MakeUriSearchPath(path_, options_.model_path);
  }

  world::Scene Load() {
    std::error_code ec;
    if (!fs::is_regular_file(path_, ec)) throw InputError(path_ + ": world file not found");
    const XMLDocument& doc = Parse(path_);
    const XMLElement* sdf = doc.RootElement();
    if (sdf == nullptr || std::string(sdf->Name()) != "sdf") throw InputError(path_ + ": root element is not <sdf>");
    const XMLElement* world_elem = sdf->FirstChildElement("world");
    if (world_elem == nullptr) throw InputError(path_ + ": <sdf> has no <world>");

    // The last <state> holds the poses Gazebo applies on load, plus insertions and deletions.
    const XMLElement* state = nullptr;
    for (const XMLElement* s = world_elem->FirstChildElement("state"); s; s = s->NextSiblingElement("state")) state = s;
    std::set<std::string> deleted;
    std::vector<const XMLElement*> model_elems;
    FrameGraph world_frames(kWorldFrame, path_ + ": <world>");
    for (const XMLElement* e = world_elem->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "model" || tag == "include") {
        model_elems.push_back(e);
      } else if (tag == "frame") {
        AddFrame(*e, path_, kWorldFrame, &world_frames);
      } else if (tag != "state" && tag != "plugin") {
        RejectIfGeometry(*e, path_, "<world>");
      }
    }
    if (state != nullptr) {
      ReadState(*state);
      if (const XMLElement* ins = state->FirstChildElement("insertions")) {
        for (const XMLElement* m = ins->FirstChildElement(); m; m = m->NextSiblingElement()) {
          if (std::string(m->Name()) == "model") {
            model_elems.push_back(m);
          } else {
            RejectIfGeometry(*m, path_, "<state><insertions>");
          }
        }
      }
      if (const XMLElement* del = state->FirstChildElement("deletions")) {
        for (const XMLElement* n = del->FirstChildElement("name"); n; n = n->NextSiblingElement("name")) {
          deleted.insert(ElementText(n));
        }
      }
    }

    // Expand every top-level model first: their frames may be referred to by each other's poses.
    std::vector<std::unique_ptr<ModelNode>> nodes;
    std::set<std::string> seen_names;
    // Models that lost all their geometry to missing meshes or includes (allow_missing), and those kept.
    int models_lost = 0, models_kept = 0;
    std::map<const ModelNode*, std::size_t> missing_while_expanding;
    for (const XMLElement* e : model_elems) {
      const std::size_t missing_before = missing_.size();
      std::unique_ptr<ModelNode> node = std::string(e->Name()) == "include"
                                            ? ExpandInclude(*e, path_, 0)
                                            : BuildNode(*e, path_, ReadPose(*e, Where(NameOf(*e, path_))),
                                                        Attribute(*e, "placement_frame"), 0);
      if (node == nullptr) {  // unresolved include, listed (allow_missing)
        ++models_lost;
        continue;
      }
      if (deleted.count(node->name)) continue;
      missing_while_expanding[node.get()] = missing_.size() - missing_before;
      if (!seen_names.insert(node->name).second) throw InputError(Where(node->name) + ": duplicate model name");
      world_frames.Add(node->name, node->pose, kWorldFrame, Where(node->name), Placement(*node));
      world_frames.AddScope(node->name, node->frames.get());
      nodes.push_back(std::move(node));
    }

    world::Scene scene(path_);
    std::vector<world::SceneObject> objects;
    double plane_z_m = 0.0;
    for (const auto& node : nodes) {
      ModelBuild build;
      build.name = node->name;
      const StatePoses* state_poses = StateOf(node->name);
      build.T_world_model = state_poses != nullptr ? state_poses->T_world_model
                                                   : world_frames.Resolve(node->name, Where(node->name));
      const std::size_t missing_before = missing_.size();
      AddModelContent(*node, Pose3::Identity(), state_poses, &build);
      if (build.has_plane) plane_z_m = build.plane_z_m;
      const bool lost_some = missing_.size() > missing_before || missing_while_expanding[node.get()] > 0;
      if (build.mesh.Empty()) {  // ground_plane, collision-only or fully missing models
        models_lost += lost_some ? 1 : 0;
        continue;
      }
      ++models_kept;
      world::SceneObject object;
      object.name = build.name;
      object.T_world_object = build.T_world_model;
      object.mesh = std::move(build.mesh);
      Classify(build, &object);
      objects.push_back(std::move(object));
    }

    // A world that kept too few of its models (a wrong model path) would be scanned as an empty room.
    const int models = models_kept + models_lost;
    if (models_lost > 0 && models_kept < options_.min_loaded_model_fraction * models) {
      throw InputError(path_ + ": only " + std::to_string(models_kept) + " of " + std::to_string(models) +
                       " models could be loaded (" + std::to_string(missing_.size()) +
                       " meshes or includes missing; the first: " + (first_missing_.empty() ? missing_.front() : first_missing_) +
                       "); fix the paths, or load it anyway with --allow-missing given twice "
                       "(scene.min_loaded_model_fraction=0)");
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
    scene.unmapped_models() = unmapped_;
    return scene;
  }

 private:
  std::string Where(const std::string& model_name) const { return path_ + ": model '" + model_name + "'"; }

  // Parsed documents stay alive for the whole load (nodes point into them); each file is read once.
  const XMLDocument& Parse(const std::string& file) {
    auto it = docs_.find(file);
    if (it != docs_.end()) return *it->second;
    auto doc = std::make_unique<XMLDocument>();
    if (doc->LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
      std::string reason = doc->ErrorStr() != nullptr ? doc->ErrorStr() : "unknown error";
      std::replace(reason.begin(), reason.end(), '\n', ' ');
      std::replace(reason.begin(), reason.end(), '\r', ' ');
      throw InputError(file + ": malformed XML: " + reason);
    }
    return *docs_.emplace(file, std::move(doc)).first->second;
  }

  // An element we skip must not hold geometry; with allow_missing it is listed instead.
  void RejectIfGeometry(const XMLElement& e, const std::string& file, const std::string& parent) {
    if (!CarriesGeometry(e)) return;
    const std::string what = "<" + std::string(e.Name()) + ">" + (e.Attribute("name") ? " '" + Attribute(e, "name") + "'" : "");
    const std::string message = file + ": " + what + Line(e) + " in " + parent + " holds geometry objscan does not load";
    if (!options_.allow_missing) throw InputError(message);
    missing_.push_back(what + " in " + parent + " (" + file + ", line " + std::to_string(e.GetLineNum()) + ")");
  }

  // The name attribute of a model, link, frame or joint; required.
  std::string NameOf(const XMLElement& e, const std::string& file) const {
    const std::string name = Attribute(e, "name");
    if (name.empty()) throw InputError(file + ": <" + e.Name() + "> without a name" + Line(e));
    return name;
  }

  // The <pose> child of `parent` (identity when absent). SDF 1.5/1.6 wrote the frame as frame='...'.
  PoseSpec ReadPose(const XMLElement& parent, const std::string& where) const {
    PoseSpec spec;
    const XMLElement* pose = parent.FirstChildElement("pose");
    if (pose == nullptr) return spec;
    std::vector<double> v;
    if (!ParseNumbers(ElementText(pose), 6, &v)) {
      throw InputError(where + ": <pose> '" + ElementText(pose) + "' is not 6 numbers (x y z roll pitch yaw)");
    }
    const std::string degrees = Attribute(*pose, "degrees");
    if (degrees == "true" || degrees == "1") {
      for (int k = 3; k < 6; ++k) v[k] *= M_PI / 180.0;
    }
    const std::string rotation_format = Attribute(*pose, "rotation_format");
    if (!rotation_format.empty() && rotation_format != "euler_rpy") {
      throw InputError(where + ": <pose rotation_format='" + rotation_format + "'> is not supported (euler_rpy only)");
    }
    spec.pose = geometry::PoseFromXyzRpy(v[0], v[1], v[2], v[3], v[4], v[5]);
    spec.relative_to = Attribute(*pose, "relative_to");
    if (spec.relative_to.empty()) spec.relative_to = Attribute(*pose, "frame");
    return spec;
  }

  // <static> is accepted for every model (objscan's scenes do not move) but must be a boolean.
  static void CheckStatic(const XMLElement& e, const std::string& where) {
    const std::string text = ElementText(&e);
    if (text != "true" && text != "false" && text != "1" && text != "0") {
      throw InputError(where + ": <static> '" + text + "' is not a boolean (true, false, 1, 0)");
    }
  }

  void AddFrame(const XMLElement& frame, const std::string& file, const std::string& scope_frame, FrameGraph* graph) {
    const std::string name = NameOf(frame, file);
    const std::string where = file + ": <frame> '" + name + "'";
    std::string attached_to = Attribute(frame, "attached_to");
    if (attached_to.empty()) attached_to = scope_frame;
    graph->Add(name, ReadPose(frame, where), attached_to, where);
  }

  // T_model_placement_frame^-1 for a model placed by one of its frames (SDF 1.8 placement_frame).
  static Pose3 Placement(const ModelNode& node) {
    if (node.placement_frame.empty()) return Pose3::Identity();
    return node.frames->Resolve(node.placement_frame, node.file + ": model '" + node.name + "' placement_frame")
        .inverse();
  }

  std::unique_ptr<ModelNode> BuildNode(const XMLElement& model, const std::string& file, const PoseSpec& pose,
                                       const std::string& placement_frame, int depth) {
    auto node = std::make_unique<ModelNode>();
    node->elem = &model;
    node->file = file;
    node->name = NameOf(model, file);
    node->pose = pose;
    node->placement_frame = placement_frame;
    const std::string where = file + ": model '" + node->name + "'";
    node->frames = std::make_unique<FrameGraph>(kModelFrame, "model '" + node->name + "'");
    std::vector<const XMLElement*> joints;
    for (const XMLElement* e = model.FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "link") {
        const std::string link_name = NameOf(*e, file);
        const std::string link_where = where + " link '" + link_name + "'";
        node->frames->Add(link_name, ReadPose(*e, link_where), kModelFrame, link_where);
        node->links.push_back(e);
      } else if (tag == "model" || tag == "include") {
        std::unique_ptr<ModelNode> child =
            tag == "include" ? ExpandInclude(*e, file, depth + 1)
                             : BuildNode(*e, file, ReadPose(*e, where + " nested model '" + Attribute(*e, "name") + "'"),
                                         Attribute(*e, "placement_frame"), depth);
        if (child == nullptr) continue;
        node->frames->Add(child->name, child->pose, kModelFrame, where + " nested model '" + child->name + "'",
                          Placement(*child));
        node->frames->AddScope(child->name, child->frames.get());
        node->children.push_back(std::move(child));
      } else if (tag == "frame") {
        AddFrame(*e, file, kModelFrame, node->frames.get());
      } else if (tag == "joint") {
        joints.push_back(e);
      } else if (tag == "static") {
        CheckStatic(*e, where);
      } else if (tag != "pose" && tag != "plugin") {
        RejectIfGeometry(*e, file, "model '" + node->name + "'");
      }
    }
    // Joints are frames too (default: relative to their child link, which may be nested "A::link").
    for (const XMLElement* joint : joints) {
      const std::string joint_name = NameOf(*joint, file);
      const std::string joint_where = where + " joint '" + joint_name + "'";
      node->frames->Add(joint_name, ReadPose(*joint, joint_where), ElementText(joint->FirstChildElement("child")),
                        joint_where);
    }
    return node;
  }

  // <include><uri>model://NAME</uri><name>..</name><pose>..</pose><static>..</static></include>:
  // the model of NAME's model.config / model.sdf under the name and pose the include gives it.
  std::unique_ptr<ModelNode> ExpandInclude(const XMLElement& include, const std::string& file, int depth) {
    const std::string uri = ElementText(include.FirstChildElement("uri"));
    const std::string where = file + ": <include> '" + uri + "'" + Line(include);
    if (uri.empty()) throw InputError(file + ": <include> without <uri>" + Line(include));
    if (depth > kMaxIncludeDepth) throw InputError(where + ": includes nest deeper than " + std::to_string(kMaxIncludeDepth) + " (an include cycle?)");
    for (const XMLElement* e = include.FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "static") CheckStatic(*e, where);
      if (tag != "uri" && tag != "name" && tag != "pose" && tag != "static" && tag != "placement_frame" &&
          tag != "plugin") {
        RejectIfGeometry(*e, file, "<include> '" + uri + "'");
      }
    }
    const UriResolution resolved = ResolveIncludeUri(uri, file, search_);
    const std::optional<std::string>& target = resolved.path;
    if (!target) {
      const std::string message = where + ": cannot resolve <include><uri> " + uri + "; searched " +
                                  JoinSearched(resolved.searched) + SearchRule(uri);
      if (!options_.allow_missing) throw InputError(message);
      if (first_missing_.empty()) first_missing_ = message;
      missing_.push_back(uri + " (<include> in " + file + ")");
      return nullptr;
    }
    std::error_code ec;
    const std::string sdf_path = fs::is_directory(*target, ec) ? ModelSdfOf(*target, where) : *target;
    const XMLDocument& doc = Parse(sdf_path);
    const XMLElement* root = doc.RootElement();
    const XMLElement* model = root != nullptr ? root->FirstChildElement("model") : nullptr;
    if (model == nullptr) throw InputError(sdf_path + ": no <sdf><model> (included from " + file + ")");
    PoseSpec pose = include.FirstChildElement("pose") != nullptr ? ReadPose(include, where) : ReadPose(*model, sdf_path);
    const std::string placement = ElementText(include.FirstChildElement("placement_frame"));
    std::unique_ptr<ModelNode> node =
        BuildNode(*model, sdf_path, pose, placement.empty() ? Attribute(*model, "placement_frame") : placement, depth);
    if (const XMLElement* name = include.FirstChildElement("name")) {
      if (ElementText(name).empty()) throw InputError(where + ": empty <name>");
      node->name = ElementText(name);
    }
    include_uris_[node.get()] = uri;
    return node;
  }

  // Which lists the folders of an unresolved URI came from (model_path.h), for the user to fix.
  static std::string SearchRule(const std::string& uri) {
    if (StartsWith(uri, "model://") || StartsWith(uri, "package://")) {
      return " (the world's folder, --model-path, $OBJSCAN_MODEL_PATH, $GAZEBO_MODEL_PATH)";
    }
    const std::string path = StartsWith(uri, "file://") ? uri.substr(7) : uri;
    if (fs::path(path).is_absolute()) return " (an absolute path)";
    return " (the naming file's folder, $GAZEBO_RESOURCE_PATH, the parent of each model path folder, the world's "
           "package root)";
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

  void ReadState(const XMLElement& state) {
    for (const XMLElement* m = state.FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
      const std::string name = NameOf(*m, path_);
      state_[name] = ReadStateModel(*m, path_ + ": <state> model '" + name + "'");
    }
  }

  StatePoses ReadStateModel(const XMLElement& m, const std::string& where) const {
    StatePoses poses;
    poses.T_world_model = ReadPose(m, where).pose;
    if (const XMLElement* scale = m.FirstChildElement("scale")) {
      std::vector<double> v;
      if (!ParseNumbers(ElementText(scale), 3, &v)) throw InputError(where + ": <scale> is not 3 numbers");
      if (std::abs(v[0] - 1) > 1e-9 || std::abs(v[1] - 1) > 1e-9 || std::abs(v[2] - 1) > 1e-9) {
        throw InputError(where + ": a model <scale> other than 1 1 1 in <state> is not supported");
      }
    }
    for (const XMLElement* l = m.FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
      const std::string link_name = Attribute(*l, "name");
      if (!link_name.empty() && l->FirstChildElement("pose") != nullptr) {
        poses.T_world_link[link_name] = ReadPose(*l, where + " link '" + link_name + "'").pose;
      }
    }
    for (const XMLElement* n = m.FirstChildElement("model"); n; n = n->NextSiblingElement("model")) {
      const std::string nested_name = NameOf(*n, path_);
      poses.nested[nested_name] = ReadStateModel(*n, where + " model '" + nested_name + "'");
    }
    return poses;
  }

  const StatePoses* StateOf(const std::string& model_name) const {
    const auto it = state_.find(model_name);
    return it == state_.end() ? nullptr : &it->second;
  }

  // Adds the visuals of `node` and its nested models to `build`. T_top_node places the node in the
  // top-level model's frame; `state` (world-frame poses) overrides link and nested-model poses.
  void AddModelContent(const ModelNode& node, const Pose3& T_top_node, const StatePoses* state, ModelBuild* build) {
    const std::string top_name = build->name;
    if (const auto it = include_uris_.find(&node); it != include_uris_.end()) build->include_uris.push_back(it->second);
    for (const XMLElement* link : node.links) {
      const std::string link_name = Attribute(*link, "name");
      const std::string link_where = Where(top_name) + " link '" + link_name + "'";
      Pose3 T_node_link = node.frames->Resolve(link_name, link_where);
      if (state != nullptr) {
        const auto it = state->T_world_link.find(link_name);
        // State link poses are in the world frame.
        if (it != state->T_world_link.end()) T_node_link = state->T_world_model.inverse() * it->second;
      }
      for (const XMLElement* e = link->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string tag = e->Name();
        if (tag == "collision") continue;  // the sensor sees visuals; collisions are simplified copies
        if (tag != "visual") {
          RejectIfGeometry(*e, node.file, "link '" + link_name + "' of model '" + top_name + "'");
          continue;
        }
        const std::string where = Where(top_name) + " visual '" + Attribute(*e, "name") + "'";
        const PoseSpec visual_pose = ReadPose(*e, where);
        const Pose3 T_node_visual = visual_pose.relative_to.empty() || visual_pose.relative_to == link_name
                                        ? T_node_link * visual_pose.pose
                                        : node.frames->Resolve(visual_pose.relative_to, where) * visual_pose.pose;
        AddGeometry(*e, where, node.file, T_top_node * T_node_visual, build);
      }
    }
    for (const auto& child : node.children) {
      const StatePoses* child_state = nullptr;
      Pose3 T_top_child = T_top_node * node.frames->Resolve(child->name, Where(top_name));
      if (state != nullptr) {
        const auto it = state->nested.find(child->name);
        if (it != state->nested.end()) {
          child_state = &it->second;
          // Nested state poses are in the world frame too.
          T_top_child = build->T_world_model.inverse() * it->second.T_world_model;
        }
      }
      AddModelContent(*child, T_top_child, child_state, build);
    }
  }

  void AddGeometry(const XMLElement& visual, const std::string& where, const std::string& file,
                   const Pose3& T_model_visual, ModelBuild* build) {
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
    } else if (kind == "empty") {
      return;
    } else if (kind == "box") {
      if (!ParseNumbers(ElementText(shape->FirstChildElement("size")), 3, &v) || v[0] < 0 || v[1] < 0 || v[2] < 0) {
        throw InputError(where + ": <box><size> must be 3 non-negative numbers");
      }
      if (v[0] * v[1] * v[2] == 0.0) return;
      part = geometry::MakeBox(Eigen::Vector3d(v[0], v[1], v[2]));
    } else if (kind == "cylinder" || kind == "capsule") {
      std::vector<double> r, l;
      if (!ParseNumbers(ElementText(shape->FirstChildElement("radius")), 1, &r) ||
          !ParseNumbers(ElementText(shape->FirstChildElement("length")), 1, &l) || !(r[0] > 0) || !(l[0] > 0)) {
        throw InputError(where + ": <" + kind + "> needs positive <radius> and <length>");
      }
      part = geometry::MakeCylinder(r[0], l[0]);
      if (kind == "capsule") {
        // A capsule is the cylinder with a half sphere on each end (whole spheres: the inner halves
        // are hidden inside the cylinder).
        for (const double z : {-l[0] / 2, l[0] / 2}) {
          geometry::Append(geometry::Transformed(geometry::MakeSphere(r[0]),
                                                 Eigen::Affine3d(Eigen::Translation3d(0, 0, z))),
                           &part);
        }
      }
    } else if (kind == "sphere") {
      if (!ParseNumbers(ElementText(shape->FirstChildElement("radius")), 1, &v) || !(v[0] > 0)) {
        throw InputError(where + ": <sphere> needs a positive <radius>");
      }
      part = geometry::MakeSphere(v[0]);
    } else if (kind == "ellipsoid") {
      if (!ParseNumbers(ElementText(shape->FirstChildElement("radii")), 3, &v) || !(v[0] > 0 && v[1] > 0 && v[2] > 0)) {
        throw InputError(where + ": <ellipsoid> needs 3 positive <radii>");
      }
      part = geometry::Transformed(geometry::MakeSphere(1.0), Eigen::Affine3d(Eigen::Scaling(v[0], v[1], v[2])));
    } else if (kind == "mesh") {
      const std::string uri = ElementText(shape->FirstChildElement("uri"));
      if (uri.empty()) throw InputError(where + ": <mesh> without <uri>");
      if (shape->FirstChildElement("submesh") != nullptr) {
        // Loading the whole file would add geometry the world does not show.
        const std::string message = where + ": <mesh><submesh> of " + uri + " is not supported";
        if (!options_.allow_missing) throw InputError(message);
        missing_.push_back(uri + " <submesh> (model '" + build->name + "')");
        return;
      }
      build->mesh_uris.push_back(uri);
      Eigen::Vector3d scale(1, 1, 1);
      if (const XMLElement* s = shape->FirstChildElement("scale")) {
        if (!ParseNumbers(ElementText(s), 3, &v) || !(v[0] > 0 && v[1] > 0 && v[2] > 0)) {
          throw InputError(where + ": <scale> '" + ElementText(s) + "' must be 3 positive numbers");
        }
        scale = Eigen::Vector3d(v[0], v[1], v[2]);
      }
      const geometry::TriangleMesh* mesh =
          MeshFor(uri, where, file, shape->FirstChildElement("uri")->GetLineNum(), build->name);
      if (mesh == nullptr) return;  // recorded as missing
      T = T * Eigen::Scaling(scale);
      geometry::Append(geometry::Transformed(*mesh, T), &build->mesh);
      return;
    } else {
      const std::string message = where + ": unsupported geometry <" + kind + ">";
      if (!options_.allow_missing) throw InputError(message);
      missing_.push_back("<" + kind + "> (model '" + build->name + "')");
      return;
    }
    geometry::Append(geometry::Transformed(part, T), &build->mesh);
  }

  // The mesh behind a URI (cached: walls and repeated furniture share files). nullptr when missing
  // and allow_missing is set. Relative paths resolve against the folder of the file naming them.
  const geometry::TriangleMesh* MeshFor(const std::string& uri, const std::string& where, const std::string& file,
                                        int line, const std::string& model) {
    const UriResolution resolution = ResolveFileUri(uri, file, search_);
    const std::optional<std::string>& resolved = resolution.path;
    if (!resolved) {
      // The world names the model; the file naming the mesh (often an included model.sdf) is what to fix.
      const std::string message = where + ": cannot resolve <mesh><uri> " + uri + " (" +
                                  (file == path_ ? "" : "in " + file + ", ") + "line " + std::to_string(line) +
                                  "); searched " + JoinSearched(resolution.searched) + SearchRule(uri);
      if (!options_.allow_missing) throw InputError(message);
      if (first_missing_.empty()) first_missing_ = message;
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

  void Classify(const ModelBuild& build, world::SceneObject* object) {
    ModelIdentity identity;
    identity.name = build.name;
    identity.uris = build.include_uris;
    identity.uris.insert(identity.uris.end(), build.mesh_uris.begin(), build.mesh_uris.end());
    std::string id = build.mesh_uris.empty() ? "" : ModelIdOfUri(build.mesh_uris.front());
    if (id.empty()) id = StripInstanceSuffix(build.name);
    identity.model_id = id;
    identity.source_dir = world_dir_;
    object->model_name = id;
    std::optional<world::Category> category;
    try {
      category = category_map_->Lookup(identity);
    } catch (const InputError& e) {
      throw InputError(path_ + ": " + e.what());
    }
    if (category) {
      object->category = *category;
      return;
    }
    // No rule: a model named after a category ("chair_2") keeps it; anything else is `other`, listed.
    category = CategoryFromName(build.name);
    if (!category) category = world::ParseCategory(id);
    if (category && !world::IsStructural(*category)) {
      object->category = *category;
      return;
    }
    object->category = world::Category::kOther;
    unmapped_.push_back(build.name + " (" + (build.include_uris.empty() ? id : build.include_uris.front()) + ")");
  }

  static geometry::TriangleMesh FloorMesh(const std::vector<world::SceneObject>& objects, double z_m) {
    geometry::Aabb3 walls, furniture;
    for (const auto& o : objects) {
      if (o.category == world::Category::kCeiling) continue;
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
  CategoryMap* category_map_;
  std::string world_dir_;
  UriSearchPath search_;
  std::string first_missing_;  // the first unresolved URI's whole message (allow_missing)
  std::map<std::string, StatePoses> state_;
  std::map<std::string, std::unique_ptr<XMLDocument>> docs_;
  std::map<const ModelNode*, std::string> include_uris_;
  std::map<std::string, std::unique_ptr<geometry::TriangleMesh>> mesh_cache_;
  std::vector<std::string> missing_;
  std::vector<std::string> unmapped_;
};

}  // namespace

world::Scene LoadGazeboWorld(const std::string& path, const SceneLoadOptions& options) {
  options.Validate();
  CategoryMap category_map = CategoryMap::Load(ResolveCategoryMapPath(options.category_map));
  return WorldLoader(path, options, &category_map).Load();
}

}  // namespace objscan::io
