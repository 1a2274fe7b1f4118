#pragma once
// SUNCG model ids -> objscan categories, in two steps: ModelCategoryMapping.csv (from the SUNCG /
// OASC data: model_id -> fine_grained_class, coarse_grained_class, nyuv2_40class) and our table
// config/suncg_categories.csv (SUNCG class -> objscan category, with a '*' default row).
#include <optional>
#include <string>
#include <unordered_map>

#include "objscan/io/data_paths.h"  // ConfigDir, ResolveConfigPath (relative table paths)
#include "objscan/world/category.h"

namespace objscan::io {


struct SuncgClasses {
  std::string fine_grained;
  std::string coarse_grained;
  std::string nyuv2_40;
};

// ModelCategoryMapping.csv.
class SuncgModelMapping {
 public:
  // Throws InputError naming the file on a missing file, missing columns or a malformed row.
  static SuncgModelMapping Load(const std::string& path);
  // Searches `start_dir` and its parents for ModelCategoryMapping.csv; empty when there is none.
  static std::string Find(const std::string& start_dir);

  const SuncgClasses* Lookup(const std::string& model_id) const;
  const std::string& path() const { return path_; }
  std::size_t size() const { return by_id_.size(); }

 private:
  std::string path_;
  std::unordered_map<std::string, SuncgClasses> by_id_;
};

// config/suncg_categories.csv: rows `suncg_class,category`, '#' comments, a header line
// `suncg_class,category`, and optionally a '*' row as the default.
class SuncgCategoryTable {
 public:
  // Throws InputError naming the file and line on a missing file, a duplicate class or a category
  // that objscan does not know.
  static SuncgCategoryTable Load(const std::string& path);

  // Fine class first, then coarse, then NYUv2-40, then '*'; nullopt when nothing matches.
  std::optional<world::Category> Lookup(const SuncgClasses& classes) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::unordered_map<std::string, world::Category> by_class_;
};

// "403_0" -> "403", "s__871_2" -> "s__871", "chair" -> "chair": Gazebo appends _N to copies.
std::string StripInstanceSuffix(const std::string& model_name);

}  // namespace objscan::io
