#include "objscan/common/config.h"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace objscan::config {
namespace {

void Flatten(const YAML::Node& node, const std::string& key, const std::string& origin, RawConfig* out) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      for (const auto& kv : node) {
        if (!kv.first.IsScalar()) {
          throw ConfigError(origin + ": a key " + (key.empty() ? "at the top level" : "under '" + key + "'") +
                            " is not a name (a list or a mapping)");
        }
        const std::string child = kv.first.Scalar();
        Flatten(kv.second, key.empty() ? child : key + "." + child, origin, out);
      }
      break;
    case YAML::NodeType::Sequence: {
      std::string joined;
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar()) {
          throw ConfigError(origin + ": config key '" + key + "' must be a list of numbers or names");
        }
        if (i) joined += ",";
        joined += node[i].Scalar();
      }
      out->Set(key, joined, origin);
      break;
    }
    case YAML::NodeType::Scalar:
      out->Set(key, node.Scalar(), origin);
      break;
    case YAML::NodeType::Null:
      if (!key.empty()) throw ConfigError(origin + ": config key '" + key + "' has no value");
      break;
    default:
      break;
  }
}

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void Bad(const RawConfig::Entry& e, const std::string& key, const char* what) {
  throw ConfigError(e.origin + ": config key '" + key + "' must be " + what + " (got '" + e.value + "')");
}

double ParseDouble(const std::string& text, const RawConfig::Entry& e, const std::string& key) {
  const std::string t = Trim(text);
  if (t.empty()) Bad(e, key, "a number");
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  // No config value is infinite or NaN: every one is a size, a count or a weight (an infinity would
  // reach a float-to-integer conversion, undefined behaviour, in the stage that uses it).
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) Bad(e, key, "a finite number");
  return v;
}

}  // namespace

RawConfig RawConfig::FromYamlFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open config file");
  std::stringstream ss;
  ss << in.rdbuf();
  return FromYamlString(ss.str(), path);
}

RawConfig RawConfig::FromYamlString(const std::string& text, const std::string& origin) {
  RawConfig raw;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& ex) {
    throw InputError(origin + ": malformed YAML at line " + std::to_string(ex.mark.line + 1) + ": " + ex.msg);
  }
  if (!root.IsNull() && !root.IsMap()) throw ConfigError(origin + ": config must be a map of sections");
  Flatten(root, "", origin, &raw);
  return raw;
}

void RawConfig::SetFromAssignment(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw ConfigError("--set '" + assignment + "': expected key=value");
  }
  Set(Trim(assignment.substr(0, eq)), Trim(assignment.substr(eq + 1)), "--set");
}

void RawConfig::Set(const std::string& key, const std::string& value, const std::string& origin) {
  Entry& e = entries_[key];
  e.value = value;
  e.origin = origin;
  e.used = false;
}

void RawConfig::Merge(const RawConfig& other) {
  for (const auto& [key, entry] : other.entries_) entries_[key] = entry;
}

RawConfig::Entry* RawConfig::Find(const std::string& key) {
  auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second;
}

void RawConfig::CheckAllUsed() const {
  for (const auto& [key, entry] : entries_) {
    if (!entry.used) throw ConfigError(entry.origin + ": unknown config key '" + key + "'");
  }
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, bool* out) {
  const std::string v = Trim(e.value);
  if (v == "true" || v == "True" || v == "1" || v == "yes" || v == "on") {
    *out = true;
  } else if (v == "false" || v == "False" || v == "0" || v == "no" || v == "off") {
    *out = false;
  } else {
    Bad(e, key, "true or false");
  }
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, std::int64_t* out) {
  const std::string t = Trim(e.value);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE) Bad(e, key, "an integer");
  *out = v;
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, std::uint64_t* out) {
  const std::string t = Trim(e.value);
  char* end = nullptr;
  errno = 0;
  if (!t.empty() && t[0] == '-') Bad(e, key, "a non-negative integer");
  const unsigned long long v = std::strtoull(t.c_str(), &end, 10);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE) Bad(e, key, "a non-negative integer");
  *out = v;
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, int* out) {
  std::int64_t v = 0;
  ParseInto(e, key, &v);
  if (v < INT32_MIN || v > INT32_MAX) Bad(e, key, "a 32-bit integer");
  *out = static_cast<int>(v);
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, double* out) {
  *out = ParseDouble(e.value, e, key);
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, std::string* out) {
  (void)key;
  *out = e.value;
}

namespace {

// The items of a sequence value: "[a, b]" or "a,b" (how RawConfig stores a YAML sequence); none for
// an empty one.
std::vector<std::string> ListItems(const std::string& value) {
  std::string t = Trim(value);
  if (!t.empty() && t.front() == '[' && t.back() == ']') t = t.substr(1, t.size() - 2);
  std::vector<std::string> items;
  if (Trim(t).empty()) return items;
  std::stringstream ss(t);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  return items;
}

}  // namespace

void ParseInto(const RawConfig::Entry& e, const std::string& key, std::vector<double>* out) {
  out->clear();
  for (const std::string& item : ListItems(e.value)) out->push_back(ParseDouble(item, e, key));
}

void ParseInto(const RawConfig::Entry& e, const std::string& key, std::vector<std::string>* out) {
  out->clear();
  for (std::string item : ListItems(e.value)) {
    item = Trim(item);
    if (item.size() >= 2 && (item.front() == '"' || item.front() == '\'') && item.back() == item.front()) {
      item = item.substr(1, item.size() - 2);
    }
    if (item.empty()) Bad(e, key, "a list of names");
    out->push_back(item);
  }
}

std::string ToJson(const FlatValues& values, int indent) {
  nlohmann::ordered_json root = nlohmann::ordered_json::object();
  for (const auto& [key, value] : values) {
    nlohmann::ordered_json* node = &root;
    std::size_t start = 0;
    for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
      node = &(*node)[key.substr(start, dot - start)];
      start = dot + 1;
    }
    nlohmann::ordered_json& leaf = (*node)[key.substr(start)];
    std::visit([&leaf](const auto& v) { leaf = v; }, value);
  }
  return root.dump(indent);
}

std::string ToYaml(const FlatValues& values) {
  std::ostringstream out;
  std::vector<std::string> open;  // currently open section path
  for (const auto& [key, value] : values) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
      parts.push_back(key.substr(start, dot - start));
      start = dot + 1;
    }
    const std::string leaf = key.substr(start);
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    open.resize(common);
    for (std::size_t i = common; i < parts.size(); ++i) {
      if (i == 0 && !out.str().empty()) out << "\n";
      out << std::string(2 * i, ' ') << parts[i] << ":\n";
      open.push_back(parts[i]);
    }
    out << std::string(2 * parts.size(), ' ') << leaf << ": ";
    std::visit(
        [&out](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, bool>) {
            out << (v ? "true" : "false");
          } else if constexpr (std::is_same_v<T, std::string>) {
            out << nlohmann::json(v).dump();
          } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
            out << "[";
            for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
            out << "]";
          } else if constexpr (std::is_same_v<T, std::vector<double>>) {
            out << "[";
            for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << nlohmann::json(v[i]).dump();
            out << "]";
          } else {
            out << nlohmann::json(v).dump();
          }
        },
        value);
    out << "\n";
  }
  return out.str();
}

void RequirePositive(const char* field, double value) {
  if (!(value > 0.0)) throw ConfigError("config: " + std::string(field) + " must be > 0 (got " + std::to_string(value) + ")");
}
void RequireNonNegative(const char* field, double value) {
  if (!(value >= 0.0)) throw ConfigError("config: " + std::string(field) + " must be >= 0 (got " + std::to_string(value) + ")");
}
void RequireInRange(const char* field, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    throw ConfigError("config: " + std::string(field) + " must be in [" + std::to_string(lo) + ", " +
                      std::to_string(hi) + "] (got " + std::to_string(value) + ")");
  }
}
void Require(bool condition, const char* field, const std::string& what) {
  if (!condition) throw ConfigError("config: " + std::string(field) + " " + what);
}

}  // namespace objscan::config
