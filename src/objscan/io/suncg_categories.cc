#include "objscan/io/suncg_categories.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "objscan/common/error.h"

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

std::vector<std::string> SplitCsvLine(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> fields;
  std::string field;
  std::stringstream ss(line);
  while (std::getline(ss, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string Trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

}  // namespace

SuncgModelMapping SuncgModelMapping::Load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open SUNCG model category mapping");
  SuncgModelMapping mapping;
  mapping.path_ = path;
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ": empty file");
  const std::vector<std::string> header = SplitCsvLine(line);
  int col_id = -1, col_fine = -1, col_coarse = -1, col_nyu = -1;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string h = Trim(header[i]);
    if (h == "model_id") col_id = static_cast<int>(i);
    if (h == "fine_grained_class") col_fine = static_cast<int>(i);
    if (h == "coarse_grained_class") col_coarse = static_cast<int>(i);
    if (h == "nyuv2_40class") col_nyu = static_cast<int>(i);
  }
  if (col_id < 0 || col_fine < 0 || col_coarse < 0 || col_nyu < 0) {
    throw InputError(path + ": header lacks model_id, fine_grained_class, coarse_grained_class or nyuv2_40class");
  }
  const int needed = std::max(std::max(col_id, col_fine), std::max(col_coarse, col_nyu));
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (Trim(line).empty()) continue;
    const std::vector<std::string> f = SplitCsvLine(line);
    if (static_cast<int>(f.size()) <= needed) {
      throw InputError(path + ":" + std::to_string(line_number) + ": expected at least " + std::to_string(needed + 1) +
                       " columns");
    }
    mapping.by_id_[Trim(f[col_id])] = SuncgClasses{Trim(f[col_fine]), Trim(f[col_coarse]), Trim(f[col_nyu])};
  }
  return mapping;
}

std::string SuncgModelMapping::Find(const std::string& start_dir) {
  std::error_code ec;
  fs::path dir = fs::absolute(start_dir.empty() ? fs::path(".") : fs::path(start_dir), ec);
  while (!dir.empty()) {
    const fs::path candidate = dir / "ModelCategoryMapping.csv";
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
    if (dir == dir.root_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return "";
}

const SuncgClasses* SuncgModelMapping::Lookup(const std::string& model_id) const {
  const auto it = by_id_.find(model_id);
  return it == by_id_.end() ? nullptr : &it->second;
}

SuncgCategoryTable SuncgCategoryTable::Load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open SUNCG category table");
  SuncgCategoryTable table;
  table.path_ = path;
  std::string line;
  int line_number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::vector<std::string> f = SplitCsvLine(trimmed);
    const std::string where = path + ":" + std::to_string(line_number);
    if (f.size() != 2) throw InputError(where + ": expected 'suncg_class,category'");
    const std::string suncg_class = Trim(f[0]), category_name = Trim(f[1]);
    if (!header_seen) {
      header_seen = true;
      if (suncg_class == "suncg_class" && category_name == "category") continue;
      throw InputError(where + ": expected the header 'suncg_class,category'");
    }
    const std::optional<world::Category> category = world::ParseCategory(category_name);
    if (!category) throw InputError(where + ": unknown objscan category '" + category_name + "'");
    if (suncg_class.empty()) throw InputError(where + ": empty SUNCG class");
    if (!table.by_class_.emplace(suncg_class, *category).second) {
      throw InputError(where + ": SUNCG class '" + suncg_class + "' is listed twice");
    }
  }
  if (table.by_class_.empty()) throw InputError(path + ": no rows");
  return table;
}

std::optional<world::Category> SuncgCategoryTable::Lookup(const SuncgClasses& classes) const {
  for (const std::string* key : {&classes.fine_grained, &classes.coarse_grained, &classes.nyuv2_40}) {
    const auto it = by_class_.find(*key);
    if (!key->empty() && it != by_class_.end()) return it->second;
  }
  const auto it = by_class_.find("*");
  if (it != by_class_.end()) return it->second;
  return std::nullopt;
}

std::string StripInstanceSuffix(const std::string& model_name) {
  const auto underscore = model_name.rfind('_');
  if (underscore == std::string::npos || underscore == 0 || underscore + 1 == model_name.size()) return model_name;
  for (std::size_t i = underscore + 1; i < model_name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(model_name[i]))) return model_name;
  }
  return model_name.substr(0, underscore);
}

}  // namespace objscan::io
