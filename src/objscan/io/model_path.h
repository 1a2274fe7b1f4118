#pragma once
// Resolution of Gazebo model:// URIs: model://NAME/rest is looked up as DIR/NAME/rest in the
// world's own folder first, then in each folder of SceneLoadOptions::model_path, then
// $OBJSCAN_MODEL_PATH, then $GAZEBO_MODEL_PATH (each a colon-separated list).
#include <optional>
#include <string>
#include <vector>

namespace objscan::io {

// The ordered folder list for a world in `world_dir`.
std::vector<std::string> ModelSearchPath(const std::string& world_dir, const std::string& model_path);

// Resolves a model://, file:// or plain path (relative to `world_dir`). nullopt when no file exists.
std::optional<std::string> ResolveModelUri(const std::string& uri, const std::string& world_dir,
                                           const std::vector<std::string>& search_path);
// Folder of a model://NAME (or model://NAME/...) URI; nullopt when not found.
std::optional<std::string> ResolveModelFolder(const std::string& uri, const std::vector<std::string>& search_path);

}  // namespace objscan::io
