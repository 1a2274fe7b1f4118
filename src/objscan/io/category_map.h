#pragma once
// Category maps: which objscan category a scene model is, from its name, the URIs it uses or its
// labels. A map is a YAML file (config/categories/*.yaml):
//
//   include: [suncg.yaml, aws-robomaker.yaml]   # optional; their rules come first, in this order
//   rules:                                      # tried in order, the first that matches wins
//     - {name: '^valve_wall', category: wall}   # ECMAScript regex searched in the instance name
//     - {uri: 'drc_practice_valve_wall', category: wall}  # ... in any URI the model uses
//     - {label: '^(kitchen )?cabinets?$', category: cabinet}  # ... in any label (ScanNet, NYU40)
//     - {suncg: ../suncg_categories.csv}        # SUNCG id via ModelCategoryMapping.csv + this table
//
//     - {label: '^Vehicles$', category: skip}  # leave the model out (model databases; see Match)
//
// Patterns ignore case. A rule with several of name/uri/label needs all of them to match. Paths
// (include, suncg) are relative to the map file. The `suncg` rule looks the model id up in the
// ModelCategoryMapping.csv found in the scene's folder or one of its parents (the OASC layout) and
// maps its class through the table (see suncg_categories.h); it does not match when there is no
// such file or the id is not in it.
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "objscan/world/category.h"

namespace objscan::io {

// What a category map looks at for one model.
struct ModelIdentity {
  std::string name;                 // instance name, e.g. "403_0", "Bed_01_001", "chair_12"
  std::vector<std::string> uris;    // <include> and mesh URIs the model uses
  std::vector<std::string> labels;  // semantic labels (ScanNet raw category, NYU40 class name)
  std::string model_id;             // SUNCG id: model://ID/... of the first mesh, else name without _N
  std::string source_dir;           // folder of the scene file (ModelCategoryMapping.csv is searched from here)
};

// What the first matching rule of a map says.
struct CategoryRuleMatch {
  bool skip = false;                        // `category: skip`: leave the model out
  std::optional<world::Category> category;  // the category otherwise
};

class CategoryMap {
 public:
  CategoryMap();
  ~CategoryMap();
  CategoryMap(CategoryMap&&) noexcept;
  CategoryMap& operator=(CategoryMap&&) noexcept;

  // Throws InputError naming the file (and rule) on a missing file, malformed YAML, an unknown key,
  // a bad regex, an unknown category or an include cycle.
  static CategoryMap Load(const std::string& path);

  // The category of the first matching rule; nullopt when no rule matches or the first that matches
  // is a `skip` rule (scene loaders treat it as unmatched). Throws InputError when a SUNCG class has no
  // category in the rule's table.
  std::optional<world::Category> Lookup(const ModelIdentity& model) const;
  // The first matching rule's category or skip; nullopt when no rule matches. Same errors as Lookup.
  std::optional<CategoryRuleMatch> Match(const ModelIdentity& model) const;

  const std::string& path() const { return path_; }
  std::size_t NumRules() const;

 private:
  struct Rule;
  struct SuncgCache;
  void LoadFile(const std::string& path, std::vector<std::string>* stack);

  std::string path_;
  std::vector<Rule> rules_;
  std::unique_ptr<SuncgCache> suncg_cache_;
};

// The file a --category-map / scene.category_map value names: as given when that file exists (a
// user's map, relative to the working folder), else relative to the project's config/ folder
// (config/categories/*.yaml ship there). Throws InputError when neither exists.
std::string ResolveCategoryMapPath(const std::string& path);

// The category of a model not matched by any rule: the category its name says when the name (without
// a trailing _N) is an objscan object category ("chair_2" -> chair), else nullopt (`other`, listed).
std::optional<world::Category> CategoryFromName(const std::string& name);

}  // namespace objscan::io
