#pragma once
// The report stage: the rules of report.rules, in their order, over the objects the loop left.
#include <memory>
#include <vector>

#include "objscan/scanning/report/report_options.h"
#include "objscan/scanning/report/report_rule.h"

namespace objscan::scanning {

class ReportPipeline {
 public:
  // Throws ConfigError for an unknown rule name (ReportOptions::Validate).
  explicit ReportPipeline(const ReportOptions& options);

  // Whether some listed rule reads the database's category sizes (ReportContext::category_extents).
  bool needs_category_extents() const;
  // The listed rules' names, in order.
  std::vector<std::string> rule_names() const;

  void Run(const ReportContext& context, ReportedObjects* objects) const;

 private:
  std::vector<std::unique_ptr<ReportRule>> rules_;
};

}  // namespace objscan::scanning
