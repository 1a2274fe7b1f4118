#include "objscan/io/model_path.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Appends `dir` unless it is empty or already listed (compared after normalisation).
void AddOnce(const std::string& dir, std::vector<std::string>* out) {
  if (dir.empty()) return;
  std::string normal = fs::path(dir).lexically_normal().string();
  while (normal.size() > 1 && normal.back() == '/') normal.pop_back();
  if (normal.empty()) normal = ".";
  if (std::find(out->begin(), out->end(), normal) == out->end()) out->push_back(normal);
}

std::vector<std::string> ColonList(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ':')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

std::vector<std::string> EnvList(const char* var) {
  const char* value = std::getenv(var);
  return value != nullptr ? ColonList(value) : std::vector<std::string>();
}

// The parent of a folder as written ("a/models/" -> "a", "models" -> "."); "" for the root.
std::string ParentOf(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.has_filename() == false) p = p.parent_path();  // "a/models/" normalises to "a/models/"
  if (p == p.root_path()) return "";
  const fs::path parent = p.parent_path();
  return parent.empty() ? "." : parent.string();
}

// The nearest folder at or above `world_dir` holding a package.xml (a ROS package's root), else
// the parent of `world_dir` (the PKG of PKG/worlds/x.world).
std::string PackageRootOf(const std::string& world_dir) {
  std::error_code ec;
  fs::path dir = fs::absolute(world_dir, ec).lexically_normal();
  if (ec) return ParentOf(world_dir);
  if (!dir.has_filename()) dir = dir.parent_path();
  for (fs::path d = dir;; d = d.parent_path()) {
    if (fs::is_regular_file(d / "package.xml", ec)) {
      // Said relative to the world's folder as the user wrote it, so messages stay readable.
      const fs::path relative = d.lexically_relative(dir);
      return (fs::path(world_dir) / relative).lexically_normal().string();
    }
    if (d == d.root_path() || d.parent_path() == d) break;
  }
  return ParentOf(world_dir);
}

std::string FolderOf(const std::string& file) {
  const std::string dir = fs::path(file).parent_path().string();
  return dir.empty() ? "." : dir;
}

enum class Want { kFile, kFolder, kEither };

bool Exists(const fs::path& p, Want want) {
  std::error_code ec;
  if (want != Want::kFolder && fs::is_regular_file(p, ec)) return true;
  return want != Want::kFile && fs::is_directory(p, ec);
}

// Looks `relative` up below each of `dirs`.
UriResolution Search(const std::string& relative, const std::vector<std::string>& dirs, Want want) {
  UriResolution r;
  for (const std::string& dir : dirs) {
    r.searched.push_back(dir);
    const fs::path candidate = fs::path(dir) / relative;
    if (Exists(candidate, want)) {
      r.path = candidate.lexically_normal().string();
      return r;
    }
  }
  return r;
}

// file://, plain paths: absolute as given, relative beside the naming file, then the resource path.
UriResolution ResolvePath(const std::string& uri, const std::string& naming_file, const UriSearchPath& search,
                          Want want) {
  const std::string path = StartsWith(uri, "file://") ? uri.substr(7) : uri;
  if (path.empty()) return {};
  if (fs::path(path).is_absolute()) {
    UriResolution r;
    r.searched.push_back(path);
    if (Exists(path, want)) r.path = fs::path(path).lexically_normal().string();
    return r;
  }
  std::vector<std::string> dirs;
  AddOnce(FolderOf(naming_file), &dirs);
  for (const std::string& d : search.resource_dirs) AddOnce(d, &dirs);
  return Search(path, dirs, want);
}

// model://NAME/rest or package://NAME/rest: the rest of the URI below the model path.
std::optional<std::string> ModelRelative(const std::string& uri) {
  std::string rest;
  if (StartsWith(uri, "model://")) {
    rest = uri.substr(8);
  } else if (StartsWith(uri, "package://")) {
    rest = uri.substr(10);
  } else {
    return std::nullopt;
  }
  while (!rest.empty() && rest.back() == '/') rest.pop_back();
  return rest;
}

}  // namespace

UriSearchPath MakeUriSearchPath(const std::string& world_path, const std::string& model_path) {
  UriSearchPath search;
  const std::string world_dir = FolderOf(world_path);
  AddOnce(world_dir, &search.model_dirs);
  std::vector<std::string> model_folders = ColonList(model_path);
  for (const char* var : {"OBJSCAN_MODEL_PATH", "GAZEBO_MODEL_PATH"}) {
    for (const std::string& d : EnvList(var)) model_folders.push_back(d);
  }
  for (const std::string& d : model_folders) AddOnce(d, &search.model_dirs);
  for (const std::string& d : EnvList("GAZEBO_RESOURCE_PATH")) AddOnce(d, &search.resource_dirs);
  for (const std::string& d : model_folders) AddOnce(ParentOf(d), &search.resource_dirs);
  AddOnce(PackageRootOf(world_dir), &search.resource_dirs);
  return search;
}

UriResolution ResolveFileUri(const std::string& uri, const std::string& naming_file, const UriSearchPath& search) {
  if (const std::optional<std::string> rest = ModelRelative(uri)) {
    if (rest->empty()) return {};
    return Search(*rest, search.model_dirs, Want::kFile);
  }
  return ResolvePath(uri, naming_file, search, Want::kFile);
}

UriResolution ResolveIncludeUri(const std::string& uri, const std::string& naming_file, const UriSearchPath& search) {
  if (const std::optional<std::string> rest = ModelRelative(uri)) {
    if (rest->empty()) return {};
    return Search(*rest, search.model_dirs, Want::kFolder);  // a model is a folder
  }
  return ResolvePath(uri, naming_file, search, Want::kEither);
}

std::string JoinSearched(const std::vector<std::string>& searched) {
  if (searched.empty()) return "nothing";
  std::string out;
  for (const std::string& s : searched) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace objscan::io
