#pragma once
// Writes the output folder of `objscan run` (DESIGN.md): run.json, scene.ply, models.ply (both
// coloured by category, with `label` and `instance`), categories.json, trajectory.csv, trajectory.tum,
// topview.png and navmap.png; with ground truth also coverage.ply (the voxels of V_S coloured by
// covered / seen but not recognised / never seen). Each file is written atomically.
#include <functional>
#include <string>

#include "objscan/eval/run_evaluation.h"
#include "objscan/io/ply.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/run_record.h"
#include "objscan/scanning/scanner.h"

namespace objscan::eval {

struct RunOutputInputs {
  const scanning::RunRecord* record = nullptr;
  const scanning::Scanner* scanner = nullptr;
  const recognition::ModelDatabase* database = nullptr;
  const scanning::SystemConfig* config = nullptr;
  const RunMetrics* metrics = nullptr;  // null when no ground truth
  std::string scene_spec;
  std::string database_path;
  // Peak resident memory of the process (run.json `peak_rss_mb`); 0 = not measured.
  double peak_rss_mb = 0.0;
  // CPU time of the process, user + system (run.json `cpu_s`); negative = not measured.
  double cpu_s = -1.0;
  // Further files of the caller (report_variants.json), written into the folder before run.json.
  std::function<void(const std::string& out_dir)> write_more_files;
  // Told one line per model that models.ply cannot draw as a mesh (none stored in the database and
  // its source cannot be loaded: the model's database scan points are written instead), once per
  // model. The caller prints it (library code never prints).
  std::function<void(const std::string& message)> warn;
};

// trajectory.tum: one line per view, "timestamp tx ty tz qx qy qz qw" (TUM RGB-D format, the
// camera's optical frame in the world, simulated time), after two '#' comment lines.
std::string TrajectoryTum(const scanning::RunRecord& record);
// models.ply: the mesh of the database model of every complete object (the mesh stored in the
// database, else its source's: recognition::LoadModelSourceMesh) placed by T_world_model, with
// object_id, category_id, label and instance per vertex. A model with no mesh anywhere is drawn by
// its database scan points (no triangles) and `warn` gets one line naming it, once per model.
io::PlyData PlacedModelsPly(const scanning::RunRecord& record, const recognition::ModelDatabase& database,
                            const std::function<void(const std::string& message)>& warn);
// JSON text of run.json.
std::string RunJson(const RunOutputInputs& in);
// models.ply's meshes come from the database (PlacedModelsPly), so a run needs no model files.
// Writes all files into `out_dir` (created when missing), each atomically, run.json last: a folder
// holding a run.json holds every file of that run (an earlier run.json is removed first, so a run
// killed while writing never leaves the old run.json beside new files; temporaries of a killed
// writer are removed too). Throws InputError naming the path.
void WriteRunOutputs(const std::string& out_dir, const RunOutputInputs& in);
// Draws the reconstruction from above: objects coloured by category, unrecognised surface grey,
// robot path and view directions.
void WriteRunTopView(const std::string& path, const RunOutputInputs& in);

}  // namespace objscan::eval
