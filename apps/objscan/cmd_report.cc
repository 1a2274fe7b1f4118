// `objscan report DIR...`: rebuild the tables and plots from finished runs or bench shards
// (results.md, results.json, confusion.csv, SVG + PNG plots in FIRST_DIR/report/ or --out).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "objscan/common/error.h"
#include "objscan/eval/report.h"

namespace objscan::app {
namespace {

struct ReportArgs {
  std::vector<std::string> dirs;
  std::string out;
};

int RunReport(const ReportArgs& a) {
  // A typo'd or empty folder would give a report of no run: say so before writing anything.
  const std::vector<std::string> without_runs = eval::FoldersWithoutRuns(a.dirs);
  if (!without_runs.empty()) {
    std::string list;
    for (const auto& d : without_runs) list += (list.empty() ? "" : ", ") + d;
    throw InputError(list + ": no run found (no run.json or failed.json below it); give a folder written by "
                     "`objscan run --out` or `objscan bench --out`");
  }
  const eval::Report report = eval::BuildReport(eval::CollectRuns(a.dirs));
  const std::string out = a.out.empty() ? (std::filesystem::path(a.dirs.front()) / "report").string() : a.out;
  const std::vector<std::string> files = eval::WriteReport(report, out);
  nlohmann::ordered_json j;
  j["out"] = out;
  j["runs_complete"] = report.complete_runs;
  j["runs_failed"] = report.failed_runs;
  j["methods"] = report.methods;
  j["scene_categories"] = report.scene_categories;
  j["files"] = files;
  // Where the reported objects go wrong, per method and overall (also in the report's results.json).
  if (!report.errors.empty()) j["reported_objects"] = nlohmann::ordered_json::parse(eval::ReportedObjectsJson(report));
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

}  // namespace

void AddReportCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = root.add_subcommand("report", "Rebuild tables and plots from finished runs or bench shards");
  cmd->add_option("dirs", args->dirs, "run or bench folders (shards are merged)")->required();
  cmd->add_option("--out", args->out, "report folder (default: FIRST_DIR/report)");
  cmd->callback([run, args] { *run = [args] { return RunReport(*args); }; });
}

}  // namespace objscan::app
