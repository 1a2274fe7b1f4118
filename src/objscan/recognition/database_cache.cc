#include "objscan/recognition/database_cache.h"

#include <filesystem>

#include "objscan/common/error.h"

namespace objscan::recognition {

CachedDatabaseStatus EnsureCachedDatabase(const std::string& path, const std::function<ModelDatabase()>& build,
                                          const std::function<void(const CachedDatabaseStatus&)>& before_build) {
  CachedDatabaseStatus status;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    try {
      ModelDatabase::Verify(path);
      return status;
    } catch (const InputError& e) {
      // A cache is ours to replace: a damaged one is rebuilt (the atomic save replaces it whole).
      status.damage = e.what();
    }
  }
  status.built = true;
  if (before_build) before_build(status);
  build().Save(path);
  return status;
}

}  // namespace objscan::recognition
