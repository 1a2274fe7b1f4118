#pragma once
// Gazebo SDF worlds (.world) as objscan scenes, read with our own SDF reader (tinyxml2).
//
// Each top-level <model> or <include> of the world (and each model inserted by the world's <state>)
// becomes one SceneObject: all its visuals, of its links and of every model nested or included in it
// at any depth, merged into one mesh in the model frame; T_world_object = the model pose.
// Covered: <include> anywhere (model://NAME through model.config / model.sdf, file://DIR, a path;
// <name>, <pose>, <static>, <placement_frame> of the include), nested <model>s, <pose relative_to>
// with SDF 1.7+ frame semantics (links, nested models, <frame attached_to>, joints, `A::B` scoped
// names, `__model__`; frame='' of SDF 1.5/1.6 read the same way), <static>, mesh <scale>, mesh files
// of any extension case (.DAE), model://, file:// and relative URIs (relative to the file naming
// them), and <state> poses (model, link and nested model poses, in the world frame, win over the
// definitions as Gazebo applies them on load). Collisions are skipped (the sensor sees visuals).
// Geometry: mesh (see mesh_io.h for axis and unit conventions), box, cylinder, sphere, capsule,
// ellipsoid; <plane> (ground_plane) is replaced by a floor quad at the plane's height, sized to the
// walls' extent plus kFloorMarginM (or the furniture's when there are no walls).
// Anything else that carries geometry (an <actor>, a <heightmap>, a <mesh><submesh>, an unknown
// element holding visuals or models) is an error naming the file and element, or with allow_missing
// an entry of Scene::missing_meshes(): never dropped silently.
// Categories: SceneLoadOptions::category_map (category_map.h) over the model's name and the URIs it
// uses; no rule: a model named after an objscan category ("chair_2") gets it, any other `other`,
// listed in Scene::unmapped_models().
#include <string>

#include "objscan/io/scene_spec.h"
#include "objscan/world/scene.h"

namespace objscan::io {

constexpr double kFloorMarginM = 0.5;

// Throws InputError with one line naming the world file and the element on bad input. With
// options.allow_missing, unresolved or unreadable meshes are listed in Scene::missing_meshes().
world::Scene LoadGazeboWorld(const std::string& path, const SceneLoadOptions& options);

}  // namespace objscan::io
