// Pre-segmentation quality on whole rooms rendered by the simulator (640x480, Kinect-style noise,
// fixed seeds): the procedural rooms of every category scanned from a fixed ring of 12 views, and
// an OASC development world. With OBJSCAN_TEST_IMAGE_DIR set, each scan also writes a top view of
// its components (a random colour per label, floor light grey, walls dark grey, unlabelled black).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "objscan/common/rng.h"
#include "objscan/common/timer.h"
#include "objscan/io/canvas.h"
#include "objscan/io/scene_spec.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/segmentation/incremental_segmenter.h"
#include "objscan/segmentation/segmentation_quality.h"
#include "objscan/eval/ground_truth_votes.h"
#include "objscan/render/depth_camera.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/navigation/navigator.h"
#include "objscan/world/procedural/procedural.h"
#include "shared_data.h"

namespace objscan::segmentation {
namespace {

constexpr double kCameraHeightM = 1.3;
constexpr double kCameraPitchDeg = -25.0;
constexpr double kRobotRadiusM = 0.2;
constexpr double kRobotHeightM = 1.4;

struct RoomScan {
  mapping::SurfaceMap map;
  eval::GroundTruthVotes votes;  // each element's ground-truth instance
  IncrementalSegmenter segmenter;
  mapping::StructureResult structure;
};

// Fuses and segments every view; floor and walls are re-detected after each frame, as the scanner
// does after each step.
void Scan(const world::Scene& scene, const std::vector<geometry::Pose3>& views, std::uint64_t seed,
          RoomScan* scan) {
  const render::DepthCamera camera(scene, render::SensorOptions());
  const mapping::StructureDetector detector;
  Rng rng(seed);
  mapping::FrameAssociation association;
  for (const geometry::Pose3& T : views) {
    const platform::DepthFrame frame = camera.Render(T, &rng);
    scan->map.Integrate(frame, &association);
    scan->votes.Observe(frame, association);
    scan->segmenter.Update(frame, association, &scan->map);
    scan->structure = detector.Update(&scan->map);
  }
}

std::vector<std::int32_t> StructuralInstances(const world::Scene& scene) {
  std::vector<std::int32_t> ids;
  for (const world::SceneObject& o : scene.objects()) {
    if (o.IsStructural()) ids.push_back(o.instance_id);
  }
  return ids;
}

// A ring of `count` cameras on a circle of radius_fraction x the room's smaller side around the
// room centre, each at the free position nearest its ring point, looking inward (across the room at
// the furniture on the far side) or outward, slightly down.
std::vector<geometry::Pose3> RingViews(const world::Scene& scene, int count, bool outward,
                                       double radius_fraction) {
  const sim::GroundTruthOccupancy truth(scene);
  const navigation::Navigator navigator(truth, kRobotRadiusM, kRobotHeightM);
  const geometry::Aabb3 room = scene.StructureBounds(world::Category::kWall);
  const Eigen::Vector2d centre = room.Center().head<2>();
  const double radius = radius_fraction * std::min(room.Size().x(), room.Size().y());
  std::vector<geometry::Pose3> views;
  for (int k = 0; k < count; ++k) {
    const double yaw = 2.0 * M_PI * k / count;
    const Eigen::Vector2d ring = centre + radius * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    Eigen::Vector2d xy;
    if (!navigator.NearestFree(ring, 2.0, &xy)) continue;
    views.push_back(geometry::CameraPoseFromYawPitch(Eigen::Vector3d(xy.x(), xy.y(), kCameraHeightM),
                                                     outward ? yaw : yaw + M_PI, geometry::DegToRad(kCameraPitchDeg)));
  }
  return views;
}

// Per furniture instance: label -> its labelled, non-structural elements.
std::map<std::int32_t, std::map<std::int32_t, int>> LabelsPerFurniture(const world::Scene& scene,
                                                                       const RoomScan& scan) {
  const mapping::SurfaceMap& map = scan.map;
  std::map<std::int32_t, std::map<std::int32_t, int>> out;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::int32_t g = scan.votes.Instance(i);
    const world::SceneObject* o = scene.Find(g);
    if (o == nullptr || o->IsStructural() || map.label(i) <= 0 || map.structure(i) != mapping::Structure::kNone) continue;
    ++out[g][map.label(i)];
  }
  return out;
}

int CountAtLeast(const std::map<std::int32_t, int>& counts, int min_count) {
  int n = 0;
  for (const auto& kv : counts) n += kv.second >= min_count ? 1 : 0;
  return n;
}

// A distinct, saturated colour per label (golden-ratio hues, brightness from a hash).
io::Rgb LabelColour(std::int32_t label) {
  const std::uint64_t h = MixSeed(static_cast<std::uint64_t>(label));
  const double hue = std::fmod(0.61803398875 * label + 0.1, 1.0) * 6.0;
  const double s = 0.55 + 0.45 * ((h >> 8) & 0xFF) / 255.0, v = 0.6 + 0.4 * ((h >> 16) & 0xFF) / 255.0;
  const double f = hue - std::floor(hue);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (static_cast<int>(hue) % 6) {
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    case 5: r = v, g = p, b = q; break;
    default: break;
  }
  return {static_cast<std::uint8_t>(255 * r), static_cast<std::uint8_t>(255 * g), static_cast<std::uint8_t>(255 * b)};
}

// Top view of the pre-segmented surface (1 cm per pixel), higher elements drawn over lower ones.
void MaybeWriteTopView(const RoomScan& scan, const world::Scene& scene, const std::string& name) {
  const char* dir = std::getenv("OBJSCAN_TEST_IMAGE_DIR");
  if (dir == nullptr) return;
  const mapping::SurfaceMap& map = scan.map;
  const io::WorldToPixel to_pixel(scene.StructureBounds(world::Category::kWall), 0.01, 10);
  io::Canvas canvas(to_pixel.width_px(), to_pixel.height_px(), {255, 255, 255});
  std::vector<std::size_t> order(map.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return map.position(a).z() < map.position(b).z(); });
  for (std::size_t i : order) {
    const Eigen::Vector2d px = to_pixel.ToPixel(map.position(i).cast<double>());
    io::Rgb c = {0, 0, 0};
    if (map.structure(i) == mapping::Structure::kFloor) {
      c = {222, 222, 222};
    } else if (map.structure(i) == mapping::Structure::kWall) {
      c = {120, 120, 120};
    } else if (map.label(i) > 0) {
      c = LabelColour(map.label(i));
    }
    canvas.SetPixel(static_cast<int>(px.x()), static_cast<int>(px.y()), c);
  }
  canvas.SavePng(std::string(dir) + "/" + name + ".png");
}

TEST(PresegRoomsTest, ProceduralRoomsFromARingOfTwelveViewsArePure) {
  for (const std::string& category : world::procedural::RoomCategories()) {
    SCOPED_TRACE(category);
    Stopwatch clock;
    const world::Scene scene = world::procedural::GenerateRoom(category, 1);
    const std::vector<geometry::Pose3> views = RingViews(scene, 12, /*outward=*/false, 0.25);
    ASSERT_EQ(views.size(), 12u);
    RoomScan scan;
    Scan(scene, views, 7, &scan);
    const PresegQuality q = EvaluatePresegmentation(scan.map, scan.votes.Instances(scan.map.size()), StructuralInstances(scene));
    // The ring sees most of the furniture (a room's worth of object points).
    const auto per_furniture = LabelsPerFurniture(scene, scan);
    int seen = 0;
    for (const auto& [instance, labels] : per_furniture) {
      int total = 0;
      for (const auto& kv : labels) total += kv.second;
      seen += total >= 200 ? 1 : 0;
    }
    EXPECT_GE(seen, static_cast<int>(0.7 * scene.NumFurniture()));
    EXPECT_GT(q.num_points, 20000u);
    EXPECT_GE(q.preseg_purity, 0.95);
    std::printf("[ info ] %-12s preseg_purity %.4f rand_index_preseg %.4f  %zu points, %zu components, "
                "%d of %zu objects seen, %.1f s\n",
                category.c_str(), q.preseg_purity, q.rand_index_preseg, q.num_points, q.num_components, seen,
                scene.NumFurniture(), clock.ElapsedSeconds());
    MaybeWriteTopView(scan, scene, "preseg_" + category);
  }
}

// A SUNCG bedroom (18 pieces of furniture) scanned from three rings: components are pure (furniture
// is not smeared across objects) and pieces of furniture are split into near-convex parts.
TEST(PresegRoomsTest, OascBedroomFurnitureIsSplitIntoPartsNotSmeared) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  Stopwatch clock;
  io::SceneLoadOptions load;
  load.model_path = data + "/gazebo-models";
  const world::Scene scene =
      io::LoadScene(data + "/oasc-dev/SUNCG/bedroom/0a2f9f9b603e3960459f332c5635051e/0_7/room.world", load);
  std::vector<geometry::Pose3> views;
  for (const auto& [outward, radius] : {std::make_pair(false, 0.25), std::make_pair(true, 0.25),
                                        std::make_pair(false, 0.4)}) {
    const std::vector<geometry::Pose3> ring = RingViews(scene, 12, outward, radius);
    views.insert(views.end(), ring.begin(), ring.end());
  }
  ASSERT_GE(views.size(), 30u);
  RoomScan scan;
  Scan(scene, views, 11, &scan);
  const PresegQuality q = EvaluatePresegmentation(scan.map, scan.votes.Instances(scan.map.size()), StructuralInstances(scene));
  EXPECT_GE(q.preseg_purity, 0.95);
  // Pieces of furniture seen well (>= 2000 elements) and how many of them have two or more parts
  // (labels holding >= 200 of their elements).
  int well_seen = 0, split = 0;
  for (const auto& [instance, labels] : LabelsPerFurniture(scene, scan)) {
    int total = 0;
    for (const auto& kv : labels) total += kv.second;
    if (total < 2000) continue;
    ++well_seen;
    split += CountAtLeast(labels, 200) >= 2 ? 1 : 0;
  }
  EXPECT_GE(well_seen, 8);
  EXPECT_GE(split, 4);
  std::printf("[ info ] OASC bedroom preseg_purity %.4f rand_index_preseg %.4f  %zu points, %zu components, "
              "%d of %d well-seen objects in parts, %.1f s\n",
              q.preseg_purity, q.rand_index_preseg, q.num_points, q.num_components, split, well_seen,
              clock.ElapsedSeconds());
  MaybeWriteTopView(scan, scene, "preseg_oasc");
}

}  // namespace
}  // namespace objscan::segmentation
