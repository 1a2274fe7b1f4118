#include "objscan/io/model_path.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

void AppendColonList(const std::string& list, std::vector<std::string>* out) {
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ':')) {
    if (!item.empty()) out->push_back(item);
  }
}

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

std::vector<std::string> ModelSearchPath(const std::string& world_dir, const std::string& model_path) {
  std::vector<std::string> dirs;
  dirs.push_back(world_dir.empty() ? "." : world_dir);
  AppendColonList(model_path, &dirs);
  for (const char* var : {"OBJSCAN_MODEL_PATH", "GAZEBO_MODEL_PATH"}) {
    if (const char* env = std::getenv(var)) AppendColonList(env, &dirs);
  }
  return dirs;
}

std::optional<std::string> ResolveModelUri(const std::string& uri, const std::string& world_dir,
                                           const std::vector<std::string>& search_path) {
  std::error_code ec;
  if (StartsWith(uri, "model://")) {
    const std::string rest = uri.substr(8);
    if (rest.empty()) return std::nullopt;
    for (const std::string& dir : search_path) {
      const fs::path candidate = fs::path(dir) / rest;
      if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal().string();
    }
    return std::nullopt;
  }
  std::string path = StartsWith(uri, "file://") ? uri.substr(7) : uri;
  fs::path p(path);
  if (p.is_relative()) p = fs::path(world_dir.empty() ? "." : world_dir) / p;
  if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  return std::nullopt;
}

std::optional<std::string> ResolveModelFolder(const std::string& uri, const std::vector<std::string>& search_path) {
  if (!StartsWith(uri, "model://")) return std::nullopt;
  std::string name = uri.substr(8);
  while (!name.empty() && name.back() == '/') name.pop_back();
  if (name.empty()) return std::nullopt;
  std::error_code ec;
  for (const std::string& dir : search_path) {
    const fs::path candidate = fs::path(dir) / name;
    if (fs::is_directory(candidate, ec)) return candidate.lexically_normal().string();
  }
  return std::nullopt;
}

}  // namespace objscan::io
