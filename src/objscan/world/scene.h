#pragma once
// The scene model: furniture objects and structure (floor, walls, ceiling), each a triangle mesh in its own
// frame (metres, Z up) with a pose in the world. Plain data plus queries; loaders live in io/ and
// world/procedural/.
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/geometry/aabb.h"
#include "objscan/geometry/mesh.h"
#include "objscan/geometry/pose.h"
#include "objscan/world/category.h"

namespace objscan::world {

// Instance id 0 means "no object" everywhere (background, invalid pixel).
constexpr std::int32_t kNoInstance = 0;

// How far from the origin a scene may reach. A room or a house spans metres to hundreds of metres;
// beyond this a file is corrupt, and the integer voxel grids of the map would overflow.
constexpr double kMaxSceneCoordinate_m = 1e4;

struct SceneObject {
  std::int32_t instance_id = kNoInstance;  // unique in the scene, > 0
  Category category = Category::kOther;
  std::string name;        // e.g. the Gazebo model name "403_0"
  std::string model_name;  // source model, e.g. SUNCG id "403" or "procedural/chair/17"
  geometry::TriangleMesh mesh;  // in the object frame
  geometry::Pose3 T_world_object = geometry::Pose3::Identity();

  bool IsStructural() const { return world::IsStructural(category); }
};

// One triangle soup for the ray caster: world-frame vertices, triangles and the instance id of
// each triangle.
struct TriangleSoup {
  std::vector<float> vertices_xyz;           // 3 floats per vertex
  std::vector<std::uint32_t> triangles;      // 3 indices per triangle
  std::vector<std::int32_t> triangle_instance;  // one per triangle
  std::size_t NumTriangles() const { return triangle_instance.size(); }
};

class Scene {
 public:
  Scene() = default;
  explicit Scene(std::string name) : name_(std::move(name)) {}

  const std::string& name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }

  // Adds an object; assigns the next free instance id when object.instance_id is kNoInstance.
  // Returns the instance id. Throws std::invalid_argument on a duplicate id.
  std::int32_t Add(SceneObject object);

  const std::vector<SceneObject>& objects() const { return objects_; }
  std::vector<SceneObject>& mutable_objects() { return objects_; }
  // nullptr when absent.
  const SceneObject* Find(std::int32_t instance_id) const;
  // Category of an instance; Category::kOther for unknown ids.
  Category CategoryOf(std::int32_t instance_id) const;

  // Bounds of the whole scene, of one object (world frame), of furniture only.
  geometry::Aabb3 Bounds() const;
  geometry::Aabb3 ObjectBounds(const SceneObject& object) const;
  geometry::Aabb3 FurnitureBounds() const;
  // Bounds of the walls (empty when there are none).
  geometry::Aabb3 StructureBounds(Category structural) const;

  std::size_t NumFurniture() const;
  std::size_t NumTriangles() const;
  TriangleSoup BuildTriangleSoup() const;

  // Meshes the loader could not resolve (kept so a scene loaded with --allow-missing can list them).
  std::vector<std::string>& missing_meshes() { return missing_meshes_; }
  const std::vector<std::string>& missing_meshes() const { return missing_meshes_; }
  // Models no category map rule matched (category `other`), as "name (source)".
  std::vector<std::string>& unmapped_models() { return unmapped_models_; }
  const std::vector<std::string>& unmapped_models() const { return unmapped_models_; }
  // True when the loader inferred the object instances itself (a ScanNet scan without its
  // aggregation: pieces grouped by proximity) instead of reading them from the file: metrics are
  // only as right as that guess.
  bool instances_inferred() const { return instances_inferred_; }
  void set_instances_inferred(bool inferred) { instances_inferred_ = inferred; }
  // What the loader changed or guessed, one sentence each (doors removed, instances inferred).
  std::vector<std::string>& load_notes() { return load_notes_; }
  const std::vector<std::string>& load_notes() const { return load_notes_; }

 private:
  std::string name_;
  std::vector<SceneObject> objects_;
  std::vector<std::string> missing_meshes_;
  std::vector<std::string> unmapped_models_;
  bool instances_inferred_ = false;
  std::vector<std::string> load_notes_;
};

}  // namespace objscan::world
