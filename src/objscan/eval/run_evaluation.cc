#include "objscan/eval/run_evaluation.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>

#include "objscan/eval/exposure.h"
#include "objscan/eval/ground_truth_votes.h"
#include "objscan/eval/observability.h"
#include "objscan/eval/reachability.h"
#include "objscan/eval/rooms.h"
#include "objscan/geometry/voxel_key.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/segmentation/segmentation_quality.h"
#include "objscan/render/raycaster.h"

namespace objscan::eval {
namespace {

constexpr double kOnFloorMaxZ_m = 0.06;  // a ground object's lowest point is this close to the floor

// Surface voxels of every non-structural object: triangles sampled at a fraction of the voxel size.
// normal_lines (when given) receives each voxel's surface orientations.
std::vector<SurfaceVoxel> SurfaceVoxelsOf(const world::Scene& scene, double voxel_m,
                                          std::vector<NormalLines>* normal_lines) {
  const float inv = static_cast<float>(1.0 / voxel_m);
  struct Acc {
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    std::map<int, double> area;
    NormalLines lines;
  };
  std::unordered_map<geometry::VoxelKey, Acc, geometry::VoxelKeyHash> acc;
  std::vector<geometry::VoxelKey> order;
  const double step = 0.4 * voxel_m;
  for (const auto& o : scene.objects()) {
    if (o.IsStructural()) continue;
    for (const auto& t : o.mesh.triangles) {
      const Eigen::Vector3d a = o.T_world_object * o.mesh.vertices[t[0]].cast<double>();
      const Eigen::Vector3d b = o.T_world_object * o.mesh.vertices[t[1]].cast<double>();
      const Eigen::Vector3d c = o.T_world_object * o.mesh.vertices[t[2]].cast<double>();
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double area = 0.5 * n.norm();
      if (area <= 0.0) continue;
      const double w = area / ((SampleCount(a, b, step) + 1) * (SampleCount(a, c, step) + 1));
      SampleTriangle(a, b, c, step, [&](const Eigen::Vector3d& p) {
        const geometry::VoxelKey k = geometry::KeyOf(p.cast<float>(), inv);
        auto [it, inserted] = acc.try_emplace(k);
        if (inserted) order.push_back(k);
        it->second.normal += w * n.normalized();
        it->second.area[o.instance_id] += w;
        if (normal_lines) AddNormalLine(&it->second.lines, n.normalized().cast<float>(), static_cast<float>(w));
      });
    }
  }
  std::sort(order.begin(), order.end());
  std::vector<SurfaceVoxel> voxels;
  voxels.reserve(order.size());
  if (normal_lines) normal_lines->clear();
  for (const auto& k : order) {
    const Acc& a = acc.at(k);
    SurfaceVoxel v;
    v.center_world = geometry::CenterOf(k, static_cast<float>(voxel_m)).cast<double>();
    v.normal_world = a.normal.norm() > 1e-12 ? a.normal.normalized() : Eigen::Vector3d::UnitZ();
    double best = -1.0;
    for (const auto& [inst, area] : a.area) {
      if (area > best) {
        best = area;
        v.instance = inst;
      }
    }
    voxels.push_back(v);
    if (normal_lines) normal_lines->push_back(a.lines);
  }
  return voxels;
}

}  // namespace

struct RunEvaluator::Impl {
  const world::Scene& scene;
  scanning::SystemConfig config;
  std::vector<world::Category> database_categories;
  double voxel_m;
  std::unordered_map<geometry::VoxelKey, int, geometry::VoxelKeyHash> voxel_index;
  std::unique_ptr<CoverageAccumulator> coverage;
  std::vector<std::vector<int>> seen_per_view;
  std::vector<Eigen::Vector3d> camera_per_view;
  std::vector<std::pair<int, double>> rand_index_per_view;
  GroundTruthVotes votes;  // each map element's ground-truth instance

  // Ground truth set: every non-structural object; the structural instances listed apart. Fixed for
  // the run, so taken once.
  std::vector<GroundTruthInstance> truth;
  std::vector<std::int32_t> structural;
  // The scene's rooms and the room of each ground-truth instance (by its bounding box's centre).
  RoomPartition rooms;
  std::unordered_map<int, int> room_of_instance;

  // Rand Index over the reconstructed non-structural points: points outside every object keep
  // their pre-segment (negated, so ids never collide).
  double RandIndexOf(const mapping::SurfaceMap& map, const std::vector<int>& object_id) const {
    std::vector<std::int32_t> segment, instance;
    segment.reserve(map.size());
    instance.reserve(map.size());
    for (std::size_t e = 0; e < map.size(); ++e) {
      if (map.structure(e) != mapping::Structure::kNone) continue;
      segment.push_back(object_id[e] >= 0 ? object_id[e] : -1 - map.label(e));
      instance.push_back(votes.Instance(e));
    }
    return NonStructuralRandIndex(segment, instance, truth);
  }

  // V_S is fixed when the first camera position is known (the exposed voxels are those joined to it
  // through empty space); until then the voxels wait here.
  std::vector<SurfaceVoxel> surface_voxels;
  std::vector<NormalLines> surface_normal_lines;  // parallel to surface_voxels until V_S is fixed

  CoverageOptions Options() const {
    CoverageOptions options;
    options.sigma = config.eval.coverage_sigma;
    options.theta_t_rad = config.eval.coverage_theta_t_rad;
    options.min_range_m = config.sensor.min_range_m;
    options.max_range_m = config.sensor.max_range_m;
    return options;
  }

  void BuildCoverage(std::vector<SurfaceVoxel> voxels) {
    const float inv = static_cast<float>(1.0 / voxel_m);
    for (std::size_t i = 0; i < voxels.size(); ++i) {
      voxel_index[geometry::KeyOf(voxels[i].center_world.cast<float>(), inv)] = static_cast<int>(i);
    }
    coverage = std::make_unique<CoverageAccumulator>(std::move(voxels), Options());
  }

  // Flags the voxels the robot's camera could not measure from anywhere it can be (`air`: the room,
  // within reach when restricted; its height band; the sensor's range and dropout angle;
  // observability.h).
  void MarkObservable(std::vector<SurfaceVoxel>* voxels, const std::vector<NormalLines>& lines,
                      const RoomAir& air) const {
    ObservabilityOptions options;
    options.min_range_m = config.sensor.min_range_m;
    options.max_range_m = config.sensor.max_range_m;
    options.max_incidence_deg = config.sensor.grazing_dropout_deg;
    options.own_surface_m = 0.5 * std::sqrt(3.0) * voxel_m;
    options.threads = config.eval.threads;
    if (config.eval.coverage_robot_camera_heights) {
      options.min_camera_z_m = air.floor_top_m() + config.robot.min_camera_height_m;
      options.max_camera_z_m = air.floor_top_m() + config.robot.max_camera_height_m;
    }
    std::vector<Eigen::Vector3d> centers;
    centers.reserve(voxels->size());
    for (const auto& v : *voxels) centers.push_back(v.center_world);
    const render::Raycaster caster(scene.BuildTriangleSoup());
    const std::vector<char> observable = ObservableVoxels(caster, centers, lines, options, &air);
    for (std::size_t i = 0; i < voxels->size(); ++i) (*voxels)[i].observable = observable[i] != 0;
  }

  // Keeps the surface voxels a camera at `seed_world`'s side of the scene could ever see.
  void BuildExposedCoverage(const Eigen::Vector3d& seed_world) {
    std::vector<Eigen::Vector3d> centers;
    centers.reserve(surface_voxels.size());
    for (const auto& v : surface_voxels) centers.push_back(v.center_world);
    CameraHeightBand band;
    if (config.eval.coverage_robot_camera_heights) {
      band.min_height_m = config.robot.min_camera_height_m;
      band.max_height_m = config.robot.max_camera_height_m;
    }
    RoomAir air(scene, voxel_m, seed_world);
    if (config.eval.coverage_robot_reach) {
      air.RestrictToRobotReach(config.robot.base_radius_m, config.robot.height_m, config.robot.max_reach_m);
    }
    const std::vector<char> exposed = air.Exposed(centers, band);
    std::vector<SurfaceVoxel> kept;
    std::vector<NormalLines> kept_lines;
    for (std::size_t i = 0; i < surface_voxels.size(); ++i) {
      if (!exposed[i]) continue;
      kept.push_back(surface_voxels[i]);
      kept_lines.push_back(std::move(surface_normal_lines[i]));
    }
    surface_voxels.clear();
    surface_voxels.shrink_to_fit();
    surface_normal_lines.clear();
    surface_normal_lines.shrink_to_fit();
    MarkObservable(&kept, kept_lines, air);
    if (config.eval.coverage_observable_only) {
      kept.erase(std::remove_if(kept.begin(), kept.end(), [](const SurfaceVoxel& v) { return !v.observable; }),
                 kept.end());
    }
    BuildCoverage(std::move(kept));
  }

  // Recognition counts per room, from the run's outputs (with their rooms) and their matching.
  std::vector<RoomMetrics> PerRoom(const std::vector<OutputObject>& outputs, const std::vector<int>& output_room,
                                   const RecognitionResult& rec) const {
    std::vector<RoomMetrics> per_room(rooms.rooms().size());
    for (std::size_t r = 0; r < per_room.size(); ++r) {
      per_room[r].room = rooms.rooms()[r].id;
      per_room[r].area_m2 = rooms.rooms()[r].area_m2;
      per_room[r].center_m = rooms.rooms()[r].center_m;
    }
    const std::set<int> matched(rec.matched_instances.begin(), rec.matched_instances.end());
    for (const GroundTruthInstance& g : truth) {
      const bool scored = IsScoredCategory(g.category) &&
                          std::find(database_categories.begin(), database_categories.end(), g.category) !=
                              database_categories.end();
      const auto it = room_of_instance.find(g.instance_id);
      if (!scored || it == room_of_instance.end() || it->second < 0) continue;
      RecognitionCounts& k = per_room[static_cast<std::size_t>(it->second)].counts;
      ++k.ground_truth;
    }
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      if (output_room[o] < 0) continue;
      RecognitionCounts& k = per_room[static_cast<std::size_t>(output_room[o])].counts;
      ++k.outputs;
      if (rec.output_is_true_positive[o]) ++k.true_positives;
    }
    const auto with_objects = std::count_if(per_room.begin(), per_room.end(),
                                            [](const RoomMetrics& r) { return r.counts.ground_truth > 0; });
    if (with_objects < 2) return {};
    // Rooms with neither ground truth nor outputs (the floor around a house) are left out.
    per_room.erase(std::remove_if(per_room.begin(), per_room.end(),
                                  [](const RoomMetrics& r) { return r.counts.ground_truth == 0 && r.counts.outputs == 0; }),
                   per_room.end());
    return per_room;
  }

  Impl(const world::Scene& s, const scanning::SystemConfig& c, std::vector<world::Category> cats)
      : scene(s), config(c), database_categories(std::move(cats)), voxel_m(c.eval.coverage_voxel_size_m) {
    surface_voxels = SurfaceVoxelsOf(scene, voxel_m, c.eval.coverage_exposed_only ? &surface_normal_lines : nullptr);
    if (!c.eval.coverage_exposed_only) BuildCoverage(std::move(surface_voxels));
    for (const auto& o : scene.objects()) {
      if (o.IsStructural()) {
        structural.push_back(o.instance_id);
        continue;
      }
      GroundTruthInstance g;
      g.instance_id = o.instance_id;
      g.category = o.category;
      g.on_floor = scene.ObjectBounds(o).min_m.z() < kOnFloorMaxZ_m;
      truth.push_back(g);
    }
    rooms = RoomPartition::FromScene(scene);
    for (const auto& o : scene.objects()) {
      if (o.IsStructural()) continue;
      const Eigen::Vector3d c = scene.ObjectBounds(o).Center();
      room_of_instance[o.instance_id] = rooms.RoomAt(c.x(), c.y());
    }
  }
};

RunEvaluator::RunEvaluator(const world::Scene& scene, const scanning::SystemConfig& config,
                           std::vector<world::Category> database_categories)
    : impl_(std::make_unique<Impl>(scene, config, std::move(database_categories))) {}

RunEvaluator::~RunEvaluator() = default;

int RunEvaluator::num_surface_voxels() const {
  return static_cast<int>(impl_->coverage ? impl_->coverage->voxels().size() : impl_->surface_voxels.size());
}

void RunEvaluator::ObserveFrame(const platform::DepthFrame& frame, const mapping::FrameAssociation& association) {
  Impl& m = *impl_;
  m.votes.Observe(frame, association);
  if (!m.coverage) m.BuildExposedCoverage(frame.T_world_camera.translation());
  const float inv = static_cast<float>(1.0 / m.voxel_m);
  const auto& voxels = m.coverage->voxels();
  std::vector<char> seen(voxels.size(), 0);
  std::vector<int> seen_list;
  const int stride = 2;  // a 5 cm voxel covers several pixels at every valid range
  for (int v = 0; v < frame.height(); v += stride) {
    for (int u = 0; u < frame.width(); u += stride) {
      const std::size_t px = static_cast<std::size_t>(v) * frame.width() + u;
      if (frame.depth_m[px] <= 0.f) continue;
      const int instance = frame.gt_instance.empty() ? 0 : frame.gt_instance[px];
      if (instance <= 0) continue;
      const Eigen::Vector3f p = frame.PointWorld(u, v).cast<float>();
      // The voxel of the (noisy) point, or the nearest neighbouring voxel of the same instance.
      const geometry::VoxelKey k = geometry::KeyOf(p, inv);
      // The voxel holding p has the nearest centre of all: when it is of the instance, it is the one;
      // otherwise the nearest of its neighbours that is.
      int best = -1;
      auto own = m.voxel_index.find(k);
      if (own != m.voxel_index.end() && voxels[own->second].instance == instance) {
        best = own->second;
      } else {
        float best_d = 1e9f;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              auto it = m.voxel_index.find(geometry::VoxelKey{k.x + dx, k.y + dy, k.z + dz});
              if (it == m.voxel_index.end() || voxels[it->second].instance != instance) continue;
              const float d = (voxels[it->second].center_world.cast<float>() - p).squaredNorm();
              if (d < best_d) {
                best_d = d;
                best = it->second;
              }
            }
      }
      if (best >= 0 && !seen[best]) {
        seen[best] = 1;
        seen_list.push_back(best);
      }
    }
  }
  std::sort(seen_list.begin(), seen_list.end());
  m.coverage->AddView(frame.T_world_camera.translation(), seen_list);
  m.seen_per_view.push_back(std::move(seen_list));
  m.camera_per_view.push_back(frame.T_world_camera.translation());
}

void RunEvaluator::ObserveAnalysis(const scanning::Scanner& scanner) {
  Impl& m = *impl_;
  std::vector<int> object_id;
  scanner.AnalysisElementObjects(&object_id);
  const double ri = m.RandIndexOf(scanner.surface_map(), object_id);
  m.rand_index_per_view.emplace_back(scanner.analysis_views(), ri);
}

void RunEvaluator::AssignGroundTruthInstances(const scanning::Scanner& scanner, scanning::RunRecord* record) const {
  const Impl& m = *impl_;
  const mapping::SurfaceMap& map = scanner.surface_map();
  std::map<std::int32_t, int> object_of_label;
  for (std::size_t i = 0; i < record->objects.size(); ++i) {
    for (auto l : record->objects[i].labels) object_of_label[l] = static_cast<int>(i);
  }
  // Over the non-structural surface: an instance's total counts its elements in no object too, so a
  // share below 1 says the object holds only a piece of what the robot reconstructed of it.
  std::vector<int> element_object, element_instance;
  for (std::size_t e = 0; e < map.size(); ++e) {
    if (map.structure(e) != mapping::Structure::kNone) continue;
    auto it = object_of_label.find(map.label(e));
    element_object.push_back(it == object_of_label.end() ? -1 : it->second);
    element_instance.push_back(m.votes.Instance(e));
  }
  const std::vector<ObjectInstanceShare> shares =
      ObjectInstanceShares(element_object, element_instance, static_cast<int>(record->objects.size()));
  for (std::size_t i = 0; i < record->objects.size(); ++i) {
    scanning::ObjectRecord& o = record->objects[i];
    o.gt_instance = shares[i].instance > 0 ? shares[i].instance : -1;
    o.gt_instance_share = o.gt_instance > 0 ? shares[i].share : 0.0;
  }
}

RunMetrics RunEvaluator::Evaluate(const scanning::Scanner& scanner, const scanning::RunRecord& record) const {
  const Impl& m = *impl_;
  // With no frame seen, V_S was never narrowed to the exposed voxels, and none is visible.
  const CoverageAccumulator unseen(m.coverage ? std::vector<SurfaceVoxel>{} : m.surface_voxels, m.Options());
  const CoverageAccumulator& coverage = m.coverage ? *m.coverage : unseen;
  RunMetrics out;
  const std::vector<GroundTruthInstance>& truth = m.truth;
  const std::vector<std::int32_t>& structural = m.structural;
  // Output objects: complete ones, and incomplete ones recognised with enough objectness, of a scored
  // category (recognised as `other` is no output).
  std::vector<OutputObject> outputs;
  std::vector<int> output_room;
  for (const auto& o : record.objects) {
    if (!o.category || !IsScoredCategory(*o.category)) continue;
    if (!o.complete && o.objectness < m.config.eval.recognized_min_objectness) continue;
    outputs.push_back({*o.category, o.gt_instance > 0 ? o.gt_instance : world::kNoInstance, o.gt_instance_share});
    auto r = m.room_of_instance.find(o.gt_instance);
    output_room.push_back(r != m.room_of_instance.end()
                              ? r->second
                              : m.rooms.RoomAt(o.T_world_model.translation().x(), o.T_world_model.translation().y()));
  }
  const RecognitionResult rec = MatchRecognitions(truth, outputs, m.database_categories);
  out.rooms = m.PerRoom(outputs, output_room, rec);
  {
    // The rooms reachable from where the robot started, and recognition over them.
    RoomReachability reach;
    if (!record.trajectory.empty()) {
      RoomReachabilityOptions options;
      options.robot_radius_m = m.config.robot.base_radius_m;
      options.robot_height_m = m.config.robot.height_m;
      options.navigation = m.config.navigation;
      const Eigen::Vector2d start(record.trajectory.front().x_m, record.trajectory.front().y_m);
      reach = ReachableRooms(m.scene, m.rooms, start, options);
    }
    const auto room_of = [&](int instance) {
      const auto it = m.room_of_instance.find(instance);
      return it == m.room_of_instance.end() ? -1 : it->second;
    };
    // Objects in walls (windows, doors) may have their centre on the far side: an object counts as
    // out of reach only when no reachable room is within half a metre of its centre.
    std::set<int> out_of_reach;
    for (const auto& o : m.scene.objects()) {
      if (o.IsStructural() || reach.Reachable(room_of(o.instance_id))) continue;
      const Eigen::Vector3d c = m.scene.ObjectBounds(o).Center();
      const std::vector<int> near = m.rooms.RoomsWithin(c.x(), c.y(), 0.5);
      if (std::none_of(near.begin(), near.end(), [&](int r) { return reach.Reachable(r); })) {
        out_of_reach.insert(o.instance_id);
      }
    }
    for (std::size_t r = 0; r < reach.reachable.size(); ++r) {
      if (reach.reachable[r]) continue;
      UnreachableRoom u;
      u.room = m.rooms.rooms()[r].id;
      u.area_m2 = m.rooms.rooms()[r].area_m2;
      u.center_m = m.rooms.rooms()[r].center_m;
      for (const auto& o : m.scene.objects()) {
        if (out_of_reach.count(o.instance_id) && room_of(o.instance_id) == static_cast<int>(r)) {
          u.objects.push_back({o.instance_id, o.name, o.category});
        }
      }
      out.unreachable_rooms.push_back(std::move(u));
    }
    std::vector<GroundTruthInstance> reachable_truth;
    for (const GroundTruthInstance& g : truth) {
      if (!out_of_reach.count(g.instance_id)) reachable_truth.push_back(g);
    }
    std::vector<OutputObject> reachable_outputs;
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      // On a ground-truth object: as that object; on background: as the room of its model.
      const int instance = outputs[o].majority_instance;
      const bool out = m.room_of_instance.count(instance) ? out_of_reach.count(instance) > 0
                                                          : !reach.Reachable(output_room[o]);
      if (!out) reachable_outputs.push_back(outputs[o]);
    }
    out.reachable = MatchRecognitions(reachable_truth, reachable_outputs, m.database_categories).all;
    // Reachable objects the robot's map holds nothing of (their surface seen within range counts too,
    // below, with the coverage).
    std::set<int> in_map;
    for (const std::int32_t i : m.votes.Instances(scanner.surface_map().size())) in_map.insert(i);
    for (const auto& o : m.scene.objects()) {
      if (o.IsStructural() || out_of_reach.count(o.instance_id) || in_map.count(o.instance_id)) continue;
      out.never_seen.push_back({o.instance_id, o.name, o.category});
    }
  }
  out.recall = rec.all.Recall();
  out.precision = rec.all.Precision();
  out.recall_floor = rec.floor.Recall();
  out.precision_floor = rec.floor.Precision();
  out.ground_truth_objects = rec.all.ground_truth;
  out.ground_truth_floor_objects = rec.floor.ground_truth;
  out.output_objects = rec.all.outputs;
  out.true_positives = rec.all.true_positives;
  out.per_category = rec.per_category;

  // Segmentation quality over the reconstructed non-structural points.
  const mapping::SurfaceMap& map = scanner.surface_map();
  std::vector<int> object_id, category_id;
  scanner.ElementObjects(&object_id, &category_id);
  out.rand_index = m.RandIndexOf(map, object_id);
  const auto preseg = segmentation::EvaluatePresegmentation(map, m.votes.Instances(map.size()), structural);
  out.rand_index_preseg = preseg.rand_index_preseg;
  out.preseg_purity = preseg.preseg_purity;

  // Coverage with δ_detect on matched instances, and after each view.
  const std::vector<int>& detected = rec.matched_instances;
  const CoverageResult cov = coverage.Result(detected);
  out.coverage_rate = cov.rate;
  out.coverage_quality = cov.quality;
  out.coverage_visible_rate = cov.num_voxels > 0 ? static_cast<double>(cov.num_visible) / cov.num_voxels : 0.0;
  std::vector<int> reported;
  for (const auto& o : record.objects) {
    if (o.gt_instance > 0) reported.push_back(o.gt_instance);
  }
  out.coverage_detected_rate = coverage.Result(reported).rate;
  const std::set<int> reported_set(reported.begin(), reported.end());
  {
    std::unordered_map<int, InstanceCoverage> seen_of;
    for (const auto& c : coverage.PerInstance()) seen_of[c.instance] = c;
    const std::set<int> matched(detected.begin(), detected.end());
    std::unordered_map<int, world::Category> category_of;
    for (const auto& g : truth) {
      category_of[g.instance_id] = g.category;
      InstanceOutcome o;
      o.instance = g.instance_id;
      o.category = g.category;
      o.in_database = std::find(m.database_categories.begin(), m.database_categories.end(), g.category) !=
                      m.database_categories.end();
      auto it = seen_of.find(g.instance_id);
      if (it != seen_of.end()) {
        o.surface_voxels = it->second.num_voxels;
        o.visible_voxels = it->second.num_visible;
      }
      o.matched = matched.count(g.instance_id) > 0;
      out.instances.push_back(o);
    }
    const auto& voxels = coverage.voxels();
    const auto& quality = coverage.best_quality();
    out.coverage_voxels.reserve(voxels.size());
    for (std::size_t i = 0; i < voxels.size(); ++i) {
      CoverageVoxelOutcome v;
      v.center_world = voxels[i].center_world.cast<float>();
      v.normal_world = voxels[i].normal_world.cast<float>();
      v.instance = voxels[i].instance;
      auto c = category_of.find(v.instance);
      if (c != category_of.end()) v.category = c->second;
      v.visible = quality[i] >= 0.0;
      v.detected = matched.count(v.instance) > 0;
      v.reported = reported_set.count(v.instance) > 0;
      v.observable = voxels[i].observable;
      out.coverage_voxels.push_back(v);
    }
  }
  CoverageAccumulator curve(coverage.voxels(), m.Options());
  for (std::size_t i = 0; i < m.seen_per_view.size(); ++i) {
    curve.AddView(m.camera_per_view[i], m.seen_per_view[i]);
    const CoverageResult c = curve.Result(detected);
    out.coverage_per_view.emplace_back(c.rate, c.quality);
  }
  {
    std::set<int> seen_in_range;
    for (const InstanceOutcome& o : out.instances) {
      if (o.visible_voxels > 0) seen_in_range.insert(o.instance);
    }
    out.never_seen.erase(std::remove_if(out.never_seen.begin(), out.never_seen.end(),
                                        [&](const ObjectRef& o) { return seen_in_range.count(o.instance) > 0; }),
                         out.never_seen.end());
  }
  out.rand_index_per_view = m.rand_index_per_view;
  out.travel_m = record.travel_m;
  out.views = record.views;
  out.nbo_count = record.nbo_count;
  out.coverage_views = record.coverage_views;
  out.nbv_per_object = record.NbvPerObject();
  return out;
}

}  // namespace objscan::eval
