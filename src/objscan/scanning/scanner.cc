#include "objscan/scanning/scanner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <unordered_map>

#include "objscan/common/error.h"
#include "objscan/common/timer.h"
#include "objscan/io/png.h"
#include "objscan/mapping/frontiers.h"
#include "objscan/mapping/occupancy_map.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/navigation/navigator.h"
#include "objscan/planning/exploration.h"
#include "objscan/planning/next_best_object.h"
#include "objscan/planning/next_best_view.h"
#include "objscan/recognition/component_matcher.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/scanning/coverage_views.h"
#include "objscan/scanning/report/report_pipeline.h"
#include "objscan/scanning/report/report_rules.h"
#include "objscan/scanning/scan_step.h"
#include "objscan/segmentation/incremental_segmenter.h"
#include "objscan/segmentation/post_segmenter.h"

namespace objscan::scanning {

const char* TerminationName(Termination t) {
  switch (t) {
    case Termination::kRunning: return "running";
    case Termination::kDone: return "done";
    case Termination::kMaxSteps: return "max_steps";
    case Termination::kStuck: return "stuck";
  }
  return "unknown";
}

namespace {

// The robot's own map as the navigator sees it, plus the cells its body has occupied: wherever the
// robot stood is free floor, even when the camera never saw it (it is below the field of view).
class RobotOccupancy : public navigation::OccupancySource {
 public:
  // `radius_m`: the disk around each visited position known to be free. It must exceed the
  // navigator's inflation radius, or the robot's own position would count as blocked.
  RobotOccupancy(const mapping::OccupancyMap& map, const std::vector<Eigen::Vector2d>& visited, double radius_m)
      : map_(map), visited_(visited), radius_m_(radius_m) {}
  navigation::OccupancyGrid2D Grid(double min_z_m, double max_z_m, double cell_size_m) const override {
    navigation::OccupancyGrid2D grid;
    geometry::Aabb3 bounds = map_.KnownBounds();
    for (const auto& v : visited_) {
      bounds.Extend(Eigen::Vector3d(v.x() - 1.0, v.y() - 1.0, 0.0));
      bounds.Extend(Eigen::Vector3d(v.x() + 1.0, v.y() + 1.0, 0.0));
    }
    if (bounds.Empty()) return grid;
    grid = map_.GridOver(bounds, min_z_m, max_z_m, cell_size_m);
    const int r = static_cast<int>(std::ceil(radius_m_ / cell_size_m)) + 1;
    for (const auto& v : visited_) {
      const Eigen::Vector2i c = grid.CellOf(v);
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          if (!grid.Contains(c.x() + dx, c.y() + dy)) continue;
          if ((grid.CellCenter(c.x() + dx, c.y() + dy) - v).norm() > radius_m_ + 0.5 * cell_size_m) continue;
          auto& cell = grid.cells[grid.Index(c.x() + dx, c.y() + dy)];
          if (cell == navigation::CellState::kUnknown) cell = navigation::CellState::kFree;
        }
      }
    }
    return grid;
  }

 private:
  const mapping::OccupancyMap& map_;
  const std::vector<Eigen::Vector2d>& visited_;
  double radius_m_;
};

// NBV candidate validity with the robot's own occupancy map and navigator.
class MapViewValidator : public planning::ViewValidator {
 public:
  MapViewValidator(const mapping::OccupancyMap& occupancy, const platform::Platform& platform,
                   const navigation::Navigator& navigator,
                   double skip_m, std::vector<geometry::Pose3> earlier_views, double min_separation_m,
                   double min_separation_deg)
      : occupancy_(occupancy),
        platform_(platform),
        navigator_(navigator),
        skip_m_(skip_m),
        earlier_views_(std::move(earlier_views)),
        min_separation_m_(min_separation_m),
        min_separation_cos_(std::cos(geometry::DegToRad(min_separation_deg))) {}

  planning::ViewValidity Check(const geometry::Pose3& T_world_camera,
                               const Eigen::Vector3d& target_world) const override {
    const Eigen::Vector3d p = T_world_camera.translation();
    // A view (nearly) repeating an earlier one of this object adds nothing.
    for (const auto& e : earlier_views_) {
      if ((e.translation() - p).norm() < min_separation_m_ &&
          e.linear().col(2).dot(T_world_camera.linear().col(2)) > min_separation_cos_) {
        return planning::ViewValidity::kRedundant;
      }
    }
    const mapping::Occupancy o = occupancy_.Query(p);
    if (o == mapping::Occupancy::kOccupied) return planning::ViewValidity::kOccupied;
    if (o == mapping::Occupancy::kUnknown) return planning::ViewValidity::kUnknown;
    // Line of sight through the occupancy map, up to the object's own extent around its centre.
    const Eigen::Vector3d d = target_world - p;
    const double length = d.norm();
    const double step = 0.5 * occupancy_.resolution_m();
    for (double s = step; s < length - skip_m_; s += step) {
      if (occupancy_.Query(p + d * (s / length)) == mapping::Occupancy::kOccupied) {
        return planning::ViewValidity::kLineOfSightBlocked;
      }
    }
    if (platform_.CheckReach(T_world_camera, navigator_) != platform::ReachStatus::kOk) {
      return planning::ViewValidity::kUnreachable;
    }
    return planning::ViewValidity::kValid;
  }

 private:
  const mapping::OccupancyMap& occupancy_;
  const platform::Platform& platform_;
  const navigation::Navigator& navigator_;
  double skip_m_;
  std::vector<geometry::Pose3> earlier_views_;
  double min_separation_m_;
  double min_separation_cos_;
};

struct CompletedObject {
  int id = -1;
  segmentation::ModelMatch model;
  double objectness = 0.0;
  std::vector<std::int32_t> labels;
};

// What the scanner keeps of one segment component (by its label) from step to step.
struct ComponentProgress {
  bool done = false;                // part of a completed object
  std::uint64_t match_revision = 0;  // raised when it grew past scanner.rematch_growth_fraction
  double matched_size = 0.0;         // its points at that revision
  std::optional<std::uint64_t> noise_at_revision;  // found noise when matched at this revision
  bool given_up = false;             // part of an object given up for good
  int views = 0;                     // NBV views spent on objects holding it
};

// What the scanner keeps of one object of interest (by its id, its smallest component label).
struct ObjectProgress {
  bool given_up = false;
  bool given_up_no_view = false;  // given up because no NBV candidate was valid
  int views_spent = 0;            // NBV views
  std::vector<double> objectness_history;  // O(r) before each of its NBV views
  std::vector<geometry::Pose3> views;      // the camera poses of its NBV and coverage views
  int coverage_attempts = 0;               // coverage views planned (coverage_views.h)
};

}  // namespace

struct Scanner::State {
  State(const SystemConfig& c, platform::Platform* p, const recognition::ModelDatabase& db, std::uint64_t seed)
      : config(c),
        database(db),
        platform(*p),
        surface(c.surface_map),
        occupancy(c.occupancy),
        segmenter(c.presegmentation),
        structure_detector(c.structure),
        recognizer(db, c.recognition),
        matcher(recognizer, c.scanner.threads),
        post_segmenter(c.postsegmentation, &matcher),
        nbv(c.nbv),
        coverage_nbv(CoverageNbvOptions(c)),
        visited(1, platform.base().xy_m),
        robot_occupancy(occupancy, visited, c.robot.base_radius_m + c.scanner.known_free_margin_m),
        navigator(robot_occupancy, c.robot.base_radius_m, c.robot.height_m, c.navigation) {
    record.seed = seed;
    record.scene = platform.world_name();
    const platform::CameraIntrinsics k = platform.intrinsics();
    frustum =
        planning::CameraFrustum::FromPinhole(k.width_px, k.height_px, k.fx_px, k.fy_px, k.min_range_m, k.max_range_m);
    ChooseStepKinds();
  }

  class ObjectScanStep;
  class FrontierExplorationStep;
  class CoverageViewStep;
  void ChooseStepKinds();

  // --- sensing ---------------------------------------------------------------------------------
  // A frame from where the camera is now, fused into the maps.
  void TakeView(StepRecord* step) {
    Stopwatch w;
    const platform::DepthFrame frame = platform.Capture();
    Charge(step, &StageTimes::sense, w.ElapsedMs());
    w.Restart();
    mapping::FrameAssociation association;
    surface.Integrate(frame, &association);
    occupancy.Integrate(frame);
    Charge(step, &StageTimes::fuse, w.ElapsedMs());
    w.Restart();
    segmenter.Update(frame, association, &surface);
    Charge(step, &StageTimes::segment, w.ElapsedMs());
    if (observer) observer(frame, association);
    ++step->views;
    ++record.views;
    step->T_world_camera = frame.T_world_camera;
    AddTrajectorySample(step->index, true);
    map_changed = true;
  }

  void Charge(StepRecord* step, double StageTimes::*stage, double ms) { step->timing_ms.*stage += ms; }

  void AddTrajectorySample(int step_index, bool view) {
    TrajectorySample s;
    const platform::BasePose base = platform.base();
    s.time_s = platform.travel().time_s;
    s.x_m = base.xy_m.x();
    s.y_m = base.xy_m.y();
    s.theta_rad = base.theta_rad;
    s.T_world_camera = platform.T_world_camera();
    s.view = view;
    s.step = step_index;
    record.trajectory.push_back(s);
  }

  // The inner waypoints of a driven path as trajectory samples (no view), so the path drawn and
  // written is the one driven; time spread along the path by length, heading along each segment.
  void AddPathSamples(const navigation::Path2D& path, double camera_z_m, double start_s, double end_s, int step_index) {
    const auto& w = path.waypoints;
    if (w.size() < 3 || !(path.length_m > 0.0)) return;
    double along_m = 0.0;
    for (std::size_t i = 1; i + 1 < w.size(); ++i) {
      along_m += (w[i] - w[i - 1]).norm();
      TrajectorySample t;
      t.time_s = start_s + (end_s - start_s) * std::min(1.0, along_m / path.length_m);
      t.x_m = w[i].x();
      t.y_m = w[i].y();
      const Eigen::Vector2d d = w[i + 1] - w[i];
      t.theta_rad = d.norm() > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
      // The camera as carried while driving: level, facing the way the base drives.
      t.T_world_camera = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(w[i].x(), w[i].y(), camera_z_m), t.theta_rad, 0.0);
      t.view = false;
      t.step = step_index;
      record.trajectory.push_back(t);
    }
  }

  // Moves the robot so its camera takes T_world_camera, the base driving on the navigator's map, and
  // takes a view there. `why` (optional) receives the reach status when the move is impossible.
  bool MoveCamera(const geometry::Pose3& T_world_camera, StepRecord* step, platform::ReachStatus* why = nullptr) {
    const platform::TravelStats before = platform.travel();
    const double camera_z_before_m = platform.T_world_camera().translation().z();
    const platform::Move move = platform.MoveCamera(T_world_camera, navigator);
    if (why) *why = move.status;
    if (!move.ok()) return false;
    for (const auto& w : move.path.waypoints) visited.push_back(w);
    visited.push_back(platform.base().xy_m);
    const platform::TravelStats after = platform.travel();
    AddPathSamples(move.path, camera_z_before_m, before.time_s, after.time_s, step->index);
    step->travel_m += after.distance_m - before.distance_m;
    step->timing_ms.navigate_sim += 1e3 * (after.time_s - before.time_s);
    TakeView(step);
    return true;
  }

  // Turning the camera in place: no navigation needed, so it works before any map.
  void TurnInPlaceView(const geometry::Pose3& T_world_camera, StepRecord* step) {
    const double before_s = platform.travel().time_s;
    platform.TurnCamera(T_world_camera);
    step->timing_ms.navigate_sim += 1e3 * (platform.travel().time_s - before_s);
    TakeView(step);
  }

  // The look-around of the exploration options, turning in place where the robot stands.
  void LookAroundInPlace(StepRecord* step) {
    step->action = "frontier";
    step->look_around = true;
    const platform::BasePose base = platform.base();
    for (const auto& T : planning::LookAroundViews(
             Eigen::Vector3d(base.xy_m.x(), base.xy_m.y(), config.scanner.start_camera_height_m), base.theta_rad,
             config.exploration)) {
      TurnInPlaceView(T, step);
    }
  }

  // --- analysis: C, R, complete / noise objects ---------------------------------------------------
  void Analyze(StepRecord* step) {
    Stopwatch w;
    UpdateStructure();
    const segmentation::ComponentGraph& graph = segmenter.Components(&surface);
    graph_cache = &graph;
    Charge(step, &StageTimes::segment, w.ElapsedMs());
    w.Restart();
    matcher.SetComponents(&graph);
    if (config.recognition.space_weight > 0.0 || config.recognition.structure_completeness) {
      // Structure alone needs no occupancy snapshot (an empty one holds no free space).
      space_evidence = std::make_unique<MapSpaceEvidence>(
          config.recognition.space_weight > 0.0 ? occupancy.Snapshot(occupancy.KnownBounds())
                                                : mapping::OccupancySnapshot(),
          structure, config.scanner.space);
      matcher.SetSpaceEvidence(space_evidence.get());
    }
    segmentation::PostSegmenterInput input;
    std::set<std::int32_t> included;
    for (const auto& c : graph.components()) {
      ComponentProgress& progress = components_seen[c.label];
      if (progress.done) continue;
      if (IsStructureResidue(c)) continue;
      const double n = static_cast<double>(c.points.size());
      if (progress.match_revision == 0 ||
          std::abs(n - progress.matched_size) > config.scanner.rematch_growth_fraction * progress.matched_size) {
        ++progress.match_revision;
        progress.matched_size = n;
      }
      if (progress.noise_at_revision) {
        if (*progress.noise_at_revision == progress.match_revision) continue;
        progress.noise_at_revision.reset();
      }
      input.components.push_back({c.label, progress.match_revision, c.points.size()});
      included.insert(c.label);
    }
    for (const auto& [a, b] : graph.Edges()) {
      if (included.count(a) && included.count(b)) input.edges.emplace_back(a, b);
    }
    post = post_segmenter.Update(input);
    Charge(step, &StageTimes::recognize, w.ElapsedMs());
    step->num_components = static_cast<int>(input.components.size());
    step->num_objects = static_cast<int>(post.objects.size());
    step->component_queries += post.stats.component_queries;
    step->pair_queries += post.stats.pair_queries;
    step->group_queries += post.stats.group_queries;

    // Objects of this step, keyed by their smallest component label.
    objects.clear();
    for (std::size_t k = 0; k < post.objects.size(); ++k) {
      const auto& r = post.objects[k];
      const int id = r.component_ids.front();
      if (r.status == segmentation::ObjectStatus::kComplete && r.best_model() != nullptr) {
        CompletedObject done;
        done.id = id;
        done.model = *r.best_model();
        done.objectness = r.objectness;
        done.labels = r.component_ids;
        for (auto l : r.component_ids) components_seen[l].done = true;
        completed.push_back(done);
        if (current_ooi == id) current_ooi = -1;
        continue;
      }
      if (r.status == segmentation::ObjectStatus::kNoise && config.scanner.remove_noise) {
        for (auto l : r.component_ids) {
          ComponentProgress& progress = components_seen[l];
          progress.noise_at_revision = progress.match_revision;
        }
        continue;
      }
      objects.push_back(static_cast<int>(k));
    }
    analysis_views = record.views;
    if (analysis_observer) analysis_observer(*owner);
  }

  // The database model's name; "" for none (model_id < 0).
  std::string ModelName(int model_id) const {
    return model_id >= 0 ? database.models()[static_cast<std::size_t>(model_id)].name : std::string();
  }

  // m's database entry; nullptr for a match without one.
  const recognition::DatabaseEntry* EntryOf(const segmentation::ModelMatch& m) const {
    if (m.entry_id < 0 || m.entry_id >= static_cast<int>(database.entries().size())) return nullptr;
    return &database.entries()[static_cast<std::size_t>(m.entry_id)];
  }

  // The points of m's database entry placed by m.T_world_model (none for a match without an entry).
  std::vector<Eigen::Vector3f> PlacedModelPoints(const segmentation::ModelMatch& m) const {
    std::vector<Eigen::Vector3f> points = database.EntryPoints(m.entry_id);
    for (auto& p : points) p = (m.T_world_model * p.cast<double>()).cast<float>();
    return points;
  }

  // The map surface, which hides what lies behind it from an NBV candidate (gathered again only
  // after the map changed).
  const std::vector<Eigen::Vector3f>& Occluders() {
    if (occluders_stale) {
      occluders = surface.positions();  // a snapshot: the map changes before the next refresh
      occluders_stale = false;
    }
    return occluders;
  }

  void UpdateStructure() {
    const double n = static_cast<double>(surface.size());
    if (structure_elements == 0 || n > (1.0 + config.scanner.structure_redetect_growth) * structure_elements) {
      structure = structure_detector.Update(&surface);
      structure_elements = n;
    } else {
      structure_detector.TagElements(&surface, &structure);
    }
  }

  // Whether most of a component lies on the floor or on a detected wall plane (within its span), in
  // a wall's reveals, or is the noise around one of those planes.
  bool IsStructureResidue(const segmentation::Component& c) const {
    const double fraction = config.scanner.structure_residue_fraction;
    if (fraction >= 1.0 || c.points.empty()) return false;
    if (structure.IsPlaneNoise(c.points, c.normals, config.scanner.structure_residue_band_m,
                               config.scanner.structure_residue_min_side_share, fraction)) {
      return true;
    }
    const double d = config.scanner.structure_residue_distance_m;
    const double reveal_m = config.scanner.structure_reveal_depth_m;
    // Across a wall: the element normal within 60 degrees of the wall's direction.
    constexpr double kRevealMaxCos = 0.5;
    std::size_t near = 0;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Eigen::Vector3d p = c.points[i].cast<double>();
      near += structure.OnStructure(p, d) ||
              (reveal_m > 0.0 && i < c.normals.size() &&
               structure.InWallReveal(p, c.normals[i].cast<double>(), reveal_m, kRevealMaxCos));
    }
    return static_cast<double>(near) >= fraction * static_cast<double>(c.points.size());
  }

  // Objects given up for want of a valid view get another chance (the map has changed since).
  void ReopenObjectsWithoutAView() {
    for (auto& [id, progress] : objects_of_interest) {
      if (!progress.given_up_no_view) continue;
      progress.given_up = false;
      progress.given_up_no_view = false;
    }
  }
  bool AnyObjectWithoutAView() const {
    return std::any_of(objects_of_interest.begin(), objects_of_interest.end(),
                       [](const auto& entry) { return entry.second.given_up_no_view; });
  }

  // The components of an object given up for good (stalled, out of views): objects made mostly of them
  // later are given up too (scanner.given_up_surface_share).
  void GiveUpSurface(const segmentation::PostSegmentedObject& r) {
    if (config.scanner.given_up_surface_share <= 0.0) return;
    for (auto l : r.component_ids) components_seen[l].given_up = true;
    any_component_given_up = true;
  }
  bool MostlyGivenUp(const segmentation::PostSegmentedObject& r, std::size_t num_points) const {
    const double share = config.scanner.given_up_surface_share;
    if (share <= 0.0 || !any_component_given_up || num_points == 0) return false;
    std::size_t spent = 0;
    for (auto l : r.component_ids) {
      const auto progress = components_seen.find(l);
      if (progress == components_seen.end() || !progress->second.given_up) continue;
      if (const segmentation::Component* c = segmenter_graph().Find(l)) spent += c->points.size();
    }
    return static_cast<double>(spent) >= share * static_cast<double>(num_points);
  }

  // Points, centre and area of a post-segmented object.
  void ObjectGeometry(const segmentation::PostSegmentedObject& r, std::vector<Eigen::Vector3f>* points,
                      geometry::Aabb3* bounds, double* area_m2, std::size_t* num_points) const {
    const segmentation::ComponentGraph& graph = segmenter_graph();
    if (points) points->clear();
    *bounds = geometry::Aabb3();
    *area_m2 = 0.0;
    *num_points = 0;
    for (auto label : r.component_ids) {
      const segmentation::Component* c = graph.Find(label);
      if (c == nullptr) continue;
      if (points) points->insert(points->end(), c->points.begin(), c->points.end());
      bounds->Extend(c->bounds);
      *area_m2 += c->area_m2;
      *num_points += c->points.size();
    }
  }
  const segmentation::ComponentGraph& segmenter_graph() const { return *graph_cache; }

  // The points of the components with these labels: what the robot saw of an object (a completed
  // one stands for its model, but its components keep the surface it was recognised from).
  std::vector<Eigen::Vector3f> ComponentPoints(const std::vector<std::int32_t>& labels) const {
    std::vector<Eigen::Vector3f> points;
    for (auto l : labels) {
      if (const segmentation::Component* c = segmenter_graph().Find(l)) {
        points.insert(points.end(), c->points.begin(), c->points.end());
      }
    }
    return points;
  }

  // --- one step ------------------------------------------------------------------------------------
  bool ScanObjectStep(StepRecord* step) {
    const geometry::Pose3 T_world_camera = platform.T_world_camera();
    const planning::RobotView view{T_world_camera.translation(), T_world_camera.linear().col(2)};
    while (true) {
      std::vector<planning::NboObject> candidates;
      std::vector<int> candidate_object;  // index into post.objects
      for (int k : objects) {
        const auto& r = post.objects[k];
        const int id = r.component_ids.front();
        ObjectProgress& progress = objects_of_interest[id];
        if (progress.given_up) continue;
        geometry::Aabb3 bounds;
        double area = 0.0;
        std::size_t n = 0;
        ObjectGeometry(r, nullptr, &bounds, &area, &n);
        if (static_cast<int>(n) < config.scanner.min_object_elements) continue;
        if (MostlyGivenUp(r, n)) {
          progress.given_up = true;
          if (current_ooi == id) current_ooi = -1;
          continue;
        }
        const int stall = config.scanner.stall_views;
        const std::vector<double>& history = progress.objectness_history;
        if (stall > 0 && progress.views_spent >= stall &&
            static_cast<int>(history.size()) > progress.views_spent - stall &&
            r.objectness - history[static_cast<std::size_t>(progress.views_spent - stall)] <
                config.scanner.stall_min_gain) {
          progress.given_up = true;
          GiveUpSurface(r);
          if (current_ooi == id) current_ooi = -1;
          step->notes.push_back("object " + std::to_string(id) + ": objectness stalled at " +
                                std::to_string(r.objectness).substr(0, 5) + " over " + std::to_string(stall) +
                                " views");
          continue;
        }
        planning::NboObject o;
        o.id = id;
        o.objectness = r.objectness;
        o.center_world = bounds.Center();
        o.area_m2 = area;
        // Views spent on any of its components count: post-segmentation regroups components from step to
        // step, and a regrouped object (new id) must not restart its view budget.
        int spent = progress.views_spent;
        for (auto l : r.component_ids) {
          const auto component = components_seen.find(l);
          if (component != components_seen.end()) spent = std::max(spent, component->second.views);
        }
        o.views_spent = spent;
        candidates.push_back(o);
        candidate_object.push_back(k);
      }
      if (candidates.empty()) return false;
      Stopwatch w;
      const planning::NboResult nbo = planning::SelectNextBestObject(candidates, view, current_ooi, config.nbo);
      Charge(step, &StageTimes::nbo, w.ElapsedMs());
      for (int id : nbo.budget_spent_ids) {
        objects_of_interest[id].given_up = true;
        for (std::size_t i = 0; i < candidates.size(); ++i) {
          if (candidates[i].id == id) GiveUpSurface(post.objects[candidate_object[i]]);
        }
      }
      if (nbo.status != planning::NboStatus::kOk) return false;
      int k = -1;
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (candidates[i].id == nbo.chosen_id) k = candidate_object[i];
      }
      const auto& gamma = post.objects[k];
      w.Restart();
      std::vector<Eigen::Vector3f> gamma_points;
      geometry::Aabb3 bounds;
      double area = 0.0;
      std::size_t n = 0;
      ObjectGeometry(gamma, &gamma_points, &bounds, &area, &n);
      // Shape priors: the aligned full models of M(gamma).
      // Matches without a database entry have no points to place; each placed set keeps its match.
      std::vector<const segmentation::ModelMatch*> placed;
      for (const auto& m : gamma.full_model_matches.models) {
        if (EntryOf(m) == nullptr) continue;
        placed.push_back(&m);
        if (placed.size() >= 15) break;
      }
      std::vector<std::vector<Eigen::Vector3f>> model_points(placed.size());
      std::vector<planning::ModelHypothesis> hypotheses;
      for (std::size_t i = 0; i < placed.size(); ++i) {
        model_points[i] = PlacedModelPoints(*placed[i]);
        planning::ModelHypothesis h;
        h.model_id = placed[i]->model_id;
        h.objectness = std::max(0.0, placed[i]->objectness);
        h.points_world = &model_points[i];
        hypotheses.push_back(h);
      }
      planning::NextBestViewInput input;
      input.gamma_points_world = &gamma_points;
      input.models = hypotheses;
      input.occluder_points_world = &Occluders();
      input.frustum = frustum;
      input.has_camera_position = true;
      input.camera_position_world = platform.T_world_camera().translation();
      const double radius = 0.5 * bounds.Diagonal();
      std::vector<geometry::Pose3> earlier = objects_of_interest[nbo.chosen_id].views;
      earlier.push_back(platform.T_world_camera());
      MapViewValidator validator(occupancy, platform, navigator, std::max(config.scanner.line_of_sight_skip_m, radius),
                                 earlier, config.scanner.min_view_separation_m, config.scanner.min_view_separation_deg);
      const planning::NextBestViewResult result = nbv.Plan(input, &validator);
      Charge(step, &StageTimes::nbv, w.ElapsedMs());
      for (const auto& c : result.candidates) {
        step->nbv_candidates.push_back({c.T_world_camera, planning::ToString(c.validity), c.gain.gain});
      }
      const int id = nbo.chosen_id;
      bool moved = false;
      if (result.status == planning::NbvStatus::kOk) {
        moved = MoveCamera(result.candidates[result.best_index].T_world_camera, step);
        if (!moved) step->notes.push_back("object " + std::to_string(id) + ": best view not reachable");
      } else {
        std::map<std::string, int> why;
        for (const auto& c : result.candidates) ++why[planning::ToString(c.validity)];
        std::string note = "object " + std::to_string(id) + ": no valid view (";
        for (const auto& [k, n] : why) note += k + " " + std::to_string(n) + ", ";
        note.resize(note.size() - 2);
        step->notes.push_back(note + ")");
      }
      ObjectProgress& progress = objects_of_interest[id];
      if (!moved) {
        progress.given_up = true;
        progress.given_up_no_view = true;
        step->nbv_candidates.clear();
        if (current_ooi == id) current_ooi = -1;
        continue;
      }
      step->action = (id == current_ooi) ? "nbv" : "nbo";
      if (id != current_ooi) ++record.nbo_count;
      current_ooi = id;
      step->ooi = id;
      progress.objectness_history.resize(static_cast<std::size_t>(progress.views_spent) + 1, 0.0);
      progress.objectness_history[static_cast<std::size_t>(progress.views_spent)] = gamma.objectness;
      ++progress.views_spent;
      for (auto l : gamma.component_ids) ++components_seen[l].views;
      progress.views.push_back(platform.T_world_camera());
      ++record.nbv_views;
      return true;
    }
  }

  static planning::NextBestViewOptions CoverageNbvOptions(const SystemConfig& c) {
    planning::NextBestViewOptions o = c.nbv;
    o.candidates.ring_elevations_deg = c.scanner.coverage_views.ring_elevations_deg;
    o.candidates.num_candidates = c.scanner.coverage_views.num_candidates;
    return o;
  }

  // Model surface this close to a wall is not aimed at by coverage views (coverage_views.h,
  // aim_at_unseen): an object's back against the wall is never seen.
  static constexpr double kCoverageAimWallMarginM = 0.1;

  // One view completing the scan of a reported object (coverage_views.h); false when no object has
  // a view showing enough of its unseen model surface.
  bool CoverageStep(StepRecord* step) {
    const CoverageViewOptions& options = config.scanner.coverage_views;
    if (!options.enabled || options.max_views_per_object <= 0) return false;
    struct Target {
      int id = -1;
      const segmentation::ModelMatch* model = nullptr;
      Eigen::Vector3d center_world = Eigen::Vector3d::Zero();
    };
    std::vector<Target> targets;
    const auto consider = [&](int id, const segmentation::ModelMatch* m, double objectness) {
      if (m == nullptr || EntryOf(*m) == nullptr) return;
      if (objectness < options.min_objectness || objects_of_interest[id].coverage_attempts >= options.max_views_per_object) return;
      targets.push_back({id, m, m->T_world_model.translation()});
    };
    for (const auto& c : completed) consider(c.id, &c.model, c.objectness);
    for (int k : objects) {
      const auto& r = post.objects[k];
      const auto* best = r.best_model();
      consider(r.component_ids.front(), best, best != nullptr ? best->objectness : 0.0);
    }
    // Nearest first (ties by id, so the order does not depend on container order).
    const Eigen::Vector2d here = platform.base().xy_m;
    std::sort(targets.begin(), targets.end(), [&](const Target& a, const Target& b) {
      const double da = (a.center_world.head<2>() - here).norm(), db = (b.center_world.head<2>() - here).norm();
      return da != db ? da < db : a.id < b.id;
    });
    const std::vector<Eigen::Vector3f>& map_points = Occluders();
    for (const Target& t : targets) {
      ++objects_of_interest[t.id].coverage_attempts;
      Stopwatch w;
      const std::vector<Eigen::Vector3f> model_points = ModelSurfaceAboveFloor(
          PlacedModelPoints(*t.model), structure.has_floor, structure.floor_height_m, options.floor_clearance_m);
      if (model_points.empty()) continue;
      // Everything the robot saw around the model counts as seen, whichever object it went to.
      geometry::Aabb3 box;
      for (const auto& p : model_points) box.Extend(p.cast<double>());
      const double margin_m = 2.0 * config.nbv.voxel_size_m;
      std::vector<Eigen::Vector3f> seen;
      for (const auto& p : map_points) {
        if (box.Contains(p.cast<double>(), margin_m)) seen.push_back(p);
      }
      if (seen.empty()) continue;
      planning::NextBestViewInput input;
      input.gamma_points_world = &seen;
      input.models = {planning::ModelHypothesis{t.model->model_id, 1.0, &model_points}};
      input.occluder_points_world = &map_points;
      input.frustum = frustum;
      input.has_camera_position = true;
      input.camera_position_world = platform.T_world_camera().translation();
      input.gain_measure = planning::ViewGainMeasure::kUnobservedSurface;
      // The model surface still unseen, leaving out what lies against a wall (no view reaches it).
      std::vector<Eigen::Vector3f> aim;
      if (options.aim_at_unseen) {
        for (const auto& p : UnseenModelPoints(model_points, seen, margin_m)) {
          const Eigen::Vector3d q = p.cast<double>();
          if (structure.InsideWalls(q, 0.0) && !structure.NearWall(q, kCoverageAimWallMarginM)) aim.push_back(p);
        }
        input.aim_points_world = &aim;
      }
      std::vector<geometry::Pose3> earlier = objects_of_interest[t.id].views;
      earlier.push_back(platform.T_world_camera());
      MapViewValidator validator(occupancy, platform, navigator,
                                 std::max(config.scanner.line_of_sight_skip_m, 0.5 * box.Diagonal()), earlier,
                                 config.scanner.min_view_separation_m, config.scanner.min_view_separation_deg);
      const planning::NextBestViewResult result = coverage_nbv.Plan(input, &validator);
      Charge(step, &StageTimes::nbv, w.ElapsedMs());
      if (result.status != planning::NbvStatus::kOk ||
          result.candidates[result.best_index].gain.gain < options.min_unseen_voxels) {
        continue;
      }
      if (!MoveCamera(result.candidates[result.best_index].T_world_camera, step)) {
        step->notes.push_back("object " + std::to_string(t.id) + ": coverage view not reachable");
        continue;
      }
      step->action = "nbv";
      step->coverage_view = true;
      step->ooi = t.id;
      step->nbv_candidates.clear();
      for (const auto& c : result.candidates) {
        step->nbv_candidates.push_back({c.T_world_camera, planning::ToString(c.validity), c.gain.gain});
      }
      objects_of_interest[t.id].views.push_back(platform.T_world_camera());
      ++record.coverage_views;
      return true;
    }
    return false;
  }

  // Exploration: returns the termination when there is nothing left to do.
  Termination ExploreStep(StepRecord* step) {
    step->action = "frontier";
    const std::vector<mapping::FrontierGoal> goals =
        mapping::FindFloorFrontiers(surface, occupancy, structure, config.frontiers);
    std::vector<planning::FrontierCandidate> frontiers;
    for (const auto& g : goals) {
      frontiers.push_back({Eigen::Vector3d(g.centroid_m.x(), g.centroid_m.y(), 0.0), g.size_cells});
    }
    const Eigen::Vector2d from = platform.base().xy_m;
    auto path_length = [&](const Eigen::Vector3d& goal) -> std::optional<double> {
      Eigen::Vector2d free_xy;
      if (!navigator.NearestFree(goal.head<2>(), config.scanner.frontier_max_snap_m, &free_xy)) return std::nullopt;
      const navigation::Path2D path = navigator.Plan(from, free_xy);
      if (!path.ok()) return std::nullopt;
      return path.length_m;
    };
    const planning::FrontierChoice choice =
        planning::ChooseFrontier(frontiers, path_length, visited_goals, config.exploration);
    RecordUnreachableFrontiers(goals, choice);
    const planning::ScanAction action = planning::DecideAction(false, choice.status);
    if (action == planning::ScanAction::kDone) return Termination::kDone;
    if (action == planning::ScanAction::kStuck) return Termination::kStuck;
    const Eigen::Vector3d goal = frontiers[choice.best_index].centroid_world;
    visited_goals.push_back(goal);
    Eigen::Vector2d base_xy;
    if (!navigator.NearestFree(goal.head<2>(), config.scanner.frontier_max_snap_m, &base_xy)) {
      step->notes.push_back("frontier goal has no free cell nearby");
      return Termination::kRunning;
    }
    // Look around at the frontier, starting towards the unexplored side.
    const double heading = std::atan2(goal.y() - from.y(), goal.x() - from.x());
    planning::ExplorationOptions look = config.exploration;
    look.look_around_yaw_steps = config.scanner.frontier_views;
    look.look_around_pitches_deg = {config.scanner.explore_pitch_deg};
    const auto views = planning::LookAroundViews(
        Eigen::Vector3d(base_xy.x(), base_xy.y(), config.scanner.start_camera_height_m), heading, look);
    bool moved = false;
    for (const auto& T : views) {
      if (!moved) {
        platform::ReachStatus why = platform::ReachStatus::kOk;
        moved = MoveCamera(T, step, &why);
        if (!moved) {
          step->notes.push_back(std::string("frontier view not reachable (") + platform::ReachStatusName(why) + ")");
          break;
        }
      } else {
        TurnInPlaceView(T, step);
      }
      step->look_around = true;
    }
    return Termination::kRunning;
  }

  // The frontiers of the last exploration step that no path reaches (RunRecord::unreachable).
  void RecordUnreachableFrontiers(const std::vector<mapping::FrontierGoal>& goals, const planning::FrontierChoice& choice) {
    UnreachableRecord& u = record.unreachable;
    u.frontiers.clear();
    u.frontier_area_m2 = 0.0;
    const double cell_m2 = config.frontiers.cell_size_m * config.frontiers.cell_size_m;
    for (std::size_t i = 0; i < goals.size(); ++i) {
      if (choice.scores[i].exclusion != planning::FrontierExclusion::kUnreachable) continue;
      const double area_m2 = cell_m2 * goals[i].size_cells;
      u.frontiers.push_back({goals[i].centroid_m.x(), goals[i].centroid_m.y(), goals[i].size_cells, area_m2});
      u.frontier_area_m2 += area_m2;
    }
  }

  // Whether the robot can drive at least kMinMoveM from where it stands. With frontiers left that no
  // path reaches, a robot that can move has explored all it can (`done`); one that cannot is `stuck`.
  static constexpr double kMinMoveM = 0.25;
  bool RobotCanMove() {
    RefreshNavigation();
    Eigen::Vector2d start;
    if (!navigator.StartFrom(platform.base().xy_m, &start)) return false;
    const std::vector<double> distance_m = navigator.DistanceField(start);
    return std::any_of(distance_m.begin(), distance_m.end(),
                       [](double d) { return std::isfinite(d) && d >= kMinMoveM; });
  }

  // The explored area and the step budget it gives (ScannerOptions::steps_per_explored_m2).
  void UpdateStepBudget() {
    RefreshNavigation();
    const navigation::OccupancyGrid2D& grid = navigator.grid();
    const double cell_m2 = grid.cell_size_m * grid.cell_size_m;
    record.explored_area_m2 =
        cell_m2 *
        static_cast<double>(grid.Count(navigation::CellState::kFree) + grid.Count(navigation::CellState::kOccupied));
    const ScannerOptions& o = config.scanner;
    const double by_area = std::min(1e9, std::ceil(o.steps_per_explored_m2 * record.explored_area_m2));
    record.step_budget = std::min(o.max_steps, std::max(o.step_budget, static_cast<int>(by_area)));
  }

  void RefreshNavigation() {
    if (!map_changed) return;
    navigator.Update(robot_occupancy);
    occluders_stale = true;
    map_changed = false;
  }

  // --- the end of the run -------------------------------------------------------------------------
  // What the last views showed.
  void FinalAnalysis() {
    StepRecord final_step;
    RefreshNavigation();
    Analyze(&final_step);
  }

  // The floor and walls the robot took for the room's structure.
  void RecordStructure() {
    record.structure = StructureRecord();
    if (structure.has_floor) record.structure.floor_height_m = structure.floor_height_m;
    for (const mapping::WallPlane& w : structure.walls) {
      record.structure.walls.push_back({w.normal.x(), w.normal.y(), w.offset_m, w.span_min_m, w.span_max_m, w.z_min_m,
                                        w.z_max_m, w.area_m2});
    }
  }

  // The report stage's view of recognition, the map and the database (report/report_context.h).
  class Sources : public ReportSources {
   public:
    explicit Sources(State& s) : s_(s) {}
    segmentation::MatchResult MatchFullModels(const std::vector<std::int32_t>& labels) override {
      return s_.matcher.Match(labels, segmentation::MatchScope::kFullModels);
    }
    std::optional<segmentation::ModelMatch> BestOfCategory(const std::vector<std::int32_t>& labels,
                                                           world::Category category) override {
      return s_.matcher.BestOfCategory(labels, category);
    }
    std::vector<Eigen::Vector3f> ComponentPoints(const std::vector<std::int32_t>& labels) const override {
      return s_.ComponentPoints(labels);
    }
    std::size_t ElementCount(const std::vector<std::int32_t>& labels) const override {
      const std::set<std::int32_t> wanted(labels.begin(), labels.end());
      std::size_t n = 0;
      for (std::size_t e = 0; e < s_.surface.size(); ++e) {
        n += s_.surface.structure(e) == mapping::Structure::kNone && wanted.count(s_.surface.label(e)) > 0;
      }
      return n;
    }
    std::string ModelName(int model_id) const override { return s_.ModelName(model_id); }
    std::vector<Eigen::Vector3f> EntryPoints(int entry_id) const override {
      return s_.database.EntryPoints(entry_id);
    }
    std::vector<float> CategoryOdds(const std::vector<std::int32_t>& labels) override {
      return s_.matcher.CategoryOdds(labels);
    }
    std::optional<world::Category> NameCategory(const std::vector<std::int32_t>& labels,
                                                const std::vector<recognition::RetrievedCategory>& votes) override {
      return s_.matcher.NameCategory(labels, votes);
    }

   private:
    State& s_;
  };

  // The objects the loop left: completed objects (their model) and the post-segmented objects large
  // enough to be scanned, each unfinished one with its best full model.
  void CollectObjects(ReportedObjects* objects) const {
    for (const auto& c : completed) {
      ReportedObject r;
      ObjectRecord& o = r.record;
      o.id = c.id;
      o.category = c.model.category;
      o.model_index = c.model.model_id;
      o.model = ModelName(c.model.model_id);
      o.objectness = c.objectness;
      o.complete = true;
      o.T_world_model = c.model.T_world_model;
      o.labels = c.labels;
      r.model_entry = c.model.entry_id;
      for (auto l : c.labels) {
        if (const segmentation::Component* comp = segmenter_graph().Find(l)) r.num_elements += comp->points.size();
      }
      objects->Add(std::move(r));
    }
    for (int k : this->objects) {
      const auto& p = post.objects[k];
      ReportedObject r;
      geometry::Aabb3 bounds;
      double area_m2 = 0.0;
      std::size_t num_points = 0;
      ObjectGeometry(p, &r.points_world, &bounds, &area_m2, &num_points);
      // Fragments too small to be scanned as objects are reported as unrecognized surface.
      if (static_cast<int>(num_points) < config.scanner.min_object_elements) continue;
      ObjectRecord& o = r.record;
      o.id = p.component_ids.front();
      o.category = p.category;
      if (const auto* best = p.best_model()) {
        o.model_index = best->model_id;
        o.model = ModelName(best->model_id);
        o.T_world_model = best->T_world_model;
        r.model_entry = best->entry_id;
      }
      o.objectness = p.objectness;
      const auto progress = objects_of_interest.find(o.id);
      o.given_up = progress != objects_of_interest.end() && progress->second.given_up;
      o.labels = p.component_ids;
      r.full_matches = &p.full_model_matches;
      objects->Add(std::move(r));
    }
  }

  // The object list of the run: the loop's objects after the report rules of `options`.
  std::vector<ObjectRecord> ReportObjects(const ReportOptions& options) {
    ReportedObjects objects;
    CollectObjects(&objects);
    const ReportPipeline pipeline(options);
    // Measured here, not at start-up: only the end of a run needs the models' sizes.
    const recognition::CategoryExtents category_extents = pipeline.needs_category_extents()
                                                              ? recognition::CategoryExtents::FromDatabase(database)
                                                              : recognition::CategoryExtents();
    Sources sources(*this);
    ReportContext context;
    context.sources = &sources;
    context.structure = &structure;
    context.category_extents = &category_extents;
    pipeline.Run(context, &objects);
    // What was seen of each object, and what else recognition considered.
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (!objects[i].reported()) continue;
      ObjectRecord& o = objects.mutable_object(i).record;
      const recognition::ObjectExtent extent = MeasureReportedExtent(context, objects, i, options.size_check);
      o.height_m = extent.height_m;
      o.footprint_diagonal_m = extent.footprint_diagonal_m;
      o.points = static_cast<int>(sources.ElementCount(o.labels));
      if (objects[i].full_matches == nullptr) continue;
      for (const auto& m : objects[i].full_matches->models) {
        o.alternatives.push_back({m.category, ModelName(m.model_id), m.objectness});
      }
    }
    std::vector<ObjectRecord> records = objects.TakeReportedRecords();
    // An object with no element left outside the structure is gone from the map: typically a completed
    // object whose pieces all became wall later (the object that now holds its surface reports it).
    records.erase(std::remove_if(records.begin(), records.end(), [](const ObjectRecord& o) { return o.points == 0; }),
                  records.end());
    return records;
  }

  const SystemConfig config;
  const recognition::ModelDatabase& database;
  platform::Platform& platform;  // the robot: where it is, its frames and its moves
  mapping::SurfaceMap surface;
  mapping::OccupancyMap occupancy;
  segmentation::IncrementalSegmenter segmenter;
  mapping::StructureDetector structure_detector;
  mapping::StructureResult structure;
  double structure_elements = 0;  // map size at the last full floor/wall search
  recognition::Recognizer recognizer;
  recognition::RecognizerComponentMatcher matcher;
  std::unique_ptr<MapSpaceEvidence> space_evidence;  // rebuilt at every analysis
  segmentation::PostSegmenter post_segmenter;
  planning::NextBestView nbv;
  planning::NextBestView coverage_nbv;  // the NBV planner with the coverage views' candidate rings
  planning::CameraFrustum frustum;
  std::vector<Eigen::Vector2d> visited;  // where the base has stood (free floor)
  RobotOccupancy robot_occupancy;
  navigation::Navigator navigator;
  FrameObserver observer;
  AnalysisObserver analysis_observer;
  const Scanner* owner = nullptr;
  int analysis_views = 0;
  RunRecord record;

  const segmentation::ComponentGraph* graph_cache = nullptr;
  segmentation::PostSegmentation post;
  std::vector<int> objects;  // partial objects of `post` (indices)
  std::vector<CompletedObject> completed;
  std::map<std::int32_t, ComponentProgress> components_seen;  // by component label
  std::map<int, ObjectProgress> objects_of_interest;          // by object id
  bool any_component_given_up = false;
  std::vector<Eigen::Vector2d> stuck_lookarounds;  // where the robot looked around on getting stuck
  int views_at_reopen = -1;  // record.views when objects without a valid view were last given another chance
  std::vector<Eigen::Vector3d> visited_goals;
  std::vector<Eigen::Vector3f> occluders;
  bool occluders_stale = true;
  bool map_changed = true;
  int current_ooi = -1;
  bool finished = false;  // Run() has reported the objects
  Stopwatch wall;
  bool analyze_objects = true;  // segment and recognise every step (object guidance)
  std::vector<std::unique_ptr<ScanStep>> step_kinds;  // tried in this order each step
};

// The paper's step: the next best object and a next best view of it.
class Scanner::State::ObjectScanStep final : public ScanStep {
 public:
  explicit ObjectScanStep(State& s) : s_(s) {}
  const char* name() const override { return "object"; }
  StepOutcome Take(StepRecord* step) override {
    return s_.ScanObjectStep(step) ? StepOutcome::Taken() : StepOutcome::NotTaken();
  }

 private:
  State& s_;
};

// Frontier exploration. Before it lets the run end it looks around once wherever the robot got stuck
// (the views show it the space its earlier, targeted views left unknown), and gives objects given up
// for want of a valid view another chance whenever views were taken since the last one.
class Scanner::State::FrontierExplorationStep final : public ScanStep {
 public:
  explicit FrontierExplorationStep(State& s) : s_(s) {}
  const char* name() const override { return "exploration"; }
  StepOutcome Take(StepRecord* step) override {
    const Termination t = s_.ExploreStep(step);
    if (t == Termination::kRunning) return StepOutcome::Taken();
    const Eigen::Vector2d here = s_.platform.base().xy_m;
    const bool looked_here = std::any_of(s_.stuck_lookarounds.begin(), s_.stuck_lookarounds.end(),
                                         [&](const Eigen::Vector2d& p) { return (p - here).norm() < 0.5; });
    if (t == Termination::kStuck && !looked_here) {
      s_.stuck_lookarounds.push_back(here);
      step->notes.push_back("no reachable goal: looking around before giving up");
      s_.LookAroundInPlace(step);
      s_.ReopenObjectsWithoutAView();  // with the better map
      s_.views_at_reopen = s_.record.views;
      return StepOutcome::Taken();
    }
    if (t == Termination::kStuck && s_.AnyObjectWithoutAView() && s_.record.views > s_.views_at_reopen) {
      // Unreachable frontiers must not end the run while an object may have a view.
      step->notes.push_back("no reachable goal: objects without a valid view get another chance");
      s_.ReopenObjectsWithoutAView();
      s_.views_at_reopen = s_.record.views;
      return StepOutcome::Taken();
    }
    return StepOutcome::NotTaken(t);
  }

 private:
  State& s_;
};

// Nothing else left: complete the scans of the reported objects (coverage_views.h).
class Scanner::State::CoverageViewStep final : public ScanStep {
 public:
  explicit CoverageViewStep(State& s) : s_(s) {}
  const char* name() const override { return "coverage"; }
  StepOutcome Take(StepRecord* step) override {
    return s_.CoverageStep(step) ? StepOutcome::Taken() : StepOutcome::NotTaken();
  }

 private:
  State& s_;
};

// The guidance: which kinds of step, in which order, and whether objects are analysed each step.
// "object" is the paper's loop (frontiers when no object is left) with coverage views at the end;
// "frontier" explores only.
void Scanner::State::ChooseStepKinds() {
  analyze_objects = config.scanner.guidance == "object";
  step_kinds.clear();
  if (analyze_objects) step_kinds.push_back(std::make_unique<ObjectScanStep>(*this));
  step_kinds.push_back(std::make_unique<FrontierExplorationStep>(*this));
  if (analyze_objects) step_kinds.push_back(std::make_unique<CoverageViewStep>(*this));
}

Scanner::Scanner(const SystemConfig& config, platform::Platform* platform, const recognition::ModelDatabase& database,
                 std::uint64_t seed) {
  config.Validate();
  if (!database.finalized()) throw InputError("model database is not finalized");
  if (database.models().empty()) throw InputError("model database is empty");
  if (platform == nullptr) throw std::invalid_argument("Scanner: no platform");
  state_ = std::make_unique<State>(config, platform, database, seed);
  state_->owner = this;
}

Scanner::~Scanner() = default;

void Scanner::set_frame_observer(FrameObserver observer) { state_->observer = std::move(observer); }
void Scanner::set_analysis_observer(AnalysisObserver observer) { state_->analysis_observer = std::move(observer); }
int Scanner::analysis_views() const { return state_->analysis_views; }
const recognition::CachedClassifierStatus& Scanner::classifier_cache_status() const {
  return state_->recognizer.classifier_cache_status();
}

void Scanner::AnalysisElementObjects(std::vector<int>* object_id) const {
  const State& s = *state_;
  std::unordered_map<std::int32_t, int> object_of_label;
  for (const auto& c : s.completed) {
    for (auto l : c.labels) object_of_label[l] = c.id;
  }
  for (int k : s.objects) {
    const auto& r = s.post.objects[k];
    for (auto l : r.component_ids) object_of_label[l] = r.component_ids.front();
  }
  object_id->assign(s.surface.size(), -1);
  for (std::size_t e = 0; e < s.surface.size(); ++e) {
    if (s.surface.structure(e) != mapping::Structure::kNone) continue;
    auto it = object_of_label.find(s.surface.label(e));
    if (it != object_of_label.end()) (*object_id)[e] = it->second;
  }
}

const RunRecord& Scanner::record() const { return state_->record; }
const mapping::SurfaceMap& Scanner::surface_map() const { return state_->surface; }

bool Scanner::Step() {
  State& s = *state_;
  RunRecord& rec = s.record;
  if (rec.terminated != Termination::kRunning) return false;
  s.UpdateStepBudget();
  if (static_cast<int>(rec.steps.size()) >= rec.step_budget) {
    rec.terminated = Termination::kMaxSteps;
    return false;
  }
  StepRecord step;
  step.index = static_cast<int>(rec.steps.size());
  Stopwatch step_wall;
  if (step.index == 0) {
    // Start by looking around in place.
    s.AddTrajectorySample(0, false);
    s.LookAroundInPlace(&step);
  } else {
    s.RefreshNavigation();
    if (s.analyze_objects) {
      s.Analyze(&step);
    } else {
      s.UpdateStructure();
    }
    bool taken = false;
    std::optional<Termination> end;
    for (const std::unique_ptr<ScanStep>& kind : s.step_kinds) {
      const StepOutcome outcome = kind->Take(&step);
      if (outcome.taken) {
        taken = true;
        break;
      }
      if (outcome.end) end = outcome.end;
    }
    if (!taken) {
      Termination t = end.value_or(Termination::kDone);
      if (t == Termination::kStuck && s.RobotCanMove()) {
        t = Termination::kDone;
        char note[96];
        std::snprintf(note, sizeof(note), "the frontiers left are unreachable (%zu, %.2f m2)",
                      rec.unreachable.frontiers.size(), rec.unreachable.frontier_area_m2);
        step.notes.push_back(note);
      }
      rec.terminated = t;
      step.notes.push_back(std::string("terminated: ") + TerminationName(t));
    }
  }
  rec.travel_m = s.platform.travel().distance_m;
  StageTimes seconds = step.timing_ms;
  for (double* t : {&seconds.sense, &seconds.fuse, &seconds.segment, &seconds.recognize, &seconds.nbo, &seconds.nbv,
                    &seconds.navigate_sim}) {
    *t /= 1e3;
  }
  rec.timing_s += seconds;
  step.wall_ms = step_wall.ElapsedMs();
  rec.steps.push_back(std::move(step));
  return rec.terminated == Termination::kRunning;
}

const RunRecord& Scanner::Run(const ProgressCallback& progress) {
  State& s = *state_;
  while (Step()) {
    ReportProgress(progress, static_cast<double>(s.record.steps.size()) / std::max(1, s.record.step_budget),
                   "step " + std::to_string(s.record.steps.size()) + ", " + std::to_string(s.completed.size()) +
                       " objects complete");
  }
  s.FinalAnalysis();
  s.RecordStructure();
  s.record.objects = s.ReportObjects(s.config.report);
  // Objects left unfinished because none of their views could be reached.
  for (const ObjectRecord& o : s.record.objects) {
    const auto progress = s.objects_of_interest.find(o.id);
    if (!o.complete && progress != s.objects_of_interest.end() && progress->second.given_up_no_view) {
      s.record.unreachable.objects.push_back(o.id);
    }
  }
  // At the step budget the last exploration step's frontiers say nothing about how the run ended.
  if (s.record.terminated == Termination::kMaxSteps) {
    s.record.unreachable.frontiers.clear();
    s.record.unreachable.frontier_area_m2 = 0.0;
  }
  s.finished = true;
  s.record.timing_s.total = s.wall.ElapsedSeconds();
  return s.record;
}

std::vector<ObjectRecord> Scanner::ReportWith(const ReportOptions& options) {
  if (!state_->finished) {
    throw std::logic_error("Scanner::ReportWith: call Run() first");
  }
  return state_->ReportObjects(options);
}

void Scanner::ElementObjects(std::vector<int>* object_id, std::vector<int>* category_id) const {
  const State& s = *state_;
  std::map<std::int32_t, const ObjectRecord*> object_of_label;
  for (const auto& o : s.record.objects) {
    for (auto l : o.labels) object_of_label[l] = &o;
  }
  object_id->assign(s.surface.size(), -1);
  category_id->assign(s.surface.size(), -1);
  for (std::size_t e = 0; e < s.surface.size(); ++e) {
    const auto st = s.surface.structure(e);
    if (st == mapping::Structure::kFloor) {
      (*category_id)[e] = world::CategoryId(world::Category::kFloor);
      continue;
    }
    if (st == mapping::Structure::kWall) {
      (*category_id)[e] = world::CategoryId(world::Category::kWall);
      continue;
    }
    if (st == mapping::Structure::kCeiling) {
      (*category_id)[e] = world::CategoryId(world::Category::kCeiling);
      continue;
    }
    auto it = object_of_label.find(s.surface.label(e));
    if (it == object_of_label.end()) continue;
    (*object_id)[e] = it->second->id;
    if (it->second->category) (*category_id)[e] = world::CategoryId(*it->second->category);
  }
}

void Scanner::WriteNavigationMap(const std::string& path, int pixels_per_cell) const {
  const State& s = *state_;
  const navigation::OccupancyGrid2D& grid = s.navigator.grid();
  const std::vector<std::uint8_t>& blocked = s.navigator.blocked();
  const int k = std::max(1, pixels_per_cell);
  const int w = std::max(1, grid.width * k), h = std::max(1, grid.height * k);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3, 128);
  auto put = [&](int px, int py, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    if (px < 0 || py < 0 || px >= w || py >= h) return;
    const std::size_t i = 3 * (static_cast<std::size_t>(h - 1 - py) * w + px);  // north up
    rgb[i] = r, rgb[i + 1] = g, rgb[i + 2] = b;
  };
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      const std::size_t c = grid.Index(ix, iy);
      std::uint8_t r = 128, g = 128, b = 128;
      if (grid.cells[c] == navigation::CellState::kFree) r = g = b = 255;
      if (grid.cells[c] == navigation::CellState::kOccupied) r = g = b = 0;
      if (blocked[c] && grid.cells[c] == navigation::CellState::kFree) r = 255, g = 190, b = 190;
      for (int dy = 0; dy < k; ++dy)
        for (int dx = 0; dx < k; ++dx) put(ix * k + dx, iy * k + dy, r, g, b);
    }
  }
  for (const auto& t : s.record.trajectory) {
    const Eigen::Vector2i c = grid.CellOf(Eigen::Vector2d(t.x_m, t.y_m));
    for (int dy = 0; dy < k; ++dy)
      for (int dx = 0; dx < k; ++dx) put(c.x() * k + dx, c.y() * k + dy, 30, 60, 220);
  }
  io::WritePngRgb(path, w, h, rgb);
}

}  // namespace objscan::scanning
