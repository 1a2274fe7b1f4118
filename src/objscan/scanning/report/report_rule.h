#pragma once
// One rule of the report stage: after the loop, it reads the reported objects and the context and
// changes objects through ReportedObjects' operations (each change is recorded under its name).
// Rules run in the order of config `report.rules`; a rule runs when it is listed.
#include "objscan/scanning/report/report_context.h"
#include "objscan/scanning/report/reported_objects.h"

namespace objscan::scanning {

class ReportRule {
 public:
  virtual ~ReportRule() = default;
  // Its name in report.rules.
  virtual const char* name() const = 0;
  // Whether it reads ReportContext::category_extents.
  virtual bool needs_category_extents() const { return false; }
  virtual void Apply(const ReportContext& context, ReportedObjects* objects) const = 0;
};

}  // namespace objscan::scanning
