#pragma once
// Configuration: one options struct per component with in-class defaults (units in field names), a
// Validate() that throws ConfigError naming the field, and a Visit() that lists the fields once:
//
//   struct SensorOptions {
//     int width_px = 640;
//     double max_range_m = 4.0;
//     template <class V> void Visit(V& v) { v("width_px", width_px); v("max_range_m", max_range_m); }
//     void Validate() const;
//   };
//
// That one list drives loading from YAML, `--set key=value` overrides, rejection of unknown keys and
// the dump of the effective configuration. A field may itself be a struct with Visit() (a section).
// Field types: bool, int, std::int64_t, std::uint64_t, double, std::string, std::vector<double>,
// std::vector<std::string> (a YAML sequence of names).
#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "objscan/common/error.h"

namespace objscan::config {

// Raw key/value pairs before they are applied to options structs: "sensor.width_px" -> "640".
// Sequences of scalars are stored comma-joined.
class RawConfig {
 public:
  // Parses a YAML file; throws InputError naming the file on a missing or malformed file.
  static RawConfig FromYamlFile(const std::string& path);
  static RawConfig FromYamlString(const std::string& text, const std::string& origin);

  // A `key=value` override (from --set); throws ConfigError when it is not of that form.
  void SetFromAssignment(const std::string& assignment);
  void Set(const std::string& key, const std::string& value, const std::string& origin);
  // Entries of `other` replace ours.
  void Merge(const RawConfig& other);

  struct Entry {
    std::string value;
    std::string origin;  // file name or "--set"
    bool used = false;
  };
  Entry* Find(const std::string& key);
  const std::map<std::string, Entry>& entries() const { return entries_; }
  // Throws ConfigError naming the first key no options struct consumed.
  void CheckAllUsed() const;

 private:
  std::map<std::string, Entry> entries_;
};

using Value = std::variant<bool, std::int64_t, std::uint64_t, double, std::string, std::vector<double>,
                           std::vector<std::string>>;
using FlatValues = std::vector<std::pair<std::string, Value>>;

// Parsers used by the visitors; throw ConfigError naming key and origin.
void ParseInto(const RawConfig::Entry& e, const std::string& key, bool* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, int* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, std::int64_t* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, std::uint64_t* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, double* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, std::string* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, std::vector<double>* out);
void ParseInto(const RawConfig::Entry& e, const std::string& key, std::vector<std::string>* out);

template <class T, class = void>
struct IsSection : std::false_type {};

namespace detail {
struct NullVisitor {
  template <class F>
  void operator()(const char*, F&) {}
};
}  // namespace detail

template <class T>
struct IsSection<T, std::void_t<decltype(std::declval<T&>().Visit(std::declval<detail::NullVisitor&>()))>>
    : std::true_type {};

// Applies raw entries under `prefix` onto an options struct (marks them used).
class ApplyVisitor {
 public:
  ApplyVisitor(RawConfig* raw, std::string prefix) : raw_(raw), prefix_(std::move(prefix)) {}
  template <class T>
  void operator()(const char* name, T& field) {
    const std::string key = prefix_ + name;
    if constexpr (IsSection<T>::value) {
      ApplyVisitor sub(raw_, key + ".");
      field.Visit(sub);
    } else {
      if (RawConfig::Entry* e = raw_->Find(key)) {
        ParseInto(*e, key, &field);
        e->used = true;
      }
    }
  }

 private:
  RawConfig* raw_;
  std::string prefix_;
};

// Collects the values of an options struct as dotted keys.
class DumpVisitor {
 public:
  DumpVisitor(FlatValues* out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}
  template <class T>
  void operator()(const char* name, T& field) {
    const std::string key = prefix_ + name;
    if constexpr (IsSection<T>::value) {
      DumpVisitor sub(out_, key + ".");
      field.Visit(sub);
    } else if constexpr (std::is_same_v<T, int>) {
      out_->emplace_back(key, Value(static_cast<std::int64_t>(field)));
    } else {
      out_->emplace_back(key, Value(field));
    }
  }

 private:
  FlatValues* out_;
  std::string prefix_;
};

template <class T, class = void>
struct HasValidate : std::false_type {};
template <class T>
struct HasValidate<T, std::void_t<decltype(std::declval<const T&>().Validate())>> : std::true_type {};

// Validates nested sections depth first, so that an error names the field by its whole key
// ("config: presegmentation.slot_split.min_gap_m must be > 0"), not by its name in its struct.
class ValidateVisitor {
 public:
  explicit ValidateVisitor(std::string prefix) : prefix_(std::move(prefix)) {}
  template <class T>
  void operator()(const char* name, T& field) {
    if constexpr (IsSection<T>::value) {
      const std::string key = prefix_ + name + ".";
      ValidateVisitor sub(key);
      field.Visit(sub);
      if constexpr (HasValidate<T>::value) {
        try {
          field.Validate();
        } catch (const ConfigError& e) {
          throw ConfigError(QualifiedMessage(e.what(), key));
        }
      }
    }
  }

 private:
  // "config: <field> ..." -> "config: <key><field> ...". A field some Validate() already wrote as a
  // dotted path keeps it, completed in front when it starts with the end of `key`
  // ("size_check.min_ratio" under "report.size_check." -> "report.size_check.min_ratio").
  static std::string QualifiedMessage(const std::string& message, const std::string& key) {
    const std::string tag = "config: ";
    if (message.compare(0, tag.size(), tag) != 0) return tag + key + ": " + message;
    const std::string rest = message.substr(tag.size());
    const std::string field = rest.substr(0, rest.find(' '));
    if (field.find('.') == std::string::npos) return tag + key + rest;
    // The longest tail of `key` (whole components) the field starts with.
    std::size_t start = 0;
    while (start < key.size()) {
      const std::string tail = key.substr(start);
      if (field.compare(0, tail.size(), tail) == 0) return tag + key.substr(0, start) + rest;
      const std::size_t dot = key.find('.', start);
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    return message;
  }
  std::string prefix_;
};

// Applies `raw` onto `options` (a section struct), rejects unknown keys, then validates.
template <class Options>
void Apply(RawConfig raw, Options* options) {
  ApplyVisitor visitor(&raw, "");
  options->Visit(visitor);
  raw.CheckAllUsed();
  ValidateVisitor validate("");
  options->Visit(validate);
  options->Validate();
}

template <class Options>
FlatValues Dump(const Options& options) {
  FlatValues out;
  DumpVisitor visitor(&out, "");
  const_cast<Options&>(options).Visit(visitor);  // Visit only reads here.
  return out;
}

// Nested JSON text of flat values ({"sensor": {"width_px": 640}}).
std::string ToJson(const FlatValues& values, int indent = 2);
// YAML text of flat values, sections as nested maps, in field order.
std::string ToYaml(const FlatValues& values);

// Helpers for Validate(): throw ConfigError "config: <field> must be ... (got v)".
void RequirePositive(const char* field, double value);
void RequireNonNegative(const char* field, double value);
void RequireInRange(const char* field, double value, double lo, double hi);
void Require(bool condition, const char* field, const std::string& what);

}  // namespace objscan::config
