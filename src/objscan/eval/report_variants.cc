#include "objscan/eval/report_variants.h"

#include <map>

#include "objscan/common/config.h"
#include "objscan/common/error.h"

namespace objscan::eval {

std::vector<ReportVariant> LoadReportVariants(const std::string& spec, const scanning::ReportOptions& run_options) {
  std::vector<ReportVariant> variants;
  if (spec.empty()) return variants;
  if (spec == "ablation") {
    for (std::size_t i = 0; i < run_options.rules.size(); ++i) {
      ReportVariant v{"without_" + run_options.rules[i], run_options};
      v.options.rules.erase(v.options.rules.begin() + static_cast<std::ptrdiff_t>(i));
      variants.push_back(std::move(v));
    }
    ReportVariant none{"no_rules", run_options};
    none.options.rules.clear();
    variants.push_back(std::move(none));
    return variants;
  }
  const config::RawConfig raw = config::RawConfig::FromYamlFile(spec);
  // Keys "name.key..." grouped by variant, in the file's key order per variant.
  std::map<std::string, config::RawConfig> by_name;
  for (const auto& [key, entry] : raw.entries()) {
    const std::size_t dot = key.find('.');
    if (dot == std::string::npos || dot == 0) {
      throw InputError(spec + ": '" + key + "' is not a variant of report options (name: {key: value, ...})");
    }
    by_name[key.substr(0, dot)].Set(key.substr(dot + 1), entry.value, entry.origin);
  }
  for (auto& [name, variant_raw] : by_name) {
    ReportVariant v{name, run_options};
    try {
      config::Apply(variant_raw, &v.options);
    } catch (const ConfigError& e) {
      throw InputError(spec + ": variant '" + name + "': " + e.what());
    }
    variants.push_back(std::move(v));
  }
  if (variants.empty()) throw InputError(spec + ": no report variant in the file");
  return variants;
}

}  // namespace objscan::eval
