#include "objscan/recognition/default_database.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/model_database.h"
#include "objscan/io/category_map.h"
#include "objscan/io/data_paths.h"
#include "objscan/io/sweethome3d.h"
#include "objscan/recognition/sweethome3d_sources.h"

namespace objscan::recognition {
namespace {

constexpr int kDefaultDatabaseVariants = 8;
// Every style of each category's generator in the built-in database, each style's models the size
// medoids of its pool models (database_builder.h). Over the 60 procedural rooms of seeds 1-12, every
// style gave coverage 72.4% against 69.1% with the first eight seeds (docs/results/db-sampling-2026-11-24.md); the medoids
// brought shelves and filing cabinets of the rooms' middle heights into it (be00778, 2026-11-25).
constexpr ProceduralSampling kDefaultDatabaseSampling = ProceduralSampling::kStyleMedoids;

// FNV-1a of the builder revision and the build options as YAML (and `extra`): a changed builder or
// default (the pre-segmentation's adjacency, say) names a new cache file instead of reusing a database
// built the old way.
std::string BuildOptionsKey(const DatabaseBuildOptions& options, const std::string& extra = "") {
  std::uint64_t hash = 1469598103934665603ull;
  const std::string key =
      "builder " + std::to_string(kDatabaseBuilderRevision) + "\n" + config::ToYaml(config::Dump(options)) + extra;
  for (const unsigned char c : key) {
    hash = (hash ^ c) * 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%08llx", static_cast<unsigned long long>(hash & 0xffffffffull));
  return buf;
}

}  // namespace

std::string DefaultDatabaseCacheDir() {
  if (const char* d = std::getenv("OBJSCAN_CACHE_DIR")) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::string(d) + "/objscan";
  if (const char* h = std::getenv("HOME")) return std::string(h) + "/.cache/objscan";
  return ".objscan-cache";
}

std::string DefaultDatabasePathIn(const std::string& cache_dir) {
  const DatabaseBuildOptions options;
  return cache_dir + "/procedural-v" + std::to_string(ModelDatabase::kFormatVersion) + "-n" +
         std::to_string(kDefaultDatabaseVariants) + "-" + ProceduralSamplingName(kDefaultDatabaseSampling) + "-" +
         BuildOptionsKey(options) + ".db";
}

namespace {

using BeforeBuild = std::function<void(const CachedDatabaseStatus& status, const std::string& path)>;

// The database at `path` in `cache_dir`, valid (database_cache.h): the folder is made when missing,
// temporaries of a killed build are removed, and `build` runs when the file is missing or damaged.
std::string EnsureBuiltInDatabase(const std::string& cache_dir, const std::string& path,
                                  const std::function<ModelDatabase()>& build, const BeforeBuild& before_build) {
  std::error_code ec;
  std::filesystem::create_directories(cache_dir, ec);
  if (ec) throw InputError(cache_dir + ": cannot create the database cache folder: " + ec.message());
  // Temporaries of a build that was killed (io/atomic_file.h).
  io::RemoveStaleTempFiles(cache_dir);
  EnsureCachedDatabase(path, build, [&](const CachedDatabaseStatus& status) {
    if (before_build) before_build(status, path);
  });
  return path;
}

}  // namespace

std::string EnsureDefaultDatabase(const std::string& cache_dir, const ProgressCallback& progress,
                                  const BeforeBuild& before_build) {
  return EnsureBuiltInDatabase(
      cache_dir, DefaultDatabasePathIn(cache_dir),
      [&] {
        return BuildDatabase(ProceduralModelSources(kDefaultDatabaseVariants, 0, kDefaultDatabaseSampling),
                             DatabaseBuildOptions(), progress);
      },
      before_build);
}

namespace {

// What the real database is made of, for its cache name: the category map's text and each catalog's
// name and size.
std::string RealDatabaseContentKey(const std::vector<std::string>& catalogs, const std::string& map_path) {
  std::ifstream map(map_path, std::ios::binary);
  std::string key((std::istreambuf_iterator<char>(map)), std::istreambuf_iterator<char>());
  for (const std::string& c : catalogs) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(c, ec);
    key += "\n" + std::filesystem::path(c).filename().string() + " " + std::to_string(ec ? 0 : size);
  }
  return key;
}

}  // namespace

std::string RealDatabasePathIn(const std::string& cache_dir) {
  const std::vector<std::string> catalogs = SweetHome3dCatalogsOf("sweethome3d");
  const std::string map_path = io::ResolveCategoryMapPath(kSweetHome3dCategoryMap);
  const DatabaseBuildOptions options;
  return cache_dir + "/sweethome3d-v" + std::to_string(ModelDatabase::kFormatVersion) + "-" +
         BuildOptionsKey(options, RealDatabaseContentKey(catalogs, map_path)) + ".db";
}

std::string EnsureRealDatabase(const std::string& cache_dir, const ProgressCallback& progress,
                               const BeforeBuild& before_build) {
  return EnsureBuiltInDatabase(
      cache_dir, RealDatabasePathIn(cache_dir),
      [&] {
        const io::CategoryMap map = io::CategoryMap::Load(io::ResolveCategoryMapPath(kSweetHome3dCategoryMap));
        const SweetHome3dSources sh3d = SweetHome3dModelSources(SweetHome3dCatalogsOf("sweethome3d"), map);
        return BuildDatabase(sh3d.sources, DatabaseBuildOptions(), progress);
      },
      before_build);
}

std::vector<std::string> ResolveTrainingDatabases(const std::vector<std::string>& names, const std::string& cache_dir,
                                                  const ProgressCallback& progress, const BeforeBuild& before_build) {
  std::vector<std::string> paths;
  paths.reserve(names.size());
  for (const std::string& name : names) {
    if (name == "procedural") {
      paths.push_back(EnsureDefaultDatabase(cache_dir, progress, before_build));
    } else if (name == "sweethome3d") {
      paths.push_back(EnsureRealDatabase(cache_dir, progress, before_build));
    } else {
      paths.push_back(name);
    }
  }
  return paths;
}

bool UsesProceduralDatabase(const std::string& scene_spec) { return scene_spec.rfind("procedural:", 0) == 0; }

std::uint64_t DatabaseMemoryLimitBytes(double max_database_memory_mb) {
  if (max_database_memory_mb > 0.0) return static_cast<std::uint64_t>(max_database_memory_mb * 1024.0 * 1024.0);
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

}  // namespace objscan::recognition
