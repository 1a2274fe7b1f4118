#include "objscan/io/scannet.h"

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "objscan/common/error.h"
#include "objscan/io/ply.h"
#include "objscan/io/scannet_instances.h"

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kMeshSuffix = "_vh_clean_2.ply";
constexpr int kNoObject = -1;

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The mesh file of a spec: the file itself, or the one *_vh_clean_2.ply in the folder.
std::string MeshFileOf(const std::string& spec) {
  std::error_code ec;
  if (fs::is_regular_file(spec, ec)) return EndsWith(spec, kMeshSuffix) ? spec : "";
  if (!fs::is_directory(spec, ec)) return "";
  const std::string by_name = (fs::path(spec) / (fs::path(spec).lexically_normal().filename().string() + kMeshSuffix)).string();
  if (fs::is_regular_file(by_name, ec)) return by_name;
  std::string found;
  for (const auto& entry : fs::directory_iterator(spec, ec)) {
    const std::string name = entry.path().filename().string();
    if (EndsWith(name, kMeshSuffix) && (found.empty() || entry.path().string() < found)) found = entry.path().string();
  }
  return found;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    std::string reason = e.what();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(path + ": malformed JSON: " + reason);
  }
}

// An instance of the ground truth: its label and the category the map gives it.
struct Instance {
  std::string name;
  std::string label;
  world::Category category = world::Category::kOther;
};

// Ground truth from the aggregation: vertex -> segment group.
void InstancesFromAggregation(const std::string& aggregation_path, const std::string& segs_path,
                              std::size_t num_vertices, std::vector<Instance>* instances,
                              std::vector<int>* vertex_instance) {
  const nlohmann::json segs = ReadJson(segs_path);
  if (!segs.is_object() || !segs.contains("segIndices") || !segs["segIndices"].is_array()) {
    throw InputError(segs_path + ": no \"segIndices\" array");
  }
  const auto& seg_indices = segs["segIndices"];
  if (seg_indices.size() != num_vertices) {
    throw InputError(segs_path + ": " + std::to_string(seg_indices.size()) + " segIndices for a mesh of " +
                     std::to_string(num_vertices) + " vertices");
  }
  const nlohmann::json aggregation = ReadJson(aggregation_path);
  if (!aggregation.is_object() || !aggregation.contains("segGroups") || !aggregation["segGroups"].is_array()) {
    throw InputError(aggregation_path + ": no \"segGroups\" array");
  }
  std::unordered_map<std::int64_t, int> instance_of_segment;
  int index = 0;
  for (const auto& group : aggregation["segGroups"]) {
    const std::string where = aggregation_path + ": segGroups[" + std::to_string(index++) + "]";
    if (!group.is_object() || !group.contains("label") || !group["label"].is_string() || !group.contains("segments") ||
        !group["segments"].is_array()) {
      throw InputError(where + ": needs a string \"label\" and a \"segments\" array");
    }
    Instance instance;
    instance.label = group["label"].get<std::string>();
    const std::int64_t object_id =
        group.contains("objectId") && group["objectId"].is_number_integer() ? group["objectId"].get<std::int64_t>() : index - 1;
    instance.name = instance.label + "_" + std::to_string(object_id);
    std::replace(instance.name.begin(), instance.name.end(), ' ', '_');
    const int id = static_cast<int>(instances->size());
    instances->push_back(instance);
    for (const auto& segment : group["segments"]) {
      if (!segment.is_number_integer()) throw InputError(where + ": segments must be integers");
      // A segment in two groups (rare annotation overlap) stays with the first.
      instance_of_segment.emplace(segment.get<std::int64_t>(), id);
    }
  }
  vertex_instance->assign(num_vertices, kNoObject);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (!seg_indices[v].is_number_integer()) throw InputError(segs_path + ": segIndices must be integers");
    const auto it = instance_of_segment.find(seg_indices[v].get<std::int64_t>());
    if (it != instance_of_segment.end()) (*vertex_instance)[v] = it->second;
  }
}

// The per-vertex NYU40 labels of labels.ply (0 = none), checked against the mesh.
std::vector<std::int32_t> ReadVertexLabels(const std::string& labels_path, const PlyData& mesh) {
  const PlyData labelled = ReadPly(labels_path);
  const std::vector<std::int32_t>* labels = nullptr;
  for (const auto& property : labelled.int_properties) {
    if (property.first == "label") labels = &property.second;
  }
  if (labels == nullptr) throw InputError(labels_path + ": vertices have no 'label' property");
  if (labels->size() != mesh.points.size()) {
    throw InputError(labels_path + ": " + std::to_string(labels->size()) + " labelled vertices for a mesh of " +
                     std::to_string(mesh.points.size()) + " vertices");
  }
  for (const std::int32_t label : *labels) {
    if (label != 0 && Nyu40ClassName(label).empty()) {
      throw InputError(labels_path + ": label " + std::to_string(label) + " is not an NYU40 class id (1-40)");
    }
  }
  return *labels;
}

// axisAlignment from the scan's .txt; nullopt when the file or the line is absent.
std::optional<Eigen::Matrix4d> ReadAxisAlignment(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = line.substr(0, eq);
    key.erase(std::remove_if(key.begin(), key.end(), [](unsigned char c) { return std::isspace(c); }), key.end());
    if (key != "axisAlignment") continue;
    std::stringstream ss(line.substr(eq + 1));
    std::vector<double> values;
    double v;
    while (ss >> v) values.push_back(v);
    if (values.size() != 16 || !ss.eof() ||
        !std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); })) {
      throw InputError(path + ": axisAlignment is not 16 numbers (a row-major 4x4 matrix)");
    }
    Eigen::Matrix4d M;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) M(r, c) = values[static_cast<std::size_t>(4 * r + c)];
    if (M.row(3).cwiseAbs().sum() - 1.0 > 1e-6 || std::abs(M(3, 3) - 1.0) > 1e-6 ||
        std::abs(M.topLeftCorner<3, 3>().determinant() - 1.0) > 1e-3) {
      throw InputError(path + ": axisAlignment is not a rigid transform");
    }
    return M;
  }
  return std::nullopt;
}

// Applies the levelling transform and refuses a scan whose levelled vertices are out of range (before
// instance inference grids them).
void LevelScan(const Eigen::Affine3d& T_level, const std::string& mesh_path, std::vector<Eigen::Vector3f>* points) {
  for (auto& p : *points) {
    const Eigen::Vector3d levelled = T_level * p.cast<double>();
    if (!levelled.allFinite() || levelled.cwiseAbs().maxCoeff() > world::kMaxSceneCoordinate_m) {
      throw InputError(mesh_path + ": vertex coordinates beyond " + std::to_string(static_cast<int>(world::kMaxSceneCoordinate_m)) +
                       " m once levelled (not a room scan)");
    }
    p = levelled.cast<float>();
  }
}

// The transform that levels the scan: floor horizontal and at z = 0.
Eigen::Affine3d LevellingTransform(const std::vector<Eigen::Vector3f>& points, const std::vector<bool>& is_floor,
                                   const std::optional<Eigen::Matrix4d>& axis_alignment) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  std::vector<Eigen::Vector3d> floor;
  for (std::size_t v = 0; v < points.size(); ++v) {
    if (is_floor[v]) floor.push_back(points[v].cast<double>());
  }
  if (axis_alignment) {
    T.matrix() = *axis_alignment;
  } else if (floor.size() >= 3) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : floor) centroid += p;
    centroid /= static_cast<double>(floor.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const auto& p : floor) covariance += (p - centroid) * (p - centroid).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    Eigen::Vector3d normal = solver.eigenvectors().col(0);  // smallest eigenvalue first
    // Up is the side the rest of the scan is on.
    std::size_t above = 0;
    for (const auto& p : points) above += normal.dot(p.cast<double>() - centroid) > 0.0;
    if (above * 2 < points.size()) normal = -normal;
    const Eigen::Quaterniond level = Eigen::Quaterniond::FromTwoVectors(normal, Eigen::Vector3d::UnitZ());
    T = Eigen::Translation3d(centroid) * level * Eigen::Translation3d(-centroid);
  }
  double floor_z = 0.0;
  if (!floor.empty()) {
    std::vector<double> z;
    z.reserve(floor.size());
    for (const auto& p : floor) z.push_back((T * p).z());
    std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
    floor_z = z[z.size() / 2];
  } else {
    floor_z = std::numeric_limits<double>::infinity();
    for (const auto& p : points) floor_z = std::min(floor_z, (T * p.cast<double>()).z());
  }
  return Eigen::Translation3d(0, 0, -floor_z) * T;
}

}  // namespace

std::string Nyu40ClassName(int label) {
  static const char* kNames[41] = {"",           "wall",          "floor",         "cabinet",     "bed",
                                   "chair",      "sofa",          "table",         "door",        "window",
                                   "bookshelf",  "picture",       "counter",       "blinds",      "desk",
                                   "shelves",    "curtain",       "dresser",       "pillow",      "mirror",
                                   "floor mat",  "clothes",       "ceiling",       "books",       "refrigerator",
                                   "television", "paper",         "towel",         "shower curtain", "box",
                                   "whiteboard", "person",        "night stand",   "toilet",      "sink",
                                   "lamp",       "bathtub",       "bag",           "otherstructure", "otherfurniture",
                                   "otherprop"};
  return label >= 0 && label <= 40 ? kNames[label] : "";
}

bool IsScanNetSpec(const std::string& spec) { return !MeshFileOf(spec).empty(); }

world::Scene LoadScanNetScan(const std::string& spec, const SceneLoadOptions& options, const CategoryMap& categories) {
  options.Validate();
  const std::string mesh_path = MeshFileOf(spec);
  if (mesh_path.empty()) throw InputError(spec + ": no *" + std::string(kMeshSuffix) + " (not a ScanNet scan)");
  const std::string file_name = fs::path(mesh_path).filename().string();
  const std::string scan_id = file_name.substr(0, file_name.size() - std::string(kMeshSuffix).size());
  const fs::path dir = fs::path(mesh_path).parent_path();
  const auto sibling = [&](const std::string& suffix) { return (dir / (scan_id + suffix)).string(); };
  const std::string aggregation_path = sibling(".aggregation.json");
  const std::string segs_path = sibling("_vh_clean_2.0.010000.segs.json");
  const std::string labels_path = sibling("_vh_clean_2.labels.ply");
  const std::string meta_path = sibling(".txt");

  PlyData mesh = ReadPly(mesh_path);
  if (mesh.triangles.empty()) throw InputError(mesh_path + ": the scan has no faces");
  for (const auto& p : mesh.points) {
    if (!p.allFinite()) throw InputError(mesh_path + ": non-finite vertex coordinates");
  }

  std::error_code ec;
  world::Scene scene(scan_id);
  // The category of a label, and whether the map knows it (else `other`, listed once per instance).
  const auto category_of = [&](const std::string& name, const std::string& label) -> std::optional<world::Category> {
    ModelIdentity identity;
    identity.name = name;
    identity.labels = {label};
    identity.source_dir = dir.string();
    std::optional<world::Category> category = categories.Lookup(identity);
    if (!category) {
      std::string snake = label;
      std::replace(snake.begin(), snake.end(), ' ', '_');
      category = world::ParseCategory(snake);
    }
    return category;
  };
  const auto add_instance = [&](Instance instance, std::vector<Instance>* instances) {
    const std::optional<world::Category> category = category_of(instance.name, instance.label);
    if (!category) scene.unmapped_models().push_back(instance.name + " (label '" + instance.label + "')");
    instance.category = category.value_or(world::Category::kOther);
    instances->push_back(std::move(instance));
  };

  std::vector<Instance> instances;
  std::vector<int> vertex_instance;
  std::vector<bool> is_floor(mesh.points.size(), false);
  const std::optional<Eigen::Matrix4d> axis_alignment = ReadAxisAlignment(meta_path);
  if (fs::is_regular_file(aggregation_path, ec)) {
    if (!fs::is_regular_file(segs_path, ec)) throw InputError(aggregation_path + ": its segments file " + segs_path + " is missing");
    std::vector<Instance> annotated;
    InstancesFromAggregation(aggregation_path, segs_path, mesh.points.size(), &annotated, &vertex_instance);
    for (Instance& instance : annotated) add_instance(std::move(instance), &instances);
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      const int i = vertex_instance[v];
      is_floor[v] = i != kNoObject && instances[static_cast<std::size_t>(i)].category == world::Category::kFloor;
    }
    LevelScan(LevellingTransform(mesh.points, is_floor, axis_alignment), mesh_path, &mesh.points);
  } else if (fs::is_regular_file(labels_path, ec)) {
    // No instances in the files: level the scan on its floor labels, then group the labelled pieces
    // into objects (scannet_instances.h).
    const std::vector<std::int32_t> labels = ReadVertexLabels(labels_path, mesh);
    std::map<std::int32_t, bool> label_is_floor;
    for (std::size_t v = 0; v < labels.size(); ++v) {
      if (labels[v] == 0) continue;
      auto it = label_is_floor.find(labels[v]);
      if (it == label_is_floor.end()) {
        const std::string name = Nyu40ClassName(labels[v]);
        it = label_is_floor.emplace(labels[v], category_of(name, name) == world::Category::kFloor).first;
      }
      is_floor[v] = it->second;
    }
    LevelScan(LevellingTransform(mesh.points, is_floor, axis_alignment), mesh_path, &mesh.points);
    const InferredInstances inferred = InferInstancesFromLabels(mesh.points, mesh.triangles, labels);
    vertex_instance = inferred.vertex_instance;
    std::map<std::string, int> count_of_label;
    for (const int label : inferred.instance_label) {
      Instance instance;
      instance.label = Nyu40ClassName(label);
      instance.name = instance.label + "_" + std::to_string(count_of_label[instance.label]++);
      std::replace(instance.name.begin(), instance.name.end(), ' ', '_');
      add_instance(std::move(instance), &instances);
    }
    scene.set_instances_inferred(true);
    scene.load_notes().push_back("instances inferred: no " + fs::path(aggregation_path).filename().string() +
                                 "; the pieces of one label in " + fs::path(labels_path).filename().string() +
                                 " closer than a few centimetres or stacked in one footprint are one object");
  } else if (options.allow_missing) {
    vertex_instance.assign(mesh.points.size(), kNoObject);
    LevelScan(LevellingTransform(mesh.points, is_floor, axis_alignment), mesh_path, &mesh.points);
  } else {
    throw InputError(mesh_path + ": no ground truth (needs " + fs::path(aggregation_path).filename().string() + " + " +
                     fs::path(segs_path).filename().string() + ", or " + fs::path(labels_path).filename().string() + ")");
  }

  // Triangles to instances: the instance of at least two of the three vertices, else of the first.
  const int unannotated = static_cast<int>(instances.size());
  std::vector<std::vector<int>> triangles_of(instances.size() + 1);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const int a = vertex_instance[tri[0]], b = vertex_instance[tri[1]], c = vertex_instance[tri[2]];
    int owner = (a == b || a == c) ? a : (b == c ? b : a);
    if (owner == kNoObject) owner = unannotated;
    triangles_of[static_cast<std::size_t>(owner)].push_back(static_cast<int>(t));
  }

  std::vector<world::SceneObject> objects;
  for (std::size_t i = 0; i <= instances.size(); ++i) {
    if (triangles_of[i].empty()) continue;
    world::SceneObject object;
    if (i < instances.size()) {
      object.name = instances[i].name;
      object.model_name = instances[i].label;
      object.category = instances[i].category;
    } else {
      object.name = "unannotated";
      object.model_name = "unannotated";
      object.category = world::Category::kOther;
    }
    // Vertices in the object frame: the object's footprint centre at floor height.
    geometry::Aabb3 box;
    std::unordered_map<int, int> remap;
    for (const int t : triangles_of[i]) {
      Eigen::Vector3i local;
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.triangles[static_cast<std::size_t>(t)][k];
        const auto [it, inserted] = remap.emplace(v, static_cast<int>(object.mesh.vertices.size()));
        if (inserted) {
          object.mesh.vertices.push_back(mesh.points[static_cast<std::size_t>(v)]);
          box.Extend(mesh.points[static_cast<std::size_t>(v)].cast<double>());
        }
        local[k] = it->second;
      }
      object.mesh.triangles.push_back(local);
    }
    const Eigen::Vector3d origin(box.Center().x(), box.Center().y(), box.min_m.z());
    for (auto& v : object.mesh.vertices) v -= origin.cast<float>();
    object.T_world_object = geometry::Pose3(Eigen::Translation3d(origin));
    objects.push_back(std::move(object));
  }

  // Structure first (floor, walls, ceiling), then objects in annotation order.
  const bool has_floor = std::any_of(objects.begin(), objects.end(), [](const world::SceneObject& o) {
    return o.category == world::Category::kFloor;
  });
  if (!has_floor) {
    // Nothing labelled floor: a floor under the scan's footprint so the robot has somewhere to stand.
    geometry::Aabb3 box;
    for (const auto& p : mesh.points) box.Extend(p.cast<double>());
    world::SceneObject floor;
    floor.category = world::Category::kFloor;
    floor.name = "floor";
    floor.model_name = "floor";
    floor.mesh = geometry::MakeQuadXY(box.min_m.x(), box.min_m.y(), box.max_m.x(), box.max_m.y());
    scene.Add(std::move(floor));
  }
  std::stable_partition(objects.begin(), objects.end(), [](const world::SceneObject& o) { return o.IsStructural(); });
  for (auto& object : objects) scene.Add(std::move(object));
  return scene;
}

}  // namespace objscan::io
