#pragma once
// Triangle meshes from files through Assimp (obj, ply, off, dae, stl, gltf/glb): every node's
// transform applied, polygons triangulated, in metres with Z up.
//
// Axis conventions (UpAxis::kAuto):
//  - COLLADA (.dae): `<unit meter=...>` is honoured and `<up_axis>` is ignored, exactly as Gazebo's
//    ColladaLoader does. The SUNCG meshes of the OASC worlds declare Y_UP but their vertex data is
//    already Z-up (their collision boxes and the floor contact prove it), and the Z_UP inch-based
//    drc_practice_valve_wall comes out 1.2192 m wide and 2.4384 m tall, standing upright.
//  - glTF/glb: Y-up by specification, rotated to Z-up.
//  - obj, ply, off, stl: no convention; taken as Z-up.
#include <string>

#include "objscan/geometry/mesh.h"

namespace objscan::io {

struct MeshLoadOptions {
  // "auto" (per format, see above), "z" (file is Z-up: keep) or "y" (file is Y-up: rotate +90 deg
  // about X so that +Y becomes +Z).
  std::string up_axis = "auto";
  // Extra uniform scale applied after the unit conversion.
  double scale = 1.0;

  template <class V>
  void Visit(V& v) {
    v("up_axis", up_axis);
    v("scale", scale);
  }
  void Validate() const;
};

// Throws InputError naming the file when it is missing, unreadable or holds no triangles.
geometry::TriangleMesh LoadMesh(const std::string& path);
geometry::TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options);

// A mesh held in memory (e.g. an entry of a zip archive) through Assimp's ReadFileFromMemory, in the
// file's own coordinates (no unit or up-axis conversion; files it references are not loaded).
// `extension` is the format hint ("3ds", "dae", "obj"); `where` names the source in errors. Throws
// InputError naming `where` when Assimp cannot read it or it holds no triangles.
geometry::TriangleMesh LoadMeshFromMemory(const std::string& bytes, const std::string& extension,
                                          const std::string& where);

// True for the extensions LoadMesh understands (case-insensitive): obj ply off dae stl gltf glb.
bool IsMeshFile(const std::string& path);

}  // namespace objscan::io
