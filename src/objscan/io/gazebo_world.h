#pragma once
// Gazebo SDF worlds (.world) as objscan scenes.
//
// Each <model> (also <include>d models and models inserted by the world's <state>) becomes one
// SceneObject: all its visuals merged into one mesh in the model frame (T_model_link *
// T_link_visual * mesh scale), T_world_object = the model pose. When the world carries a <state>
// (worlds saved from Gazebo do), its model and link poses win over the <model> definitions, as
// Gazebo applies them when it loads the world. Geometry: mesh (see mesh_io.h for axis and unit
// conventions), box, cylinder, sphere; <plane> (ground_plane) is replaced by a floor quad at the
// plane's height, sized to the walls' extent plus kFloorMarginM (or the furniture's when there are no
// walls). Walls are the drc_practice_valve_wall / valve_wall* models. Furniture categories: the
// SUNCG model id (from model://ID/... or the model name "ID_k") through ModelCategoryMapping.csv
// (searched in the world's folder and its parents) and SceneLoadOptions::suncg_category_table;
// without a mapping, a model named after an objscan category ("chair_2") gets that category, any
// other model `other`.
#include <string>

#include "objscan/io/scene_spec.h"
#include "objscan/world/scene.h"

namespace objscan::io {

constexpr double kFloorMarginM = 0.5;

// Throws InputError with one line naming the world file and the element on bad input. With
// options.allow_missing, unresolved or unreadable meshes are listed in Scene::missing_meshes().
world::Scene LoadGazeboWorld(const std::string& path, const SceneLoadOptions& options);

}  // namespace objscan::io
