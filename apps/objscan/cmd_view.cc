// `objscan view OUT/`: write OUT/view.html, one self-contained page replaying the run in a browser.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "objscan/eval/run_view.h"
#include "objscan/io/atomic_file.h"

namespace objscan::app {
namespace {

struct ViewArgs {
  std::string dir;
  std::string out;
  eval::RunViewOptions options;
};

int RunView(const ViewArgs& a) {
  eval::RunViewSummary summary;
  const std::string page = eval::RunViewHtml(a.dir, a.options, &summary);
  const std::string out = a.out.empty() ? (std::filesystem::path(a.dir) / "view.html").string() : a.out;
  io::WriteFileAtomically(out, page);
  nlohmann::ordered_json j;
  j["out"] = out;
  j["bytes"] = page.size();
  j["steps"] = summary.steps;
  j["views"] = summary.views;
  j["points"] = summary.points;
  j["scene_points"] = summary.scene_points;
  j["models"] = summary.models;
  j["nbv_candidates"] = summary.candidates;
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

}  // namespace

void AddViewCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<ViewArgs>();
  auto* cmd = root.add_subcommand("view", "Write OUT/view.html, a self-contained page replaying a run (three.js)");
  cmd->add_option("dir", args->dir, "a finished run folder (objscan run --out)")->required();
  cmd->add_option("--out", args->out, "the page to write (default: DIR/view.html)");
  cmd->add_option("--three-js", args->options.three_js_path, "three.min.js to inline (Debian: libjs-three)")
      ->capture_default_str();
  cmd->add_option("--orbit-controls", args->options.orbit_controls_path, "three.js OrbitControls.js to inline")
      ->capture_default_str();
  cmd->add_option("--max-points", args->options.max_points, "points of scene.ply put in the page (every k-th beyond)")
      ->capture_default_str();
  cmd->callback([run, args] { *run = [args] { return RunView(*args); }; });
}

}  // namespace objscan::app
