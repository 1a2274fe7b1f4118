#include "objscan/io/category_map.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "objscan/common/error.h"
#include "objscan/io/suncg_categories.h"

namespace objscan::io {
namespace fs = std::filesystem;

struct CategoryMap::Rule {
  std::string where;  // "FILE: rule N" for messages
  std::optional<std::regex> name, uri, label;
  std::optional<world::Category> category;
  bool skip = false;        // `category: skip`
  std::string suncg_table;  // non-empty: a SUNCG rule
};

// SUNCG lookups load their CSVs once per map (a world has hundreds of models).
struct CategoryMap::SuncgCache {
  std::map<std::string, std::string> mapping_file_of_dir;  // scene folder -> ModelCategoryMapping.csv ("" none)
  std::map<std::string, std::unique_ptr<SuncgModelMapping>> mappings;
  std::map<std::string, std::unique_ptr<SuncgCategoryTable>> tables;
};

namespace {

bool SearchAny(const std::regex& re, const std::vector<std::string>& texts) {
  return std::any_of(texts.begin(), texts.end(), [&](const std::string& t) { return std::regex_search(t, re); });
}

std::regex CompilePattern(const YAML::Node& node, const std::string& where, const char* key) {
  const std::string pattern = node.as<std::string>();
  try {
    return std::regex(pattern, std::regex::ECMAScript | std::regex::icase | std::regex::optimize);
  } catch (const std::regex_error& e) {
    throw InputError(where + ": " + key + " '" + pattern + "' is not a valid regular expression (" + e.what() + ")");
  }
}

}  // namespace

CategoryMap::CategoryMap() : suncg_cache_(std::make_unique<SuncgCache>()) {}
CategoryMap::~CategoryMap() = default;
CategoryMap::CategoryMap(CategoryMap&&) noexcept = default;
CategoryMap& CategoryMap::operator=(CategoryMap&&) noexcept = default;

std::size_t CategoryMap::NumRules() const { return rules_.size(); }

CategoryMap CategoryMap::Load(const std::string& path) {
  CategoryMap map;
  map.path_ = path;
  std::vector<std::string> stack;
  map.LoadFile(path, &stack);
  return map;
}

void CategoryMap::LoadFile(const std::string& path, std::vector<std::string>* stack) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": category map not found");
  const std::string canonical = fs::weakly_canonical(path, ec).string();
  if (std::find(stack->begin(), stack->end(), canonical) != stack->end()) {
    throw InputError(path + ": category map includes itself (include cycle)");
  }
  stack->push_back(canonical);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    std::string reason = e.what();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(path + ": malformed YAML: " + reason);
  }
  if (!root.IsMap()) throw InputError(path + ": a category map is a YAML mapping with 'rules' (and 'include')");
  const fs::path dir = fs::path(path).parent_path();
  const auto relative = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (dir / p).string(); };
  const auto include_file = [&](const std::string& name) {
    const std::string included = relative(name);
    if (!fs::is_regular_file(included, ec)) throw InputError(path + ": included category map " + included + " not found");
    LoadFile(included, stack);
  };
  try {
    for (const auto& entry : root) {
      const std::string key = entry.first.as<std::string>();
      if (key != "include" && key != "rules") {
        throw InputError(path + ": unknown key '" + key + "' (a category map has 'include' and 'rules')");
      }
    }
    if (const YAML::Node include = root["include"]) {
      if (include.IsScalar()) {
        include_file(include.as<std::string>());
      } else if (include.IsSequence()) {
        for (const auto& item : include) include_file(item.as<std::string>());
      } else {
        throw InputError(path + ": 'include' must be a file name or a list of file names");
      }
    }
    const YAML::Node rules = root["rules"];
    if (rules && !rules.IsSequence()) throw InputError(path + ": 'rules' must be a list");
    int index = 0;
    for (const auto& node : rules) {
      ++index;
      Rule rule;
      rule.where = path + ": rule " + std::to_string(index);
      if (!node.IsMap()) throw InputError(rule.where + ": a rule is a mapping such as {name: REGEX, category: CAT}");
      for (const auto& field : node) {
        const std::string key = field.first.as<std::string>();
        if (key == "name") {
          rule.name = CompilePattern(field.second, rule.where, "name");
        } else if (key == "uri") {
          rule.uri = CompilePattern(field.second, rule.where, "uri");
        } else if (key == "label") {
          rule.label = CompilePattern(field.second, rule.where, "label");
        } else if (key == "category") {
          const std::string name = field.second.as<std::string>();
          rule.skip = name == "skip";
          rule.category = world::ParseCategory(name);
          if (!rule.category && !rule.skip) {
            throw InputError(rule.where + ": unknown category '" + name + "' (a category name or 'skip')");
          }
        } else if (key == "suncg") {
          rule.suncg_table = relative(field.second.as<std::string>());
          if (!fs::is_regular_file(rule.suncg_table, ec)) {
            throw InputError(rule.where + ": SUNCG category table " + rule.suncg_table + " not found");
          }
        } else {
          throw InputError(rule.where + ": unknown key '" + key + "' (one of name, uri, label, category, suncg)");
        }
      }
      const bool has_pattern = rule.name || rule.uri || rule.label;
      if (!rule.suncg_table.empty()) {
        if (has_pattern || rule.category || rule.skip) throw InputError(rule.where + ": a 'suncg' rule has no other keys");
      } else if (!has_pattern || !(rule.category || rule.skip)) {
        throw InputError(rule.where + ": a rule needs a pattern (name, uri or label) and a category");
      }
      rules_.push_back(std::move(rule));
    }
  } catch (const YAML::Exception& e) {
    std::string reason = e.what();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(path + ": malformed category map: " + reason);
  }
  stack->pop_back();
}

std::optional<world::Category> CategoryMap::Lookup(const ModelIdentity& model) const {
  const std::optional<CategoryRuleMatch> match = Match(model);
  if (!match || match->skip) return std::nullopt;
  return match->category;
}

std::optional<CategoryRuleMatch> CategoryMap::Match(const ModelIdentity& model) const {
  for (const Rule& rule : rules_) {
    if (!rule.suncg_table.empty()) {
      SuncgCache& cache = *suncg_cache_;
      auto dir_it = cache.mapping_file_of_dir.find(model.source_dir);
      if (dir_it == cache.mapping_file_of_dir.end()) {
        dir_it = cache.mapping_file_of_dir.emplace(model.source_dir, SuncgModelMapping::Find(model.source_dir)).first;
      }
      if (dir_it->second.empty()) continue;
      auto& mapping = cache.mappings[dir_it->second];
      if (!mapping) mapping = std::make_unique<SuncgModelMapping>(SuncgModelMapping::Load(dir_it->second));
      const SuncgClasses* classes = mapping->Lookup(model.model_id);
      if (classes == nullptr) continue;
      auto& table = cache.tables[rule.suncg_table];
      if (!table) table = std::make_unique<SuncgCategoryTable>(SuncgCategoryTable::Load(rule.suncg_table));
      const std::optional<world::Category> category = table->Lookup(*classes);
      if (!category) {
        throw InputError("model '" + model.name + "': SUNCG class '" + classes->fine_grained + "' of model id '" +
                         model.model_id + "' has no objscan category in " + table->path());
      }
      return CategoryRuleMatch{false, category};
    }
    if (rule.name && !std::regex_search(model.name, *rule.name)) continue;
    if (rule.uri && !SearchAny(*rule.uri, model.uris)) continue;
    if (rule.label && !SearchAny(*rule.label, model.labels)) continue;
    return CategoryRuleMatch{rule.skip, rule.category};
  }
  return std::nullopt;
}

std::string ResolveCategoryMapPath(const std::string& path) {
  std::error_code ec;
  if (path.empty()) throw InputError("category map: empty path");
  if (fs::is_regular_file(path, ec)) return path;
  const std::string in_config = ResolveConfigPath(path);
  if (fs::is_regular_file(in_config, ec)) return in_config;
  throw InputError(path + ": category map not found (also looked in " + ConfigDir() + ")");
}

std::optional<world::Category> CategoryFromName(const std::string& name) {
  const std::optional<world::Category> category = world::ParseCategory(StripInstanceSuffix(name));
  if (category && !world::IsStructural(*category)) return category;
  return std::nullopt;
}

}  // namespace objscan::io
