#pragma once
// Measuring the report rules (scanning/report/) on one run: the same end of the loop reported with
// other report options, each scored like the run itself. Variants come from eval.report_variants:
// "ablation" (the run's rule list without each rule in turn, and with no rule), or a YAML file of
// named variants (names without dots), each the run's report options with the keys it gives:
//   no_size_check:
//     rules: [reopen_outgrown, model_label, absorb_fragments]
//   unsure_90:
//     rules: [drop_unsure]
//     min_labelled_objectness: 0.9
#include <string>
#include <vector>

#include "objscan/scanning/report/report_options.h"

namespace objscan::eval {

struct ReportVariant {
  std::string name;
  scanning::ReportOptions options;
};

// Throws InputError naming the file (or ConfigError naming the key) on bad input.
std::vector<ReportVariant> LoadReportVariants(const std::string& spec, const scanning::ReportOptions& run_options);

}  // namespace objscan::eval
