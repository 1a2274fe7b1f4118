#pragma once
// The object-aware scanning loop (Algorithm 1 of the paper) over a robot (platform::Platform): sense,
// fuse, pre-segment, post-segment with the recognizer, choose the next best object and its next best
// view (or a floor frontier when no object is left), move, repeat; complete objects are replaced by
// their best database model and leave the scene surface T. The scan starts where the platform is; the
// method reads nothing but the platform's frames, poses and moves (objscan's simulator is one platform,
// sim/simulated_robot.h).
#include <functional>
#include <memory>
#include <set>
#include <string>

#include "objscan/common/progress.h"
#include "objscan/platform/depth_frame.h"
#include "objscan/platform/platform.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/run_record.h"
#include "objscan/scanning/system_config.h"

namespace objscan::mapping {
struct FrameAssociation;
}  // namespace objscan::mapping
namespace objscan::recognition {
struct CachedClassifierStatus;
}  // namespace objscan::recognition

namespace objscan::scanning {

// Called with every frame the robot takes and where the surface map fused its pixels (evaluation
// accumulates ground-truth coverage and each map element's ground-truth instance from them; the
// method itself never reads the frame's ground-truth channel).
using FrameObserver =
    std::function<void(const platform::DepthFrame& frame, const mapping::FrameAssociation& association)>;
class Scanner;
// Called after every analysis of the map (post-segmentation), e.g. to score the segmentation over views.
using AnalysisObserver = std::function<void(const Scanner& scanner)>;

class Scanner {
 public:
  // Scans with the robot `platform`, from where it stands; `database` must be finalized. Both must
  // outlive the scanner. `seed` is the run's, kept in its record: the scanner draws no random numbers
  // (the simulator seeds its sensor noise from the same seed).
  Scanner(const SystemConfig& config, platform::Platform* platform, const recognition::ModelDatabase& database,
          std::uint64_t seed);
  ~Scanner();
  Scanner(const Scanner&) = delete;
  Scanner& operator=(const Scanner&) = delete;

  void set_frame_observer(FrameObserver observer);
  void set_analysis_observer(AnalysisObserver observer);

  // One iteration; returns false once terminated.
  bool Step();
  // Steps until terminated; progress reports steps against the step budget (RunRecord::step_budget).
  const RunRecord& Run(const ProgressCallback& progress = nullptr);

  const RunRecord& record() const;
  // The objects the report stage gives from the end of this run with other report options (to
  // measure the report rules; the run's own record is unchanged). Only after Run().
  std::vector<ObjectRecord> ReportWith(const ReportOptions& options);
  const mapping::SurfaceMap& surface_map() const;
  // Per map element: the output object id (-1 none) and category id (-1 unrecognized / structural).
  void ElementObjects(std::vector<int>* object_id, std::vector<int>* category_id) const;
  // Per map element: the object id of the latest analysis (completed objects and the current
  // post-segmented objects; -1 none), and the number of views that analysis saw.
  void AnalysisElementObjects(std::vector<int>* object_id) const;
  int analysis_views() const;
  // How the recognizer's category classifier came from its cache (Recognizer::classifier_cache_status):
  // all empty until the scan first asked the classifier, and with recognition.classifier.cache off.
  // Read it between steps or after Run(), never while a step runs.
  const recognition::CachedClassifierStatus& classifier_cache_status() const;
  // The robot's navigation map as a PNG (what the method believes, not ground truth): free white,
  // occupied black, unknown grey, cells the robot's centre cannot take (inflation) tinted red, its
  // path blue. Throws InputError naming the path when it cannot be written.
  void WriteNavigationMap(const std::string& path, int pixels_per_cell = 4) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace objscan::scanning
