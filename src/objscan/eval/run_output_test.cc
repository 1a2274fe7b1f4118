#include "objscan/eval/run_output.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace objscan::eval {
namespace {

// An object the graph cut left without a category ("none" label) is written with category null.
TEST(RunJsonTest, ObjectsWithAndWithoutCategory) {
  scanning::RunRecord record;
  record.terminated = scanning::Termination::kDone;
  scanning::ObjectRecord chair;
  chair.id = 3;
  chair.category = world::Category::kChair;
  chair.objectness = 0.97;
  chair.complete = true;
  scanning::ObjectRecord unknown;
  unknown.id = 7;
  unknown.objectness = 0.2;
  record.objects = {chair, unknown};
  const scanning::SystemConfig config;
  RunOutputInputs in;
  in.record = &record;
  in.config = &config;
  in.scene_spec = "procedural:bedroom:1";
  const nlohmann::json j = nlohmann::json::parse(RunJson(in));
  EXPECT_EQ(j["terminated"], "done");
  ASSERT_EQ(j["objects"].size(), 2u);
  EXPECT_EQ(j["objects"][0]["category"], "chair");
  EXPECT_TRUE(j["objects"][1]["category"].is_null());
  EXPECT_EQ(j["objects"][1]["id"], 7);
}

// The structure the robot found is written as planes: no floor is null, each wall its plane and extent.
TEST(RunJsonTest, StructureWithWallsAndNoFloor) {
  scanning::RunRecord record;
  record.terminated = scanning::Termination::kDone;
  scanning::WallRecord wall;
  wall.normal_x = 0.0;
  wall.normal_y = -1.0;
  wall.offset_m = -3.5;
  wall.span_min_m = 0.25;
  wall.span_max_m = 4.0;
  wall.z_min_m = 0.0;
  wall.z_max_m = 2.6;
  wall.area_m2 = 9.0;
  record.structure.walls = {wall};
  const scanning::SystemConfig config;
  RunOutputInputs in;
  in.record = &record;
  in.config = &config;
  nlohmann::json j = nlohmann::json::parse(RunJson(in));
  EXPECT_TRUE(j["structure"]["floor_height_m"].is_null());
  ASSERT_EQ(j["structure"]["walls"].size(), 1u);
  const auto& w = j["structure"]["walls"][0];
  EXPECT_EQ(w["normal_xy"], nlohmann::json({0.0, -1.0}));
  EXPECT_EQ(w["offset_m"], -3.5);
  EXPECT_EQ(w["span_m"], nlohmann::json({0.25, 4.0}));
  EXPECT_EQ(w["z_m"], nlohmann::json({0.0, 2.6}));
  EXPECT_EQ(w["area_m2"], 9.0);
  record.structure.floor_height_m = 0.01;
  j = nlohmann::json::parse(RunJson(in));
  EXPECT_EQ(j["structure"]["floor_height_m"], 0.01);
}

// trajectory.tum: a line per view (driving samples left out), the camera position and its rotation
// as a unit quaternion with qw >= 0, in the order taken.
TEST(TrajectoryTumTest, OneLinePerViewWithTheCameraPose) {
  scanning::RunRecord record;
  const std::vector<std::pair<double, double>> yaw_pitch_deg = {{0, 0}, {90, -20}, {-170, 10}};
  for (std::size_t i = 0; i < yaw_pitch_deg.size(); ++i) {
    scanning::TrajectorySample driving;
    driving.time_s = 2.0 * i;
    driving.view = false;
    record.trajectory.push_back(driving);
    scanning::TrajectorySample view;
    view.time_s = 2.0 * i + 1.0;
    view.view = true;
    view.T_world_camera = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(1.0 + i, -2.0, 1.2),
                                                           geometry::DegToRad(yaw_pitch_deg[i].first),
                                                           geometry::DegToRad(yaw_pitch_deg[i].second));
    record.trajectory.push_back(view);
  }
  std::istringstream in(TrajectoryTum(record));
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#') rows.push_back(line);
  }
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::istringstream row(rows[i]);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(row >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << rows[i];
    std::string rest;
    EXPECT_FALSE(row >> rest) << "more than 8 columns: " << rows[i];
    EXPECT_DOUBLE_EQ(t, 2.0 * i + 1.0);
    EXPECT_NEAR(x, 1.0 + i, 1e-6);
    EXPECT_NEAR(y, -2.0, 1e-6);
    EXPECT_NEAR(z, 1.2, 1e-6);
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_NEAR(q.norm(), 1.0, 1e-8);
    EXPECT_GE(qw, 0.0);
    const geometry::Pose3& T = record.trajectory[2 * i + 1].T_world_camera;
    EXPECT_TRUE(q.toRotationMatrix().isApprox(T.linear(), 1e-8)) << rows[i];
    // The optical axis (camera z) points where yaw and pitch say.
    double yaw = 0, pitch = 0;
    geometry::YawPitchOfCamera(geometry::Pose3(q.toRotationMatrix()), &yaw, &pitch);
    EXPECT_NEAR(geometry::RadToDeg(geometry::WrapAngle(yaw - geometry::DegToRad(yaw_pitch_deg[i].first))), 0.0, 1e-5);
    EXPECT_NEAR(geometry::RadToDeg(pitch), yaw_pitch_deg[i].second, 1e-5);
  }
}

// models.ply draws each complete object's model from the mesh stored in the database (no file needed),
// placed; a model with no mesh anywhere (built from scans, source gone) is drawn by its scan points
// and named in one warning, once however many objects use it.
TEST(PlacedModelsPlyTest, StoredMeshesArePlacedAndAModelWithoutMeshIsNamedOnce) {
  recognition::ModelDatabase db;
  recognition::DatabaseModel stored;
  stored.name = "chair/stored";
  stored.category = world::Category::kChair;
  stored.source = "/nowhere/house.world#chair_0";  // loadable from nowhere: the stored mesh is used
  stored.full_entry = 0;
  stored.mesh = geometry::MakeBox(Eigen::Vector3d(-0.2, -0.2, 0.0), Eigen::Vector3d(0.2, 0.2, 0.9));
  recognition::DatabaseModel gone = stored;
  gone.name = "table/gone";
  gone.category = world::Category::kTable;
  gone.source = "/nowhere/house.world#table_0";
  gone.full_entry = 1;
  gone.mesh = geometry::TriangleMesh();
  db.mutable_models() = {stored, gone};
  recognition::DatabaseEntry chair_entry, table_entry;
  chair_entry.model_index = 0;
  chair_entry.points = {{0.f, 0.f, 0.f}};
  table_entry.model_index = 1;
  table_entry.kind = recognition::EntryKind::kFullModel;
  table_entry.points = {{0.f, 0.f, 0.7f}, {0.5f, 0.f, 0.7f}, {0.f, 0.3f, 0.7f}};
  db.mutable_entries() = {chair_entry, table_entry};

  scanning::RunRecord record;
  const auto object = [](int id, int model, bool complete, const Eigen::Vector3d& at) {
    scanning::ObjectRecord o;
    o.id = id;
    o.model_index = model;
    o.complete = complete;
    o.category = model == 0 ? world::Category::kChair : world::Category::kTable;
    o.T_world_model = geometry::Pose3(Eigen::Translation3d(at));
    return o;
  };
  record.objects = {object(3, 0, true, {1.0, 2.0, 0.0}), object(4, 1, true, {-1.0, 0.0, 0.0}),
                    object(5, 1, true, {4.0, 0.0, 0.0}), object(6, 0, false, {9.0, 9.0, 0.0})};
  std::vector<std::string> warnings;
  const io::PlyData ply = PlacedModelsPly(record, db, [&](const std::string& m) { warnings.push_back(m); });

  ASSERT_EQ(ply.points.size(), 8u + 3u + 3u);  // the box, then the table's points twice; not object 6
  ASSERT_EQ(ply.triangles.size(), 12u);         // the box's, from the database
  geometry::Aabb3 box;
  for (int k = 0; k < 8; ++k) box.Extend(ply.points[k].cast<double>());
  EXPECT_NEAR((box.min_m - Eigen::Vector3d(0.8, 1.8, 0.0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((box.max_m - Eigen::Vector3d(1.2, 2.2, 0.9)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((ply.points[8] - Eigen::Vector3f(-1.f, 0.f, 0.7f)).norm(), 0.f, 1e-6f);
  EXPECT_NEAR((ply.points[11] - Eigen::Vector3f(4.f, 0.f, 0.7f)).norm(), 0.f, 1e-6f);
  ASSERT_FALSE(ply.int_properties.empty());
  EXPECT_EQ(ply.int_properties[0].first, "object_id");
  EXPECT_EQ(ply.int_properties[0].second.front(), 3);
  EXPECT_EQ(ply.int_properties[0].second.back(), 5);

  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("model table/gone"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("house.world#table_0"), std::string::npos) << warnings[0];
  EXPECT_EQ(warnings[0].find('\n'), std::string::npos) << warnings[0];
  // No callback: the same file, nothing told.
  EXPECT_EQ(PlacedModelsPly(record, db, nullptr).points.size(), ply.points.size());
}

}  // namespace
}  // namespace objscan::eval
