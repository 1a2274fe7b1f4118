#pragma once
// Gazebo's resolution of the URIs a world and its models name (as gazebo classic's SystemPaths does,
// plus objscan's own first look beside the naming file):
// - model://NAME/rest: DIR/NAME/rest for DIR in the model path: the world's own folder, then each
//   folder of SceneLoadOptions::model_path, then $OBJSCAN_MODEL_PATH, then $GAZEBO_MODEL_PATH (each a
//   colon-separated list). package://PKG/rest is read as model://PKG/rest.
// - file://REL or a plain relative path REL: the folder of the file naming it first, then DIR/REL for
//   DIR in the resource path: each folder of $GAZEBO_RESOURCE_PATH, the parent of each model path
//   folder (a model folder `PKG/models` makes `file://models/...` of PKG resolve, as the AWS RoboMaker
//   worlds write their meshes), then the world's package root (the nearest folder above the world
//   holding a ROS package.xml, else the world folder's parent).
// - file:///ABS or /ABS: as given.
#include <optional>
#include <string>
#include <vector>

namespace objscan::io {

// The folders a world's URIs are looked up in, in search order, each listed once.
struct UriSearchPath {
  std::vector<std::string> model_dirs;     // for model:// and package://
  std::vector<std::string> resource_dirs;  // for relative file:// and plain paths, after the naming file's folder
};

// The search path of the world file `world_path` with the extra model folders `model_path`
// (colon-separated) and the environment as it is now.
UriSearchPath MakeUriSearchPath(const std::string& world_path, const std::string& model_path);

// What looking up one URI found: the file or folder (nullopt when none exists) and every folder
// that was searched, in order (the absolute path itself for an absolute URI).
struct UriResolution {
  std::optional<std::string> path;
  std::vector<std::string> searched;
};

// A mesh (or any file) named by `uri` in the file `naming_file`.
UriResolution ResolveFileUri(const std::string& uri, const std::string& naming_file, const UriSearchPath& search);
// The target of an <include>: a model folder (model://NAME, package://NAME) or a folder or SDF file
// (file://, plain path), named in `naming_file`.
UriResolution ResolveIncludeUri(const std::string& uri, const std::string& naming_file, const UriSearchPath& search);

// "DIR1, DIR2, ..." for error messages (", " joined; "nothing" when empty).
std::string JoinSearched(const std::vector<std::string>& searched);

}  // namespace objscan::io
