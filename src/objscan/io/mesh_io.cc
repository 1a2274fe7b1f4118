#include "objscan/io/mesh_io.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "objscan/common/error.h"

namespace objscan::io {
namespace {

std::string LowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Exact-position vertex welding: formats such as COLLADA split vertices by texture coordinate and
// normal; we keep geometry only.
struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey& o) const { return std::memcmp(bits, o.bits, sizeof(bits)) == 0; }
};
struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return h;
  }
};

class MeshBuilder {
 public:
  explicit MeshBuilder(geometry::TriangleMesh* mesh) : mesh_(mesh) {}

  int Vertex(const Eigen::Vector3f& p) {
    PositionKey key;
    for (int k = 0; k < 3; ++k) {
      const float v = p[k] == 0.0f ? 0.0f : p[k];  // -0 and +0 weld together
      std::memcpy(&key.bits[k], &v, 4);
    }
    const auto [it, inserted] = index_.emplace(key, static_cast<int>(mesh_->vertices.size()));
    if (inserted) mesh_->vertices.push_back(p);
    return it->second;
  }

 private:
  geometry::TriangleMesh* mesh_;
  std::unordered_map<PositionKey, int, PositionKeyHash> index_;
};

void AddNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& T_parent, MeshBuilder* builder,
             geometry::TriangleMesh* mesh) {
  const aiMatrix4x4 T = T_parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& am = *scene.mMeshes[node.mMeshes[m]];
    std::vector<int> remap(am.mNumVertices);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const aiVector3D p = T * am.mVertices[v];
      remap[v] = builder->Vertex(Eigen::Vector3f(p.x, p.y, p.z));
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      const Eigen::Vector3i t(remap[face.mIndices[0]], remap[face.mIndices[1]], remap[face.mIndices[2]]);
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      mesh->triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) AddNode(scene, *node.mChildren[c], T, builder, mesh);
}

}  // namespace

void MeshLoadOptions::Validate() const {
  if (up_axis != "auto" && up_axis != "z" && up_axis != "y") {
    throw ConfigError("up_axis: '" + up_axis + "' is not one of auto, z, y");
  }
  if (!(scale > 0.0)) throw ConfigError("scale: must be > 0");
}

bool IsMeshFile(const std::string& path) {
  static const char* kExtensions[] = {".obj", ".ply", ".off", ".dae", ".stl", ".gltf", ".glb"};
  const std::string ext = LowerExtension(path);
  return std::any_of(std::begin(kExtensions), std::end(kExtensions), [&](const char* e) { return ext == e; });
}

geometry::TriangleMesh LoadMesh(const std::string& path) { return LoadMesh(path, MeshLoadOptions()); }

geometry::TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options) {
  options.Validate();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": mesh file not found");
  const std::string ext = LowerExtension(path);
  if (!IsMeshFile(path)) {
    throw InputError(path + ": unsupported mesh format '" + ext + "' (expected obj, ply, off, dae, stl, gltf, glb)");
  }

  Assimp::Importer importer;
  // Gazebo ignores COLLADA <up_axis>; so do we (Assimp would otherwise rotate Z_UP files to Y-up).
  // Assimp still applies <unit meter=...> at the root, which is what Gazebo does too.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    // Assimp rejects files whose every mesh was dropped (no faces, only points/lines).
    if (reason.find("No meshes") != std::string::npos) throw InputError(path + ": mesh has no triangles");
    throw InputError(path + ": cannot read mesh (" + (reason.empty() ? std::string("unknown error") : reason) + ")");
  }

  geometry::TriangleMesh mesh;
  MeshBuilder builder(&mesh);
  AddNode(*scene, *scene->mRootNode, aiMatrix4x4(), &builder, &mesh);
  if (mesh.triangles.empty()) throw InputError(path + ": mesh has no triangles");

  const bool y_up = options.up_axis == "y" || (options.up_axis == "auto" && (ext == ".gltf" || ext == ".glb"));
  if (y_up || options.scale != 1.0) {
    const float s = static_cast<float>(options.scale);
    for (auto& v : mesh.vertices) {
      // +90 deg about X: (x, y, z) -> (x, -z, y), so the file's +Y becomes our +Z.
      v = y_up ? Eigen::Vector3f(s * v.x(), -s * v.z(), s * v.y()) : Eigen::Vector3f(s * v);
    }
  }
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) throw InputError(path + ": mesh has non-finite vertex coordinates");
  }
  return mesh;
}

geometry::TriangleMesh LoadMeshFromMemory(const std::string& bytes, const std::string& extension,
                                          const std::string& where) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(),
                                                     aiProcess_Triangulate | aiProcess_SortByPType, extension.c_str());
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(where + ": cannot read mesh (" + (reason.empty() ? std::string("unknown error") : reason) + ")");
  }
  geometry::TriangleMesh mesh;
  MeshBuilder builder(&mesh);
  AddNode(*scene, *scene->mRootNode, aiMatrix4x4(), &builder, &mesh);
  if (mesh.triangles.empty()) throw InputError(where + ": mesh has no triangles");
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) throw InputError(where + ": mesh has non-finite vertex coordinates");
  }
  return mesh;
}

}  // namespace objscan::io
