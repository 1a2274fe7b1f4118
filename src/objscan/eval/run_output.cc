#include "objscan/eval/run_output.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"
#include "objscan/io/canvas.h"
#include "objscan/io/category_labels.h"
#include "objscan/io/ply.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/recognition/database_builder.h"

namespace objscan::eval {
namespace {

using Json = nlohmann::ordered_json;

Json PoseJson(const geometry::Pose3& T) {
  double yaw = 0, pitch = 0;
  geometry::YawPitchOfCamera(T, &yaw, &pitch);
  const Eigen::Quaterniond q(T.linear());
  return Json{{"xyz", {T.translation().x(), T.translation().y(), T.translation().z()}},
              {"quat_wxyz", {q.w(), q.x(), q.y(), q.z()}},
              {"yaw_deg", geometry::RadToDeg(yaw)},
              {"pitch_deg", geometry::RadToDeg(pitch)}};
}

Json ModelPoseJson(const geometry::Pose3& T) {
  const Eigen::Vector3d x = T.linear().col(0);
  return Json{{"xyz", {T.translation().x(), T.translation().y(), T.translation().z()}},
              {"yaw_deg", geometry::RadToDeg(std::atan2(x.y(), x.x()))}};
}

}  // namespace

std::string TrajectoryTum(const scanning::RunRecord& record) {
  std::ostringstream out;
  out << "# objscan views: T_world_camera, camera frame x right y down z forward, time in simulated seconds\n"
      << "# timestamp tx ty tz qx qy qz qw\n";
  char line[256];
  for (const auto& t : record.trajectory) {
    if (!t.view) continue;
    Eigen::Quaterniond q(t.T_world_camera.linear());
    q.normalize();
    // q and -q are the same rotation: qw >= 0 makes the file the same for the same run.
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d p = t.T_world_camera.translation();
    std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t.time_s, p.x(), p.y(), p.z(), q.x(),
                  q.y(), q.z(), q.w());
    out << line;
  }
  return out.str();
}

std::string RunJson(const RunOutputInputs& in) {
  const scanning::RunRecord& r = *in.record;
  Json j;
  j["scene"] = in.scene_spec;
  j["seed"] = r.seed;
  j["database"] = in.database_path;
  j["config"] = Json::parse(scanning::ToJson(*in.config));
  j["terminated"] = scanning::TerminationName(r.terminated);
  j["explored_area_m2"] = std::round(r.explored_area_m2 * 100.0) / 100.0;
  j["step_budget"] = r.step_budget;
  {
    // What the robot's own map left out of reach at the end (run_record.h).
    Json frontiers = Json::array();
    for (const auto& f : r.unreachable.frontiers) {
      frontiers.push_back(Json{{"xy_m", {std::round(f.x_m * 100.0) / 100.0, std::round(f.y_m * 100.0) / 100.0}},
                               {"cells", f.cells},
                               {"area_m2", std::round(f.area_m2 * 1e4) / 1e4}});
    }
    j["unreachable"] = Json{{"frontier_area_m2", std::round(r.unreachable.frontier_area_m2 * 1e4) / 1e4},
                            {"frontiers", frontiers},
                            {"objects", r.unreachable.objects}};
  }
  Json steps = Json::array();
  for (const auto& s : r.steps) {
    Json step{{"index", s.index},
              {"action", s.action},
              {"look_around", s.look_around},
              {"coverage_view", s.coverage_view},
              {"ooi", s.ooi},
              {"views", s.views},
              {"pose", PoseJson(s.T_world_camera)},
              {"travel_m", s.travel_m},
              {"components", s.num_components},
              {"objects", s.num_objects},
              {"queries", Json{{"component", s.component_queries}, {"pair", s.pair_queries}, {"group", s.group_queries}}}};
    const scanning::StageTimes& t = s.timing_ms;
    step["timing_ms"] = Json{{"sense", t.sense}, {"fuse", t.fuse}, {"segment", t.segment},
                             {"recognize", t.recognize}, {"nbo", t.nbo}, {"nbv", t.nbv},
                             {"navigate_sim", t.navigate_sim}, {"wall", s.wall_ms}};
    if (!s.notes.empty()) step["notes"] = s.notes;
    if (!s.nbv_candidates.empty()) {
      Json cands = Json::array();
      for (const auto& c : s.nbv_candidates) {
        cands.push_back(Json{{"pose", PoseJson(c.T_world_camera)}, {"validity", c.validity}, {"gain", c.gain}});
      }
      step["nbv_candidates"] = cands;
    }
    steps.push_back(step);
  }
  j["steps"] = steps;
  Json walls = Json::array();
  for (const auto& w : r.structure.walls) {
    walls.push_back(Json{{"normal_xy", {w.normal_x, w.normal_y}},
                         {"offset_m", w.offset_m},
                         {"span_m", {w.span_min_m, w.span_max_m}},
                         {"z_m", {w.z_min_m, w.z_max_m}},
                         {"area_m2", w.area_m2}});
  }
  j["structure"] = Json{{"floor_height_m", r.structure.floor_height_m ? Json(*r.structure.floor_height_m) : Json(nullptr)},
                        {"walls", walls}};
  Json objects = Json::array();
  for (const auto& o : r.objects) {
    Json obj{{"id", o.id},
             {"category", o.category ? Json(world::CategoryName(*o.category)) : Json(nullptr)},
             {"model", o.model},
             {"objectness", o.objectness},
             {"complete", o.complete},
             {"given_up", o.given_up},
             {"pose", ModelPoseJson(o.T_world_model)},
             {"points", o.points}};
    if (o.wall_opening_share) obj["wall_opening_share"] = *o.wall_opening_share;
    if (!o.label_changes.empty()) {
      const auto name = [](const std::optional<world::Category>& c) {
        return c ? Json(world::CategoryName(*c)) : Json(nullptr);
      };
      Json changes = Json::array();
      for (const scanning::LabelChange& c : o.label_changes) {
        Json change{{"rule", c.rule}, {"action", c.action}, {"from", name(c.from)}, {"to", name(c.to)}};
        if (!c.model.empty()) change["model"] = c.model;
        if (c.joined_id >= 0) change["joined_id"] = c.joined_id;
        changes.push_back(change);
      }
      obj["label_changes"] = changes;
    }
    obj["height_m"] = o.height_m;
    obj["footprint_diagonal_m"] = o.footprint_diagonal_m;
    if (!o.alternatives.empty()) {
      Json alternatives = Json::array();
      for (const auto& a : o.alternatives) {
        alternatives.push_back(
            Json{{"category", world::CategoryName(a.category)}, {"model", a.model}, {"objectness", a.objectness}});
      }
      obj["alternatives"] = alternatives;
    }
    if (o.gt_instance > 0) {
      obj["gt_instance"] = o.gt_instance;
      obj["gt_instance_share"] = o.gt_instance_share;
    }
    objects.push_back(obj);
  }
  j["objects"] = objects;
  if (in.metrics) {
    const RunMetrics& m = *in.metrics;
    Json metrics{{"recall", m.recall},
                 {"precision", m.precision},
                 {"recall_floor", m.recall_floor},
                 {"precision_floor", m.precision_floor},
                 {"ground_truth_objects", m.ground_truth_objects},
                 {"ground_truth_floor_objects", m.ground_truth_floor_objects},
                 {"output_objects", m.output_objects},
                 {"true_positives", m.true_positives},
                 {"rand_index", m.rand_index},
                 {"rand_index_preseg", m.rand_index_preseg},
                 {"preseg_purity", m.preseg_purity},
                 {"coverage_rate", m.coverage_rate},
                 {"coverage_quality", m.coverage_quality},
                 {"coverage_visible_rate", m.coverage_visible_rate},
                 {"coverage_detected_rate", m.coverage_detected_rate},
                 {"travel_m", m.travel_m},
                 {"views", m.views},
                 {"nbo_count", m.nbo_count},
                 {"nbv_per_object", m.nbv_per_object},
                 {"coverage_views", m.coverage_views}};
    Json per_category = Json::object();
    for (int c = 0; c < world::kNumObjectCategories; ++c) {
      const auto& k = m.per_category[c];
      if (k.ground_truth == 0 && k.outputs == 0) continue;
      per_category[world::CategoryName(static_cast<world::Category>(c))] =
          Json{{"ground_truth", k.ground_truth}, {"outputs", k.outputs}, {"true_positives", k.true_positives}};
    }
    metrics["per_category"] = per_category;
    if (!m.rooms.empty()) {
      Json rooms = Json::array();
      for (const RoomMetrics& r : m.rooms) {
        rooms.push_back(Json{{"room", r.room},
                             {"area_m2", r.area_m2},
                             {"center_m", {r.center_m.x(), r.center_m.y()}},
                             {"ground_truth", r.counts.ground_truth},
                             {"outputs", r.counts.outputs},
                             {"true_positives", r.counts.true_positives},
                             {"recall", r.counts.Recall()},
                             {"precision", r.counts.Precision()}});
      }
      metrics["rooms"] = rooms;
    }
    // Over the rooms the robot could reach from its start (eval/reachability.h), beside the totals.
    metrics["reachable"] = Json{{"ground_truth_objects", m.reachable.ground_truth},
                                {"output_objects", m.reachable.outputs},
                                {"true_positives", m.reachable.true_positives},
                                {"recall", m.reachable.Recall()},
                                {"precision", m.reachable.Precision()}};
    Json unreachable_rooms = Json::array();
    for (const UnreachableRoom& u : m.unreachable_rooms) {
      Json objects = Json::array();
      for (const auto& o : u.objects) {
        objects.push_back(Json{{"instance", o.instance}, {"name", o.name}, {"category", world::CategoryName(o.category)}});
      }
      unreachable_rooms.push_back(Json{{"room", u.room},
                                       {"area_m2", u.area_m2},
                                       {"center_m", {u.center_m.x(), u.center_m.y()}},
                                       {"objects", objects}});
    }
    metrics["unreachable_rooms"] = unreachable_rooms;
    Json never_seen = Json::array();
    for (const ObjectRef& o : m.never_seen) {
      never_seen.push_back(Json{{"instance", o.instance}, {"name", o.name}, {"category", world::CategoryName(o.category)}});
    }
    metrics["never_seen"] = never_seen;
    Json instances = Json::array();
    for (const auto& o : m.instances) {
      instances.push_back(Json{{"instance", o.instance},
                               {"category", world::CategoryName(o.category)},
                               {"in_database", o.in_database},
                               {"surface_voxels", o.surface_voxels},
                               {"visible_voxels", o.visible_voxels},
                               {"matched", o.matched}});
    }
    metrics["instances"] = instances;
    Json curve = Json::array();
    for (const auto& [rate, quality] : m.coverage_per_view) curve.push_back({rate, quality});
    metrics["coverage_per_view"] = curve;
    Json ri_curve = Json::array();
    for (const auto& [views, ri] : m.rand_index_per_view) ri_curve.push_back({views, ri});
    metrics["rand_index_per_view"] = ri_curve;
    j["metrics"] = metrics;
  }
  j["timing_s"] = Json{{"total", r.timing_s.total},         {"sense", r.timing_s.sense},
                       {"fuse", r.timing_s.fuse},           {"segment", r.timing_s.segment},
                       {"recognize", r.timing_s.recognize}, {"nbo", r.timing_s.nbo},
                       {"nbv", r.timing_s.nbv},             {"navigate_sim", r.timing_s.navigate_sim}};
  if (in.peak_rss_mb > 0.0) j["peak_rss_mb"] = std::round(in.peak_rss_mb * 10.0) / 10.0;
  if (in.cpu_s >= 0.0) j["cpu_s"] = std::round(in.cpu_s * 100.0) / 100.0;
  return j.dump(2) + "\n";
}

void WriteRunTopView(const std::string& path, const RunOutputInputs& in) {
  const mapping::SurfaceMap& map = in.scanner->surface_map();
  std::vector<int> object_id, category_id;
  in.scanner->ElementObjects(&object_id, &category_id);
  geometry::Aabb3 box = map.Bounds();
  for (const auto& t : in.record->trajectory) box.Extend(t.T_world_camera.translation());
  if (box.Empty()) box.Extend(Eigen::Vector3d::Zero());
  const double mpp = 0.01;
  const io::WorldToPixel to_px(box, mpp, 40);
  const int legend_w = 230;
  io::Canvas canvas(to_px.width_px() + legend_w, std::max(to_px.height_px(), 420), {255, 255, 255});
  // Elements drawn from low to high so tops cover what is below.
  std::vector<std::size_t> order(map.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return map.position(a).z() < map.position(b).z(); });
  std::set<int> categories_present;
  const int dot = std::max(1, static_cast<int>(std::ceil(map.voxel_size_m() / mpp)));
  for (std::size_t e : order) {
    const int cat = category_id[e];
    // Seen from above the ceiling would hide the rooms under it (as in objscan scene --topview).
    if (cat == world::CategoryId(world::Category::kCeiling)) continue;
    const Eigen::Vector2d p = to_px.ToPixel(map.position(e).cast<double>());
    // The palette of the PLY files (world::LabelColor); objects shaded by height.
    const auto c = world::LabelColor(cat);
    io::Rgb color{c[0], c[1], c[2]};
    if (cat >= 0 && !world::IsStructural(static_cast<world::Category>(cat))) {
      color = io::ShadeRgb(color, 0.75 + 0.25 * std::min(1.0, map.position(e).z() / 1.5));
      categories_present.insert(cat);
    }
    canvas.FillRect(static_cast<int>(p.x()), static_cast<int>(p.y()), static_cast<int>(p.x()) + dot,
                    static_cast<int>(p.y()) + dot, color);
  }
  // Robot path and views.
  std::vector<Eigen::Vector2d> path_px;
  for (const auto& t : in.record->trajectory) path_px.push_back(to_px.ToPixel(t.x_m, t.y_m));
  canvas.DrawPolyline(path_px, {220, 30, 30}, 2.0);
  for (const auto& t : in.record->trajectory) {
    if (!t.view) continue;
    const Eigen::Vector3d c = t.T_world_camera.translation();
    Eigen::Vector3d f = t.T_world_camera.linear().col(2);
    f.z() = 0.0;
    if (f.norm() < 1e-6) f = Eigen::Vector3d::UnitX();
    f.normalize();
    canvas.DrawArrow(to_px.ToPixel(c), to_px.ToPixel(c + 0.35 * f), {20, 20, 160}, 1.5, 7.0);
    canvas.FillCircle(to_px.ToPixel(c), 3.0, {255, 255, 255});
    canvas.DrawCircle(to_px.ToPixel(c), 3.0, {20, 20, 160}, 1.0);
  }
  if (!in.record->trajectory.empty()) {
    canvas.FillCircle(path_px.front(), 6.0, {220, 30, 30});
  }
  // Legend.
  int y = 12;
  const int x0 = to_px.width_px() + 10;
  canvas.DrawText(x0, y, "objscan run", {0, 0, 0}, 2);
  y += 24;
  std::ostringstream summary;
  summary << in.record->views << " views, " << std::fixed << std::setprecision(1) << in.record->travel_m << " m";
  canvas.DrawText(x0, y, summary.str(), {0, 0, 0}, 1);
  y += 14;
  if (in.metrics) {
    std::ostringstream m;
    m << std::fixed << std::setprecision(2) << "recall " << in.metrics->recall << " prec " << in.metrics->precision;
    canvas.DrawText(x0, y, m.str(), {0, 0, 0}, 1);
    y += 14;
  }
  y += 6;
  for (int cat : categories_present) {
    const auto c = world::CategoryColor(static_cast<world::Category>(cat));
    canvas.FillRect(x0, y, x0 + 14, y + 14, {c[0], c[1], c[2]});
    canvas.DrawText(x0 + 20, y + 3, world::CategoryName(static_cast<world::Category>(cat)), {0, 0, 0}, 1);
    y += 18;
  }
  canvas.FillRect(x0, y, x0 + 14, y + 14,
                  {world::kUnrecognizedColor[0], world::kUnrecognizedColor[1], world::kUnrecognizedColor[2]});
  canvas.DrawText(x0 + 20, y + 3, "unrecognized", {0, 0, 0}, 1);
  y += 18;
  canvas.DrawLine({double(x0), y + 8.0}, {x0 + 14.0, y + 8.0}, {220, 30, 30}, 2.0);
  canvas.DrawText(x0 + 20, y + 3, "robot path", {0, 0, 0}, 1);
  y += 18;
  canvas.DrawArrow({double(x0), y + 8.0}, {x0 + 14.0, y + 8.0}, {20, 20, 160}, 1.5, 6.0);
  canvas.DrawText(x0 + 20, y + 3, "view", {0, 0, 0}, 1);
  canvas.SavePng(path);
}

io::PlyData PlacedModelsPly(const scanning::RunRecord& record, const recognition::ModelDatabase& database,
                            const std::function<void(const std::string& message)>& warn) {
  io::PlyData models;
  std::vector<std::int32_t> model_object, model_category;
  std::set<int> models_without_mesh;
  for (const auto& o : record.objects) {
    if (!o.complete || o.model_index < 0) continue;
    const auto& model = database.models()[o.model_index];
    geometry::TriangleMesh mesh;
    try {
      // The mesh stored in the database, else the one of the model's source.
      mesh = recognition::LoadModelSourceMesh(model);
    } catch (const InputError& e) {
      // No mesh anywhere (a database built from scans whose source is gone): the database scan
      // points stand in, and the caller is told once per model.
      for (const auto& p : database.entries()[model.full_entry].points) mesh.vertices.push_back(p);
      if (models_without_mesh.insert(o.model_index).second && warn) {
        warn(std::string(e.what()) + " (models.ply has its scan points instead)");
      }
    }
    const int offset = static_cast<int>(models.points.size());
    for (const auto& v : mesh.vertices) {
      models.points.push_back((o.T_world_model * v.cast<double>()).cast<float>());
      model_object.push_back(o.id);
      model_category.push_back(o.category ? world::CategoryId(*o.category) : -1);
    }
    for (const auto& t : mesh.triangles) models.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  models.int_properties.emplace_back("object_id", model_object);
  models.int_properties.emplace_back("category_id", model_category);
  io::AddCategoryLabels(model_category, &model_object, /*colour_by_category=*/true, &models);
  return models;
}

namespace {

// scene.ply: the reconstructed surface with object and category ids, coloured by category, with
// the `label` and `instance` fields viewers and other tools look for (io::AddCategoryLabels' fields).
// Written an element at a time: a house's map has millions of elements, which took about 190 MB
// more as a PlyData at the end of the run.
void WriteScenePly(const std::string& path, const scanning::Scanner& scanner) {
  const mapping::SurfaceMap& map = scanner.surface_map();
  std::vector<int> object_id, category_id;
  scanner.ElementObjects(&object_id, &category_id);
  if (object_id.size() != map.size() || category_id.size() != map.size()) {
    throw InputError(path + ": " + std::to_string(object_id.size()) + " object ids for " + std::to_string(map.size()) +
                     " map elements");
  }
  io::PlyLayout layout;
  layout.num_vertices = map.size();
  layout.normals = true;
  layout.colors = true;
  layout.int_properties = {"object_id", "category_id", "label", "instance"};
  layout.comments = io::CategoryPlyComments();
  io::PlyStreamWriter writer(path, std::move(layout));
  for (std::size_t e = 0; e < map.size(); ++e) {
    const auto c = world::LabelColor(category_id[e]);
    const std::int32_t ints[4] = {object_id[e], category_id[e], category_id[e], object_id[e]};
    writer.AddVertex(map.position(e), map.normal(e), {c[0], c[1], c[2]}, ints);
  }
  writer.Commit();
}

}  // namespace

void WriteRunOutputs(const std::string& out_dir, const RunOutputInputs& in) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw InputError(out_dir + ": cannot create output folder: " + ec.message());
  const fs::path dir(out_dir);
  // run.json marks a finished run (objscan bench resumes on it): the old one goes before any file of
  // this run replaces its neighbours.
  io::RemoveStaleTempFiles(out_dir);
  fs::remove(dir / "run.json", ec);
  if (ec) throw InputError((dir / "run.json").string() + ": cannot replace: " + ec.message());

  WriteScenePly((dir / "scene.ply").string(), *in.scanner);

  // models.ply: the database models that replaced complete objects, placed.
  const io::PlyData models = PlacedModelsPly(*in.record, *in.database, in.warn);
  io::WritePly((dir / "models.ply").string(), models);

  // coverage.ply (ground truth known): every voxel of V_S, coloured green when it counts for the
  // coverage rate, orange when seen on an object that was not recognised, red when never seen
  // within range, so what the robot missed can be looked at.
  if (in.metrics) {
    io::PlyData coverage;
    std::vector<std::int32_t> instance, category, visible, detected, reported, observable;
    for (const auto& v : in.metrics->coverage_voxels) {
      coverage.points.push_back(v.center_world);
      coverage.normals.push_back(v.normal_world);
      coverage.colors.push_back(!v.visible   ? std::array<std::uint8_t, 3>{220, 40, 40}
                                : v.detected ? std::array<std::uint8_t, 3>{40, 180, 60}
                                             : std::array<std::uint8_t, 3>{240, 150, 30});
      instance.push_back(v.instance);
      category.push_back(world::CategoryId(v.category));
      visible.push_back(v.visible ? 1 : 0);
      detected.push_back(v.detected ? 1 : 0);
      reported.push_back(v.reported ? 1 : 0);
      observable.push_back(v.observable ? 1 : 0);
    }
    coverage.int_properties.emplace_back("instance", instance);
    coverage.int_properties.emplace_back("category_id", category);
    coverage.int_properties.emplace_back("visible", visible);
    coverage.int_properties.emplace_back("detected", detected);
    coverage.int_properties.emplace_back("reported", reported);
    coverage.int_properties.emplace_back("observable", observable);
    // Coloured by coverage; its `instance` is the ground-truth one, so only `label` is added.
    io::AddCategoryLabels(category, nullptr, /*colour_by_category=*/false, &coverage);
    io::WritePly((dir / "coverage.ply").string(), coverage);
  }

  // trajectory.csv
  std::ostringstream csv;
  csv << "step,time_s,base_x_m,base_y_m,base_theta_deg,camera_x_m,camera_y_m,camera_z_m,camera_yaw_deg,camera_pitch_deg,view\n";
  csv << std::fixed << std::setprecision(4);
  for (const auto& t : in.record->trajectory) {
    double yaw = 0, pitch = 0;
    geometry::YawPitchOfCamera(t.T_world_camera, &yaw, &pitch);
    csv << t.step << ',' << t.time_s << ',' << t.x_m << ',' << t.y_m << ',' << geometry::RadToDeg(t.theta_rad) << ','
        << t.T_world_camera.translation().x() << ',' << t.T_world_camera.translation().y() << ','
        << t.T_world_camera.translation().z() << ',' << geometry::RadToDeg(yaw) << ',' << geometry::RadToDeg(pitch)
        << ',' << (t.view ? 1 : 0) << '\n';
  }
  io::WriteFileAtomically((dir / "trajectory.csv").string(), csv.str());
  io::WriteFileAtomically((dir / "trajectory.tum").string(), TrajectoryTum(*in.record));
  io::WriteFileAtomically((dir / "categories.json").string(), io::CategoriesJson());
  WriteRunTopView((dir / "topview.png").string(), in);
  in.scanner->WriteNavigationMap((dir / "navmap.png").string());
  if (in.write_more_files) in.write_more_files(out_dir);
  io::WriteFileAtomically((dir / "run.json").string(), RunJson(in));
}

}  // namespace objscan::eval
