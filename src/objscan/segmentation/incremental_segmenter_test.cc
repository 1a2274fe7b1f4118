#include "objscan/segmentation/incremental_segmenter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "objscan/common/rng.h"
#include "objscan/mapping/testing/analytic_world.h"
#include "objscan/mapping/planes.h"
#include "objscan/segmentation/segmentation_quality.h"
#include "objscan/eval/ground_truth_votes.h"
#include "objscan/render/depth_camera.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::segmentation {
namespace {

using mapping::testing::AnalyticWorld;
using mapping::testing::LookAt;

struct Scanned {
  mapping::SurfaceMap map;
  IncrementalSegmenter segmenter;
  eval::GroundTruthVotes votes;  // each element's ground-truth instance
};

void Scan(const AnalyticWorld& world, const std::vector<geometry::Pose3>& poses, std::uint64_t seed, Scanned* s) {
  Rng rng(seed);
  mapping::FrameAssociation assoc;
  for (const geometry::Pose3& T : poses) {
    const platform::DepthFrame frame = world.Render(T, &rng);
    s->map.Integrate(frame, &assoc);
    s->votes.Observe(frame, assoc);
    s->segmenter.Update(frame, assoc, &s->map);
  }
}

// Ring of `count` views at `radius` and `height` around `target`.
std::vector<geometry::Pose3> Ring(const Eigen::Vector3d& target, double radius, double height, int count) {
  std::vector<geometry::Pose3> poses;
  for (int k = 0; k < count; ++k) {
    const double yaw = 2.0 * M_PI * k / count + 0.3;
    poses.push_back(LookAt(target + Eigen::Vector3d(radius * std::cos(yaw), radius * std::sin(yaw), height), target));
  }
  return poses;
}

// For each ground-truth instance: label -> number of labelled elements.
std::map<std::int32_t, std::map<std::int32_t, int>> LabelsPerInstance(const Scanned& s) {
  const mapping::SurfaceMap& map = s.map;
  std::map<std::int32_t, std::map<std::int32_t, int>> out;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (map.label(i) > 0) ++out[s.votes.Instance(i)][map.label(i)];
  }
  return out;
}

std::pair<std::int32_t, double> MajorityLabel(const std::map<std::int32_t, int>& counts) {
  int total = 0, best = 0;
  std::int32_t label = 0;
  for (const auto& [l, c] : counts) {
    total += c;
    if (c > best) {
      best = c;
      label = l;
    }
  }
  return {label, total > 0 ? static_cast<double>(best) / total : 0.0};
}

TEST(IncrementalSegmenterTest, FlatFaceStaysOneSegment) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.75, -0.5, 0.35), Eigen::Vector3d(0.75, 0.5, 0.4), 1);
  Scanned s;
  Scan(world, Ring(Eigen::Vector3d(0, 0, 0.4), 1.4, 1.0, 6), 11, &s);
  // Elements of the top face (normal up).
  std::map<std::int32_t, int> top;
  for (std::size_t i = 0; i < s.map.size(); ++i) {
    if (s.map.normal(i).z() > 0.9f && s.map.label(i) > 0) ++top[s.map.label(i)];
  }
  ASSERT_FALSE(top.empty());
  EXPECT_GE(MajorityLabel(top).second, 0.97);
}

TEST(IncrementalSegmenterTest, BoxStandingOnABoxGivesTwoAdjacentComponents) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.4, -0.3, 0.0), Eigen::Vector3d(0.4, 0.3, 0.45), 1);
  world.Add(Eigen::Vector3d(-0.2, -0.15, 0.45), Eigen::Vector3d(0.15, 0.15, 0.75), 2);
  Scanned s;
  Scan(world, Ring(Eigen::Vector3d(0, 0, 0.4), 1.5, 0.9, 8), 12, &s);
  const auto per_instance = LabelsPerInstance(s);
  const auto [bottom_label, bottom_share] = MajorityLabel(per_instance.at(1));
  const auto [top_label, top_share] = MajorityLabel(per_instance.at(2));
  EXPECT_NE(bottom_label, top_label);
  EXPECT_GE(bottom_share, 0.9);
  EXPECT_GE(top_share, 0.9);
  const ComponentGraph& graph = s.segmenter.Components(&s.map);
  ASSERT_NE(graph.Find(bottom_label), nullptr);
  ASSERT_NE(graph.Find(top_label), nullptr);
  EXPECT_TRUE(graph.Adjacent(bottom_label, top_label));
  // The big components are exactly these two.
  int big = 0;
  for (const Component& c : graph.components()) big += c.area_m2 > 0.02 ? 1 : 0;
  EXPECT_EQ(big, 2);
  const PresegQuality q = EvaluatePresegmentation(s.map, s.votes.Instances(s.map.size()), {});
  EXPECT_GE(q.preseg_purity, 0.97);
  EXPECT_GE(q.rand_index_preseg, 0.9);
}

// Two boxes 12 cm apart: not adjacent with the default 2-voxel cells, adjacent with 8-voxel cells
// (elements about 12 voxels apart across the gap fall in neighbouring cells).
TEST(IncrementalSegmenterTest, AdjacencyCellSizeJoinsPartsAcrossASmallGap) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.5, -0.3, 0.0), Eigen::Vector3d(-0.06, 0.3, 0.45), 1);
  world.Add(Eigen::Vector3d(0.06, -0.3, 0.0), Eigen::Vector3d(0.5, 0.3, 0.45), 2);
  for (const int cell_voxels : {2, 8}) {
    Scanned s;
    IncrementalSegmenterOptions options;
    options.adjacency_cell_voxels = cell_voxels;
    s.segmenter = IncrementalSegmenter(options);
    Scan(world, Ring(Eigen::Vector3d(0, 0, 0.3), 1.6, 1.0, 8), 13, &s);
    const auto per_instance = LabelsPerInstance(s);
    const std::int32_t left = MajorityLabel(per_instance.at(1)).first;
    const std::int32_t right = MajorityLabel(per_instance.at(2)).first;
    ASSERT_NE(left, right);
    const ComponentGraph& graph = s.segmenter.Components(&s.map);
    ASSERT_NE(graph.Find(left), nullptr);
    ASSERT_NE(graph.Find(right), nullptr);
    EXPECT_EQ(graph.Adjacent(left, right), cell_voxels == 8) << cell_voxels << "-voxel cells";
  }
}

TEST(IncrementalSegmenterTest, ChairIsSplitIntoNearConvexParts) {
  // Seat (1), back (2), four legs (3..6), floor (10).
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-2, -2, -0.05), Eigen::Vector3d(2, 2, 0.0), 10);
  world.Add(Eigen::Vector3d(-0.22, -0.22, 0.42), Eigen::Vector3d(0.22, 0.22, 0.47), 1);
  // Parts meet at concave folds or depth steps (no flush faces, which would join them).
  world.Add(Eigen::Vector3d(-0.19, 0.14, 0.47), Eigen::Vector3d(0.19, 0.18, 0.9), 2);
  const double l = 0.035;
  int id = 3;
  for (double x : {-0.16, 0.16 - l}) {
    for (double y : {-0.16, 0.16 - l}) world.Add(Eigen::Vector3d(x, y, 0.0), Eigen::Vector3d(x + l, y + l, 0.42), id++);
  }
  Scanned s;
  Scan(world, Ring(Eigen::Vector3d(0, 0, 0.4), 1.3, 0.7, 8), 13, &s);
  const auto per_instance = LabelsPerInstance(s);
  const std::int32_t seat = MajorityLabel(per_instance.at(1)).first;
  const std::int32_t back = MajorityLabel(per_instance.at(2)).first;
  const std::int32_t floor = MajorityLabel(per_instance.at(10)).first;
  EXPECT_NE(seat, back);
  EXPECT_NE(seat, floor);
  EXPECT_NE(back, floor);
  for (int leg = 3; leg <= 6; ++leg) {
    const std::int32_t leg_label = MajorityLabel(per_instance.at(leg)).first;
    EXPECT_NE(leg_label, seat) << "leg " << leg;
    EXPECT_NE(leg_label, floor) << "leg " << leg;
  }
  // Parts are not smeared into each other.
  EXPECT_GE(EvaluatePresegmentation(s.map, s.votes.Instances(s.map.size()), {10}).preseg_purity, 0.95);
  const ComponentGraph& graph = s.segmenter.Components(&s.map);
  EXPECT_TRUE(graph.Adjacent(seat, back));
}

TEST(IncrementalSegmenterTest, PartSeenInTwoPartialViewsEndsWithOneLabel) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-1.5, -0.3, 0.35), Eigen::Vector3d(1.5, 0.3, 0.4), 1);
  Scanned s;
  // Two close views see disjoint ends of the slab, giving two labels ...
  Scan(world,
       {LookAt(Eigen::Vector3d(-0.9, -0.05, 1.3), Eigen::Vector3d(-0.9, 0, 0.4)),
        LookAt(Eigen::Vector3d(0.9, -0.05, 1.3), Eigen::Vector3d(0.9, 0, 0.4))},
       14, &s);
  std::map<std::int32_t, int> top;
  for (std::size_t i = 0; i < s.map.size(); ++i) {
    if (s.map.normal(i).z() > 0.9f && s.map.label(i) > 0) ++top[s.map.label(i)];
  }
  EXPECT_EQ(top.size(), 2u);
  // ... then views of the whole slab show they are one surface.
  const geometry::Pose3 whole = LookAt(Eigen::Vector3d(0, -0.05, 2.6), Eigen::Vector3d(0, 0, 0.4));
  Scan(world, {whole, whole}, 15, &s);
  top.clear();
  for (std::size_t i = 0; i < s.map.size(); ++i) {
    if (s.map.normal(i).z() > 0.9f && s.map.label(i) > 0) ++top[s.map.label(i)];
  }
  EXPECT_GE(MajorityLabel(top).second, 0.99);
}

// A kitchen row: three cabinets against a wall with 2 cm gaps, their fronts and tops 5 cm apart,
// seen from 2.5 to 3 m. Only the steps separate them (too small for the depth-jump test and too
// few pixels of side face for the normals to turn), so each must keep its own label.
TEST(IncrementalSegmenterTest, CabinetsInARowWithSmallStepsStaySeparate) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-1, -3, -0.05), Eigen::Vector3d(3, 3, 0.0), 10);   // floor
  world.Add(Eigen::Vector3d(-0.1, -3, 0.0), Eigen::Vector3d(0.0, 3, 2.4), 11);  // wall
  world.Add(Eigen::Vector3d(0.0, -1.3, 0.0), Eigen::Vector3d(0.60, -0.32, 0.87), 1);
  world.Add(Eigen::Vector3d(0.0, -0.30, 0.0), Eigen::Vector3d(0.65, 0.62, 0.92), 2);
  world.Add(Eigen::Vector3d(0.0, 0.64, 0.0), Eigen::Vector3d(0.60, 1.4, 0.87), 3);
  Scanned s;
  std::vector<geometry::Pose3> poses;
  for (double y : {-1.2, 0.0, 1.2}) {
    poses.push_back(LookAt(Eigen::Vector3d(2.6, y, 1.3), Eigen::Vector3d(0.3, 0.0, 0.5)));
  }
  Scan(world, poses, 17, &s);
  const auto per_instance = LabelsPerInstance(s);
  std::set<std::int32_t> labels;
  for (int cabinet = 1; cabinet <= 3; ++cabinet) {
    const auto [label, share] = MajorityLabel(per_instance.at(cabinet));
    labels.insert(label);
    EXPECT_GE(share, 0.6) << "cabinet " << cabinet;
  }
  EXPECT_EQ(labels.size(), 3u) << "cabinets share a label";
  EXPECT_GE(EvaluatePresegmentation(s.map, s.votes.Instances(s.map.size()), {10, 11}).preseg_purity, 0.95);
}

// Procedural furniture on thin legs and feet standing on the floor, rendered by the simulator with
// Kinect-style noise from 2.5 to 3.5 m: where a foot meets the floor the fold is a few blurred
// pixels, so without the floor prior the floor's segment leaks into the furniture and its label
// chains the pieces together.
TEST(IncrementalSegmenterTest, FloorPriorKeepsTheFloorLabelOffFurniture) {
  world::Scene scene("floor_and_furniture");
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-4, -4, 4, 4);
  const std::int32_t floor_id = scene.Add(floor);
  const world::Category kinds[] = {world::Category::kShelves, world::Category::kChair, world::Category::kTable,
                                   world::Category::kShelves};
  for (int k = 0; k < 4; ++k) {
    const world::procedural::FurnitureModel model = world::procedural::GenerateFurniture(kinds[k], 40 + k);
    world::SceneObject o;
    o.category = model.category;
    o.mesh = model.mesh;
    o.T_world_object = geometry::PoseFromXyzRpy(1.1 * std::cos(M_PI / 2 * k), 1.1 * std::sin(M_PI / 2 * k), 0.0, 0.0,
                                                0.0, M_PI / 2 * k);
    scene.Add(o);
  }
  const render::DepthCamera camera(scene, render::SensorOptions());
  Rng rng(19);
  Scanned s;
  mapping::FrameAssociation assoc;
  for (int k = 0; k < 8; ++k) {
    const double yaw = 2.0 * M_PI * k / 8 + 0.2;
    const platform::DepthFrame frame =
        camera.Render(LookAt(Eigen::Vector3d(3.2 * std::cos(yaw), 3.2 * std::sin(yaw), 1.3), Eigen::Vector3d(0, 0, 0.3)),
                      &rng);
    s.map.Integrate(frame, &assoc);
    s.votes.Observe(frame, assoc);
    s.segmenter.Update(frame, assoc, &s.map);
  }
  // Labels per instance over the elements clear of the floor (a pedestal's base plate lying within
  // the floor tolerance is floor for the prior and for the structure detector alike).
  std::map<std::int32_t, std::map<std::int32_t, int>> per_instance;
  for (std::size_t i = 0; i < s.map.size(); ++i) {
    const std::int32_t g = s.votes.Instance(i);
    if (s.map.label(i) > 0 && (g == floor_id || s.map.position(i).z() > 0.04f)) ++per_instance[g][s.map.label(i)];
  }
  const std::int32_t floor_label = MajorityLabel(per_instance.at(floor_id)).first;
  for (const world::SceneObject& o : scene.objects()) {
    if (o.instance_id == floor_id) continue;
    const auto& counts = per_instance.at(o.instance_id);
    const auto it = counts.find(floor_label);
    const int total = std::accumulate(counts.begin(), counts.end(), 0,
                                      [](int sum, const std::pair<const std::int32_t, int>& c) { return sum + c.second; });
    EXPECT_TRUE(it == counts.end() || it->second < 0.01 * total)
        << world::CategoryName(o.category) << " " << it->second << " of " << total;
  }
  mapping::StructureDetector().Update(&s.map);
  EXPECT_GE(EvaluatePresegmentation(s.map, s.votes.Instances(s.map.size()), {floor_id}).preseg_purity, 0.97);
}

TEST(IncrementalSegmenterTest, ComponentsTrackChangesIncrementally) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.3, -0.3, 0.0), Eigen::Vector3d(0.3, 0.3, 0.4), 1);
  world.Add(Eigen::Vector3d(1.0, -0.3, 0.0), Eigen::Vector3d(1.6, 0.3, 0.4), 2);
  Scanned s;
  Scan(world, {LookAt(Eigen::Vector3d(0.65, -1.8, 1.2), Eigen::Vector3d(0.65, 0, 0.2))}, 16, &s);
  const ComponentGraph& g1 = s.segmenter.Components(&s.map);
  ASSERT_GE(g1.size(), 2u);
  EXPECT_FALSE(s.segmenter.changed_labels().empty());
  // Separate boxes are not adjacent.
  const auto per_instance = LabelsPerInstance(s);
  const std::int32_t a = MajorityLabel(per_instance.at(1)).first, b = MajorityLabel(per_instance.at(2)).first;
  EXPECT_FALSE(g1.Adjacent(a, b));
  const Component* ca = g1.Find(a);
  ASSERT_NE(ca, nullptr);
  EXPECT_EQ(ca->points.size(), ca->normals.size());
  EXPECT_NEAR(ca->area_m2, ca->points.size() * 1e-4, 1e-9);
  EXPECT_TRUE(ca->bounds.Contains(Eigen::Vector3d(0, -0.3, 0.2), 0.02));
  // Nothing changed: nothing is recomputed.
  const std::uint64_t revision = ca->revision;
  s.segmenter.Components(&s.map);
  EXPECT_TRUE(s.segmenter.changed_labels().empty());
  EXPECT_EQ(s.segmenter.Components(&s.map).Find(a)->revision, revision);
  // Removing an object drops its component.
  s.map.Remove({a});
  const ComponentGraph& g2 = s.segmenter.Components(&s.map);
  EXPECT_EQ(g2.Find(a), nullptr);
  EXPECT_NE(g2.Find(b), nullptr);
}

// The adjacency kept across calls (edges between unchanged components are not recomputed) equals the
// adjacency computed from scratch. The scanned surface is relabelled by 7 cm cubes (so labels touch
// across the segmenter's 16-voxel blocks), then random cubes change label a few at a time, leaving
// most components unchanged between calls.
class IncrementalAdjacencyTest : public ::testing::TestWithParam<int> {};

TEST_P(IncrementalAdjacencyTest, EqualsRecomputingIt) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.4, -0.3, 0.0), Eigen::Vector3d(0.4, 0.3, 0.45), 1);
  world.Add(Eigen::Vector3d(-0.2, -0.15, 0.45), Eigen::Vector3d(0.2, 0.15, 0.8), 2);
  world.Add(Eigen::Vector3d(0.4, -0.3, 0.0), Eigen::Vector3d(0.9, 0.3, 0.3), 3);
  Scanned s;
  Scan(world, Ring(Eigen::Vector3d(0.25, 0.0, 0.3), 2.0, 1.3, 4), 40, &s);
  auto cube_of = [](const Eigen::Vector3f& p) {
    const Eigen::Vector3i c = (p / 0.07f).array().floor().cast<int>();
    return (c.x() + 50) * 10000 + (c.y() + 50) * 100 + (c.z() + 50);
  };
  std::map<int, std::int32_t> label_of_cube;
  for (std::size_t i = 0; i < s.map.size(); ++i) {
    const int cube = cube_of(s.map.position(i));
    auto it = label_of_cube.emplace(cube, static_cast<std::int32_t>(label_of_cube.size()) + 1).first;
    s.map.SetLabel(i, it->second, 1.f);
  }
  ASSERT_GT(label_of_cube.size(), 50u);
  IncrementalSegmenterOptions options;
  options.min_component_elements = 5;
  options.adjacency_cell_voxels = GetParam();
  IncrementalSegmenter incremental(options);
  Rng rng(7);
  std::int32_t next_label = static_cast<std::int32_t>(label_of_cube.size()) + 1;
  std::vector<int> cubes;
  for (const auto& [cube, label] : label_of_cube) cubes.push_back(cube);
  std::size_t max_edges = 0, changed_rounds = 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> previous;
  for (int round = 0; round < 12; ++round) {
    if (round > 0) {
      // Three cubes take a fresh label or the label of another cube (a merge).
      for (int k = 0; k < 3; ++k) {
        const int cube = cubes[static_cast<std::size_t>(rng.UniformInt(0, static_cast<int>(cubes.size()) - 1))];
        const std::int32_t label =
            rng.Uniform01() < 0.5 ? next_label++
                                  : label_of_cube[cubes[static_cast<std::size_t>(
                                        rng.UniformInt(0, static_cast<int>(cubes.size()) - 1))]];
        for (std::size_t i = 0; i < s.map.size(); ++i) {
          if (cube_of(s.map.position(i)) == cube) s.map.SetLabel(i, label, 1.f);
        }
      }
    }
    const ComponentGraph& graph = incremental.Components(&s.map);
    mapping::SurfaceMap copy = s.map;
    copy.TakeDirtyLabels();
    for (std::int32_t l : copy.Labels()) copy.RelabelAll({l}, l);
    IncrementalSegmenter fresh(options);
    const ComponentGraph& full = fresh.Components(&copy);
    if (round > 0) {
      EXPECT_LT(incremental.changed_labels().size(), graph.size() / 4) << "round " << round;
    }
    ASSERT_EQ(graph.size(), full.size()) << "round " << round;
    EXPECT_EQ(graph.Edges(), full.Edges()) << "round " << round;
    max_edges = std::max(max_edges, full.Edges().size());
    if (full.Edges() != previous) ++changed_rounds;
    previous = full.Edges();
  }
  EXPECT_GT(max_edges, 50u);
  EXPECT_GE(changed_rounds, 8u);
}

// Cell sizes: the default, one that does not divide the 16-voxel blocks, and the largest allowed.
INSTANTIATE_TEST_SUITE_P(CellVoxels, IncrementalAdjacencyTest, ::testing::Values(2, 3, 8));

}  // namespace
}  // namespace objscan::segmentation

namespace objscan::segmentation {
namespace {

// Three base cabinets 2.5 cm apart against a wall, first seen from 4 m (the gaps unresolved: one
// frame segment spans the run), then from about 1.6 m on both sides (the gaps' side faces in view).
Scanned ScanCounterRun(bool slot_split) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-1, -3, -0.05), Eigen::Vector3d(5, 3, 0.0), 10);   // floor
  world.Add(Eigen::Vector3d(-0.1, -3, 0.0), Eigen::Vector3d(0.0, 3, 2.4), 11);  // wall
  for (int k = 0; k < 3; ++k) {
    const double y0 = -0.925 + 0.625 * k;
    world.Add(Eigen::Vector3d(0.0, y0, 0.0), Eigen::Vector3d(0.6, y0 + 0.6, 0.9), k + 1);
  }
  IncrementalSegmenterOptions options;
  options.slot_split.enabled = slot_split;
  Scanned s{mapping::SurfaceMap(), IncrementalSegmenter(options), eval::GroundTruthVotes()};
  std::vector<geometry::Pose3> poses;
  for (double y : {-0.5, 0.0, 0.5}) poses.push_back(LookAt(Eigen::Vector3d(4.2, y, 1.4), Eigen::Vector3d(0.3, 0.0, 0.45)));
  for (double y : {-1.3, -0.6, 0.0, 0.6, 1.3}) {
    poses.push_back(LookAt(Eigen::Vector3d(1.9, y, 1.3), Eigen::Vector3d(0.4, -0.6 * y, 0.45)));
  }
  Rng rng(23);
  mapping::FrameAssociation assoc;
  for (const geometry::Pose3& T : poses) {
    const platform::DepthFrame frame = world.Render(T, &rng);
    s.map.Integrate(frame, &assoc);
    s.votes.Observe(frame, assoc);
    s.segmenter.Update(frame, assoc, &s.map);
    s.segmenter.Components(&s.map);
  }
  return s;
}

TEST(IncrementalSegmenterTest, SlotSplitCutsACounterRunIntoItsCabinets) {
  for (bool slot_split : {false, true}) {
    Scanned s = ScanCounterRun(slot_split);
    const ComponentGraph& graph = s.segmenter.Components(&s.map);
    const auto per_instance = LabelsPerInstance(s);
    std::vector<std::int32_t> labels;
    for (int cabinet = 1; cabinet <= 3; ++cabinet) {
      const auto [label, share] = MajorityLabel(per_instance.at(cabinet));
      labels.push_back(label);
      if (slot_split) {
        EXPECT_GE(share, 0.8) << "cabinet " << cabinet;
      }
    }
    const std::set<std::int32_t> distinct(labels.begin(), labels.end());
    if (!slot_split) {
      // The premise: without the cut, the far views merge the run.
      EXPECT_LT(distinct.size(), 3u);
      continue;
    }
    EXPECT_EQ(distinct.size(), 3u) << "cabinets share a label";
    // Each cabinet's label is a component of the graph.
    for (std::int32_t label : labels) EXPECT_NE(graph.Find(label), nullptr);
  }
}

}  // namespace
}  // namespace objscan::segmentation
