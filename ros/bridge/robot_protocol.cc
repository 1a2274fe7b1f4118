#include "robot_protocol.h"

#include <nlohmann/json.hpp>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

using Json = nlohmann::json;

constexpr RequestKind kKinds[] = {RequestKind::kHello,      RequestKind::kMap,        RequestKind::kCheckReach,
                                  RequestKind::kMoveCamera, RequestKind::kTurnCamera, RequestKind::kCapture};
constexpr platform::ReachStatus kReachStatuses[] = {
    platform::ReachStatus::kOk,         platform::ReachStatus::kCameraHeightOutOfRange,
    platform::ReachStatus::kPitchOutOfRange, platform::ReachStatus::kNoFreeBase,
    platform::ReachStatus::kStartBlocked, platform::ReachStatus::kUnreachable};
constexpr navigation::PlanStatus kPlanStatuses[] = {navigation::PlanStatus::kReached, navigation::PlanStatus::kStartBlocked,
                                                    navigation::PlanStatus::kGoalBlocked, navigation::PlanStatus::kUnreachable};

[[noreturn]] void Fail(const std::string& why) { throw InputError("robot protocol: " + why); }

// Enumerations travel by name, so a message stays readable in `rostopic echo` and a reordered enum
// cannot change its meaning.
template <class E, std::size_t N, class NameFn>
E FromName(const std::string& name, const E (&values)[N], NameFn name_of, const char* what) {
  for (E v : values) {
    if (name == name_of(v)) return v;
  }
  Fail(std::string("unknown ") + what + " '" + name + "'");
}

// 3x4, row-major: the rotation as it is (no quaternion to round).
Json PoseJson(const geometry::Pose3& pose) {
  Json a = Json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) a.push_back(pose.matrix()(r, c));
  }
  return a;
}

geometry::Pose3 PoseOf(const Json& a, const char* what) {
  if (!a.is_array() || a.size() != 12) Fail(std::string(what) + " is not 12 numbers");
  geometry::Pose3 pose = geometry::Pose3::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = a.at(r * 4 + c).get<double>();
  }
  return pose;
}

Json GridJson(const navigation::OccupancyGrid2D& grid) {
  // One digit per cell (CellState), row-major: compact, and exact.
  std::string cells(grid.cells.size(), '0');
  for (std::size_t i = 0; i < grid.cells.size(); ++i) cells[i] = static_cast<char>('0' + static_cast<int>(grid.cells[i]));
  return {{"cell_size_m", grid.cell_size_m},
          {"origin_m", {grid.origin_m.x(), grid.origin_m.y()}},
          {"width", grid.width},
          {"height", grid.height},
          {"cells", cells}};
}

navigation::OccupancyGrid2D GridOf(const Json& j) {
  navigation::OccupancyGrid2D grid;
  grid.cell_size_m = j.at("cell_size_m").get<double>();
  grid.origin_m = Eigen::Vector2d(j.at("origin_m").at(0).get<double>(), j.at("origin_m").at(1).get<double>());
  grid.width = j.at("width").get<int>();
  grid.height = j.at("height").get<int>();
  const std::string cells = j.at("cells").get<std::string>();
  if (grid.width < 0 || grid.height < 0 ||
      cells.size() != static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height)) {
    Fail("map of " + std::to_string(grid.width) + "x" + std::to_string(grid.height) + " with " +
         std::to_string(cells.size()) + " cells");
  }
  grid.cells.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] < '0' || cells[i] > '2') Fail("map cell '" + std::string(1, cells[i]) + "'");
    grid.cells[i] = static_cast<navigation::CellState>(cells[i] - '0');
  }
  return grid;
}

Json StateJson(const RobotState& s) {
  return {{"base", {s.base.xy_m.x(), s.base.xy_m.y(), s.base.theta_rad}},
          {"T_world_camera", PoseJson(s.T_world_camera)},
          {"travel",
           {{"distance_m", s.travel.distance_m},
            {"time_s", s.travel.time_s},
            {"turn_rad", s.travel.turn_rad},
            {"moves", s.travel.moves},
            {"arm_moves", s.travel.arm_moves}}}};
}

RobotState StateOf(const Json& j) {
  RobotState s;
  const Json& b = j.at("base");
  s.base.xy_m = Eigen::Vector2d(b.at(0).get<double>(), b.at(1).get<double>());
  s.base.theta_rad = b.at(2).get<double>();
  s.T_world_camera = PoseOf(j.at("T_world_camera"), "state.T_world_camera");
  const Json& t = j.at("travel");
  s.travel.distance_m = t.at("distance_m").get<double>();
  s.travel.time_s = t.at("time_s").get<double>();
  s.travel.turn_rad = t.at("turn_rad").get<double>();
  s.travel.moves = t.at("moves").get<int>();
  s.travel.arm_moves = t.at("arm_moves").get<int>();
  return s;
}

Json Parse(const std::string& text) {
  Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) Fail("not a JSON object: " + OneLine(text.substr(0, 80)));
  return j;
}

// nlohmann's own errors (a missing key, a string where a number belongs) as the protocol's.
template <class F>
auto Decoding(const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const nlohmann::json::exception& e) {
    Fail(std::string(what) + ": " + e.what());
  }
}

}  // namespace

const char* RequestKindName(RequestKind kind) {
  switch (kind) {
    case RequestKind::kHello: return "hello";
    case RequestKind::kMap: return "map";
    case RequestKind::kCheckReach: return "check_reach";
    case RequestKind::kMoveCamera: return "move_camera";
    case RequestKind::kTurnCamera: return "turn_camera";
    case RequestKind::kCapture: return "capture";
  }
  return "unknown";
}

std::string EncodeRequest(const RobotRequest& r) {
  Json j = {{"id", r.id}, {"kind", RequestKindName(r.kind)}};
  switch (r.kind) {
    case RequestKind::kCheckReach:
    case RequestKind::kMoveCamera:
      j["map_revision"] = r.map_revision;
      j["T_world_camera"] = PoseJson(r.T_world_camera);
      break;
    case RequestKind::kTurnCamera: j["T_world_camera"] = PoseJson(r.T_world_camera); break;
    case RequestKind::kMap:
      j["map"] = {{"revision", r.map.revision},
                  {"grid", GridJson(r.map.grid)},
                  {"robot_radius_m", r.map.robot_radius_m},
                  {"robot_height_m", r.map.robot_height_m},
                  {"cell_size_m", r.map.options.cell_size_m},
                  {"min_obstacle_height_m", r.map.options.min_obstacle_height_m},
                  {"smooth_path", r.map.options.smooth_path},
                  {"start_escape_m", r.map.options.start_escape_m}};
      break;
    case RequestKind::kCapture:
      if (r.asked_stamp_ns != 0) j["asked_stamp_ns"] = r.asked_stamp_ns;
      break;
    case RequestKind::kHello: break;
  }
  return j.dump();
}

RobotRequest DecodeRequest(const std::string& text) {
  const Json j = Parse(text);
  return Decoding("request", [&] {
    RobotRequest r;
    r.id = j.at("id").get<std::uint64_t>();
    r.kind = FromName(j.at("kind").get<std::string>(), kKinds, RequestKindName, "request kind");
    if (r.kind == RequestKind::kCheckReach || r.kind == RequestKind::kMoveCamera) {
      r.map_revision = j.at("map_revision").get<std::uint64_t>();
    }
    if (r.kind == RequestKind::kCheckReach || r.kind == RequestKind::kMoveCamera || r.kind == RequestKind::kTurnCamera) {
      r.T_world_camera = PoseOf(j.at("T_world_camera"), "T_world_camera");
    }
    if (r.kind == RequestKind::kCapture && j.contains("asked_stamp_ns")) {
      r.asked_stamp_ns = j.at("asked_stamp_ns").get<std::uint64_t>();
    }
    if (r.kind == RequestKind::kMap) {
      const Json& m = j.at("map");
      r.map.revision = m.at("revision").get<std::uint64_t>();
      r.map.grid = GridOf(m.at("grid"));
      r.map.robot_radius_m = m.at("robot_radius_m").get<double>();
      r.map.robot_height_m = m.at("robot_height_m").get<double>();
      r.map.options.cell_size_m = m.at("cell_size_m").get<double>();
      r.map.options.min_obstacle_height_m = m.at("min_obstacle_height_m").get<double>();
      r.map.options.smooth_path = m.at("smooth_path").get<bool>();
      r.map.options.start_escape_m = m.at("start_escape_m").get<double>();
    }
    return r;
  });
}

std::string EncodeResponse(const RobotResponse& r) {
  Json j = {{"id", r.id}, {"state", StateJson(r.state)}};
  if (!r.error.empty()) j["error"] = r.error;
  j["status"] = platform::ReachStatusName(r.status);
  Json waypoints = Json::array();
  for (const auto& w : r.path.waypoints) waypoints.push_back({w.x(), w.y()});
  j["path"] = {{"status", navigation::PlanStatusName(r.path.status)},
               {"waypoints", waypoints},
               {"length_m", r.path.length_m},
               {"grid_length_m", r.path.grid_length_m},
               {"expansions", r.path.expansions}};
  j["T_world_camera_taken"] = PoseJson(r.T_world_camera_taken);
  if (!r.world_name.empty()) j["world_name"] = r.world_name;
  const platform::CameraIntrinsics& k = r.intrinsics;
  j["intrinsics"] = {{"width_px", k.width_px}, {"height_px", k.height_px}, {"fx_px", k.fx_px},
                     {"fy_px", k.fy_px},       {"cx_px", k.cx_px},         {"cy_px", k.cy_px},
                     {"min_range_m", k.min_range_m}, {"max_range_m", k.max_range_m}};
  return j.dump();
}

RobotResponse DecodeResponse(const std::string& text) {
  const Json j = Parse(text);
  return Decoding("response", [&] {
    RobotResponse r;
    r.id = j.at("id").get<std::uint64_t>();
    r.state = StateOf(j.at("state"));
    if (j.contains("error")) r.error = j.at("error").get<std::string>();
    r.status = FromName(j.at("status").get<std::string>(), kReachStatuses, platform::ReachStatusName, "reach status");
    const Json& p = j.at("path");
    r.path.status = FromName(p.at("status").get<std::string>(), kPlanStatuses, navigation::PlanStatusName, "path status");
    for (const Json& w : p.at("waypoints")) r.path.waypoints.emplace_back(w.at(0).get<double>(), w.at(1).get<double>());
    r.path.length_m = p.at("length_m").get<double>();
    r.path.grid_length_m = p.at("grid_length_m").get<double>();
    r.path.expansions = p.at("expansions").get<int>();
    r.T_world_camera_taken = PoseOf(j.at("T_world_camera_taken"), "T_world_camera_taken");
    if (j.contains("world_name")) r.world_name = j.at("world_name").get<std::string>();
    const Json& k = j.at("intrinsics");
    r.intrinsics.width_px = k.at("width_px").get<int>();
    r.intrinsics.height_px = k.at("height_px").get<int>();
    r.intrinsics.fx_px = k.at("fx_px").get<double>();
    r.intrinsics.fy_px = k.at("fy_px").get<double>();
    r.intrinsics.cx_px = k.at("cx_px").get<double>();
    r.intrinsics.cy_px = k.at("cy_px").get<double>();
    r.intrinsics.min_range_m = k.at("min_range_m").get<double>();
    r.intrinsics.max_range_m = k.at("max_range_m").get<double>();
    return r;
  });
}

}  // namespace objscan::ros_bridge
