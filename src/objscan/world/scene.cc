#include "objscan/world/scene.h"

#include <stdexcept>

namespace objscan::world {

std::int32_t Scene::Add(SceneObject object) {
  if (object.instance_id == kNoInstance) {
    std::int32_t next = 1;
    for (const auto& o : objects_) next = std::max(next, o.instance_id + 1);
    object.instance_id = next;
  } else if (Find(object.instance_id) != nullptr) {
    throw std::invalid_argument("duplicate instance id " + std::to_string(object.instance_id));
  }
  objects_.push_back(std::move(object));
  return objects_.back().instance_id;
}

const SceneObject* Scene::Find(std::int32_t instance_id) const {
  for (const auto& o : objects_) {
    if (o.instance_id == instance_id) return &o;
  }
  return nullptr;
}

Category Scene::CategoryOf(std::int32_t instance_id) const {
  const SceneObject* o = Find(instance_id);
  return o ? o->category : Category::kOther;
}

geometry::Aabb3 Scene::ObjectBounds(const SceneObject& object) const {
  return geometry::Bounds(object.mesh, object.T_world_object);
}

geometry::Aabb3 Scene::Bounds() const {
  geometry::Aabb3 box;
  for (const auto& o : objects_) box.Extend(ObjectBounds(o));
  return box;
}

geometry::Aabb3 Scene::FurnitureBounds() const {
  geometry::Aabb3 box;
  for (const auto& o : objects_) {
    if (!o.IsStructural()) box.Extend(ObjectBounds(o));
  }
  return box;
}

geometry::Aabb3 Scene::StructureBounds(Category structural) const {
  geometry::Aabb3 box;
  for (const auto& o : objects_) {
    if (o.category == structural) box.Extend(ObjectBounds(o));
  }
  return box;
}

std::size_t Scene::NumFurniture() const {
  std::size_t n = 0;
  for (const auto& o : objects_) n += o.IsStructural() ? 0 : 1;
  return n;
}

std::size_t Scene::NumTriangles() const {
  std::size_t n = 0;
  for (const auto& o : objects_) n += o.mesh.NumTriangles();
  return n;
}

TriangleSoup Scene::BuildTriangleSoup() const {
  TriangleSoup soup;
  soup.vertices_xyz.reserve(3 * NumTriangles());
  soup.triangles.reserve(3 * NumTriangles());
  soup.triangle_instance.reserve(NumTriangles());
  for (const auto& o : objects_) {
    const std::uint32_t offset = static_cast<std::uint32_t>(soup.vertices_xyz.size() / 3);
    for (const auto& v : o.mesh.vertices) {
      const Eigen::Vector3d w = o.T_world_object * v.cast<double>();
      soup.vertices_xyz.push_back(static_cast<float>(w.x()));
      soup.vertices_xyz.push_back(static_cast<float>(w.y()));
      soup.vertices_xyz.push_back(static_cast<float>(w.z()));
    }
    const bool flip = o.T_world_object.linear().determinant() < 0.0;
    for (const auto& t : o.mesh.triangles) {
      soup.triangles.push_back(offset + static_cast<std::uint32_t>(t[0]));
      soup.triangles.push_back(offset + static_cast<std::uint32_t>(flip ? t[2] : t[1]));
      soup.triangles.push_back(offset + static_cast<std::uint32_t>(flip ? t[1] : t[2]));
      soup.triangle_instance.push_back(o.instance_id);
    }
  }
  return soup;
}

}  // namespace objscan::world
