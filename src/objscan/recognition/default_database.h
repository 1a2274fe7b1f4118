#pragma once
// The built-in procedural model database of `objscan run` and `objscan bench` (and of the Python
// module): every style of each category's generator, built once and cached in a file named after
// the database format, the builder revision and the build options, so a changed builder never reuses
// a stale cache.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "objscan/common/progress.h"
#include "objscan/recognition/database_cache.h"

namespace objscan::recognition {

// $OBJSCAN_CACHE_DIR, else $XDG_CACHE_HOME/objscan, else $HOME/.cache/objscan, else .objscan-cache.
std::string DefaultDatabaseCacheDir();

// The path of the built-in database in `cache_dir` (nothing is built or checked).
std::string DefaultDatabasePathIn(const std::string& cache_dir);

// Makes the built-in database valid in `cache_dir` (created when missing; built when missing or
// damaged, database_cache.h) and returns its path. `before_build` (optional) is called once before a
// build starts, with the status so far (its `damage` says why a file was rejected) and the path;
// `progress` reports the build. Throws InputError naming the folder when it cannot be created.
std::string EnsureDefaultDatabase(
    const std::string& cache_dir, const ProgressCallback& progress = nullptr,
    const std::function<void(const CachedDatabaseStatus& status, const std::string& path)>& before_build = nullptr);

// The built-in real database: every piece of furniture of the Sweet Home 3D catalogs
// (io::SweetHome3dCatalogDir(), Debian's sweethome3d-furniture) that config/categories/sweethome3d.yaml
// names, the default of every scene that is not procedural. Its file in `cache_dir` is named after the
// database format, the builder revision and options, the category map's text and the catalogs' names
// and sizes, so a changed catalog or map builds a new one. Throws InputError naming the folder when
// no catalog is found (install sweethome3d-furniture, or pass --db).
std::string RealDatabasePathIn(const std::string& cache_dir);
std::string EnsureRealDatabase(
    const std::string& cache_dir, const ProgressCallback& progress = nullptr,
    const std::function<void(const CachedDatabaseStatus& status, const std::string& path)>& before_build = nullptr);

// The files `names` stand for, as recognition.classifier.extra_training_databases lists them: the
// words "procedural" and "sweethome3d" are the built-in procedural and real databases (made valid in
// `cache_dir` like EnsureDefaultDatabase and EnsureRealDatabase; `progress` and `before_build` as there),
// any other name is a database file, returned as it is.
std::vector<std::string> ResolveTrainingDatabases(
    const std::vector<std::string>& names, const std::string& cache_dir, const ProgressCallback& progress = nullptr,
    const std::function<void(const CachedDatabaseStatus& status, const std::string& path)>& before_build = nullptr);

// The built-in database for a scene: the procedural one for procedural:CATEGORY:SEED scenes, the real
// one for every other scene (Gazebo worlds, mesh scenes, scans).
bool UsesProceduralDatabase(const std::string& scene_spec);

// The memory limit of a model database in bytes (ModelDatabase::Load): `max_database_memory_mb`
// (recognition.max_database_memory_mb), or when that is 0 the memory the machine has available now
// (MemAvailable; 0 = no limit when unknown).
std::uint64_t DatabaseMemoryLimitBytes(double max_database_memory_mb);

}  // namespace objscan::recognition
