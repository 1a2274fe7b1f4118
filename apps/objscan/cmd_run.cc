// `objscan run`: scan a scene autonomously and write the DESIGN.md output folder.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "objscan/eval/report_variants.h"
#include "objscan/io/scene_spec.h"
#include "objscan/scanning/scene_limits.h"
#include "objscan/scanning/system_config.h"
#include "objscan/sim/simulated_robot.h"
#include "run_scan.h"

namespace objscan::app {
namespace {

struct RunArgs {
  std::string scene = "procedural:bedroom:1";
  std::string db;
  std::string out = "objscan-out";
  std::uint64_t seed = 1;
  ConfigArgs config;
  bool print_config = false;
  bool quiet = false;
  bool save_frames = false;
};

int RunScan(const RunArgs& args) {
  const scanning::SystemConfig config = LoadRunConfig(args.config);
  if (args.print_config) {
    std::fputs(scanning::ToYaml(config).c_str(), stdout);
    return 0;
  }
  // Check every input before writing anything.
  eval::LoadReportVariants(config.eval.report_variants, config.report);
  const world::Scene scene = io::LoadScene(args.scene, config.scene);
  scanning::CheckSceneLimits(scene, config, args.scene);
  // What the loader changed or guessed (doors removed, instances inferred) bears on every metric.
  for (const std::string& note : scene.load_notes()) {
    if (!args.quiet) std::fprintf(stderr, "objscan run: note: %s\n", note.c_str());
  }
  const RunDatabase database = LoadRunDatabase(args.db, args.scene, config, args.quiet);

  // The simulated robot, put down in the scene as an operator would; the scanner starts where it stands.
  sim::SimulatedRobot robot(scene, config.sensor, config.robot, config.navigation, args.seed);
  ScanRunInputs in;
  in.config = &config;
  in.database = &database;
  in.scene = &scene;
  in.scene_spec = args.scene;
  in.seed = args.seed;
  in.out = args.out;
  in.quiet = args.quiet;
  in.save_frames = args.save_frames;
  return ScanAndWrite(in, &robot);
}

}  // namespace

void AddRunCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = root.add_subcommand("run", "Scan a scene autonomously (NBO + NBV) and write a labelled reconstruction");
  cmd->add_option("--scene", args->scene, "scene SPEC: .world, .yaml/.json scene file, ScanNet scan folder or *_vh_clean_2.ply, mesh, or procedural:CATEGORY:SEED")
      ->capture_default_str();
  cmd->add_option("--db", args->db, "model database file (default: the built-in procedural database for procedural scenes, the built-in real one, the Sweet Home 3D library, for every other scene; built once and cached)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed (sensor noise and every random choice)")->capture_default_str();
  AddConfigOptions(cmd, &args->config);
  cmd->add_flag("--print-config", args->print_config, "print the effective configuration as YAML and exit");
  cmd->add_flag("--quiet", args->quiet, "no progress output on stderr");
  cmd->add_flag("--save-frames", args->save_frames,
                "also write every depth image to OUT/frames (TUM RGB-D layout: depth/NNNNNN.png at 5000 units "
                "per metre, depth.txt, groundtruth.txt camera poses, intrinsics.json)");
  cmd->callback([run, args] { *run = [args] { return RunScan(*args); }; });
}

}  // namespace objscan::app
