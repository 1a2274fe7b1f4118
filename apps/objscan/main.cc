// objscan: object-aware autonomous scene scanning (Liu et al., SIGGRAPH 2018) in a fast simulator.
#include <cstdio>
#include <exception>

#include "commands.h"
#include "run_scan.h"

int main(int argc, char** argv) {
  CLI::App root{
      "objscan: object-aware autonomous scene scanning and reconstruction (next best object, next best "
      "view, objectness, multi-class graph cuts) in a fast headless simulator."};
  root.require_subcommand(1);
  root.set_version_flag("--version", "objscan 0.1.0");
  objscan::app::RunFn run;
  objscan::app::AddSceneCommand(root, &run);
  objscan::app::AddRenderCommand(root, &run);
  objscan::app::AddDbCommand(root, &run);
  objscan::app::AddRunCommand(root, &run);
  objscan::app::AddBenchCommand(root, &run);
  objscan::app::AddReportCommand(root, &run);
  objscan::app::AddViewCommand(root, &run);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return root.exit(e);
  }
  return objscan::app::ReportErrors("objscan", [&run] { return run ? run() : 0; });
}
