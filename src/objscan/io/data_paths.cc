#include "objscan/io/data_paths.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

// Set by src/objscan/io/CMakeLists.txt; the defaults keep the file compiling on its own.
#ifndef OBJSCAN_SOURCE_CONFIG_DIR
#define OBJSCAN_SOURCE_CONFIG_DIR "config"
#endif
#ifndef OBJSCAN_BUILD_DIR
#define OBJSCAN_BUILD_DIR ""
#endif
#ifndef OBJSCAN_CONFIG_FROM_BINDIR
#define OBJSCAN_CONFIG_FROM_BINDIR "../share/objscan/config"
#endif
#ifndef OBJSCAN_CONFIG_FROM_LIBDIR
#define OBJSCAN_CONFIG_FROM_LIBDIR "../share/objscan/config"
#endif

namespace objscan::io {
namespace fs = std::filesystem;

std::string LoadedModulePath() {
  Dl_info info{};
  // Any function of this file identifies the module (executable or shared library) it was loaded from.
  if (dladdr(reinterpret_cast<void*>(&LoadedModulePath), &info) == 0 || info.dli_fname == nullptr) return "";
  std::error_code ec;
  const fs::path path = fs::canonical(info.dli_fname, ec);
  return ec ? std::string(info.dli_fname) : path.string();
}

namespace {

bool IsBelow(const fs::path& path, const fs::path& folder) {
  if (folder.empty()) return false;
  const fs::path relative = path.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

std::string FindConfigDir() {
  const std::string module = LoadedModulePath();
  if (module.empty()) return OBJSCAN_SOURCE_CONFIG_DIR;
  std::error_code ec;
  const fs::path build = fs::weakly_canonical(OBJSCAN_BUILD_DIR, ec);
  if (!ec && IsBelow(fs::path(module), build)) return OBJSCAN_SOURCE_CONFIG_DIR;
  const fs::path dir = fs::path(module).parent_path();
  const fs::path from_lib = (dir / OBJSCAN_CONFIG_FROM_LIBDIR).lexically_normal();
  const fs::path from_bin = (dir / OBJSCAN_CONFIG_FROM_BINDIR).lexically_normal();
  if (fs::is_directory(from_lib, ec)) return from_lib.string();
  if (fs::is_directory(from_bin, ec)) return from_bin.string();
  return from_bin.string();
}

}  // namespace

std::string ConfigDir() {
  if (const char* env = std::getenv("OBJSCAN_CONFIG_DIR"); env != nullptr && *env != '\0') return env;
  // The module does not move while it runs: look once.
  static const std::string dir = FindConfigDir();
  return dir;
}

std::string ResolveConfigPath(const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (fs::path(ConfigDir()) / path).string();
}

}  // namespace objscan::io
