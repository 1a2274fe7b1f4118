#pragma once
// What the report's files share (report.cc builds the Report; report_json.cc, report_markdown.cc and
// report_files.cc write it): selections of runs and the paper's rows. Not part of the library's API.
#include <string>
#include <vector>

#include "objscan/eval/report.h"

namespace objscan::eval::report_internal {

// The runs of `method` in a scene category ("all": every category), complete ones only if asked.
std::vector<const RunSummary*> Select(const Report& report, const std::string& method, const std::string& category,
                                      bool complete_only);
// The statistics of `method` in a scene category; nullptr when it has no scene there.
const SceneCategoryStats* Stats(const Report& report, const std::string& method, const std::string& category);
bool Has(const std::vector<std::string>& v, const std::string& s);

// The paper's row for a scene or object category; nullptr when the paper has none.
const PaperSceneRow* PaperScene(const std::string& category);
const PaperObjectRow* PaperObject(const std::string& category);
const PaperTimingRow* PaperTiming(const std::string& category);

// The first complete run of "ours" in a scene category (by scene id): Fig. 11 shows one scene each.
const RunSummary* ExampleRun(const Report& report, const std::string& category);
// The methods of the paper's NBO ablation figures, in their order.
const std::vector<std::string>& AblationMethods();

// The errors of the methods alone (without "all"), and the "all" entry (null when there is none).
std::vector<const MethodErrors*> ErrorsPerMethod(const Report& report);
const MethodErrors* ErrorsOverall(const Report& report);

}  // namespace objscan::eval::report_internal
