#pragma once
// A model database file kept as a cache (the built-in procedural database in ~/.cache/objscan, the
// databases `objscan bench` builds for some methods): used when its checksum verifies, built and
// saved atomically when it is missing, and rebuilt when it is damaged (truncated, bit-flipped, an
// older format), never used damaged.
#include <functional>
#include <string>

#include "objscan/recognition/model_database.h"

namespace objscan::recognition {

struct CachedDatabaseStatus {
  bool built = false;     // the file was (re)built by this call
  std::string damage;     // why an existing file was rejected and rebuilt (the InputError text); "" if not
};

// Makes `path` a valid database file: keeps it when ModelDatabase::Verify accepts it, otherwise builds
// one with `build` and saves it atomically (the folder must exist). `before_build` (optional) is called
// once, with the returned status so far, before a build starts (the app prints its messages there).
// Throws what `build` or Save throws.
CachedDatabaseStatus EnsureCachedDatabase(const std::string& path, const std::function<ModelDatabase()>& build,
                                          const std::function<void(const CachedDatabaseStatus&)>& before_build = nullptr);

}  // namespace objscan::recognition
