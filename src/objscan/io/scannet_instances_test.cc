#include "objscan/io/scannet_instances.h"

#include <gtest/gtest.h>

#include <set>

namespace objscan::io {
namespace {

// A labelled mesh built from boxes, each box one connected piece (its 8 corners, 12 triangles).
struct LabelledMesh {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<std::int32_t> labels;

  // Returns the index of the box's first vertex. Each face is split into a grid of `n` x `n` so that a
  // box has enough vertices to be an object (6 (n+1)^2 vertices, corners repeated per face and welded
  // within the face only: faces touch along their edges, which joins them through proximity).
  int AddBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, int label, int n = 4) {
    const int first = static_cast<int>(points.size());
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const int base = static_cast<int>(points.size());
        for (int j = 0; j <= n; ++j) {
          for (int i = 0; i <= n; ++i) {
            Eigen::Vector3f p;
            p[axis] = side ? hi[axis] : lo[axis];
            p[u] = lo[u] + (hi[u] - lo[u]) * static_cast<float>(i) / static_cast<float>(n);
            p[w] = lo[w] + (hi[w] - lo[w]) * static_cast<float>(j) / static_cast<float>(n);
            points.push_back(p);
            labels.push_back(label);
          }
        }
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            const int a = base + j * (n + 1) + i;
            triangles.emplace_back(a, a + 1, a + n + 2);
            triangles.emplace_back(a, a + n + 2, a + n + 1);
          }
        }
      }
    }
    return first;
  }

  InferredInstances Infer() const { return InferInstancesFromLabels(points, triangles, labels); }
};

constexpr int kChair = 5, kCabinet = 3, kTable = 7;

int InstanceOf(const InferredInstances& r, int vertex) { return r.vertex_instance[static_cast<std::size_t>(vertex)]; }

TEST(ScanNetInstancesTest, SeatOverItsBaseIsOneChairAndChairsSideBySideAreTwo) {
  LabelledMesh mesh;
  // Chair A: base up to 0.25 m, seat from 0.45 m (a 20 cm gap in one footprint).
  const int a_base = mesh.AddBox({0, 0, 0}, {0.4f, 0.4f, 0.25f}, kChair);
  const int a_seat = mesh.AddBox({0, 0, 0.45f}, {0.4f, 0.4f, 0.9f}, kChair);
  // Chair B 20 cm beside it, also in two pieces.
  const int b_base = mesh.AddBox({0.6f, 0, 0}, {1.0f, 0.4f, 0.25f}, kChair);
  const int b_seat = mesh.AddBox({0.6f, 0, 0.45f}, {1.0f, 0.4f, 0.9f}, kChair);
  const InferredInstances r = mesh.Infer();
  ASSERT_EQ(r.instance_label.size(), 2u);
  EXPECT_EQ(r.instance_label[0], kChair);
  EXPECT_EQ(InstanceOf(r, a_base), 0);
  EXPECT_EQ(InstanceOf(r, a_seat), 0);
  EXPECT_EQ(InstanceOf(r, b_base), 1);
  EXPECT_EQ(InstanceOf(r, b_seat), 1);
}

TEST(ScanNetInstancesTest, PiecesWithinAFewCentimetresJoinFartherOnesDoNot) {
  LabelledMesh mesh;
  // A table top and a leg 3 cm beside its edge (not under it: footprints apart), and a second table
  // 10 cm away.
  const int top = mesh.AddBox({0, 0, 0.7f}, {1.0f, 0.6f, 0.75f}, kTable);
  const int leg = mesh.AddBox({1.03f, 0, 0}, {1.08f, 0.05f, 0.7f}, kTable);
  const int other = mesh.AddBox({1.18f, 0, 0.7f}, {2.0f, 0.6f, 0.75f}, kTable);
  const InferredInstances r = mesh.Infer();
  ASSERT_EQ(r.instance_label.size(), 2u);
  EXPECT_EQ(InstanceOf(r, top), InstanceOf(r, leg));
  EXPECT_NE(InstanceOf(r, top), InstanceOf(r, other));
}

TEST(ScanNetInstancesTest, WallCabinetsOverBaseCabinetsAndOtherLabelsStayApart) {
  LabelledMesh mesh;
  const int base = mesh.AddBox({0, 0, 0}, {1.0f, 0.6f, 0.9f}, kCabinet);
  const int wall = mesh.AddBox({0, 0.2f, 1.45f}, {1.0f, 0.6f, 2.1f}, kCabinet);  // 55 cm above
  const int chair = mesh.AddBox({0, 0, 0.9f}, {0.4f, 0.4f, 1.2f}, kChair);       // touching, another label
  const InferredInstances r = mesh.Infer();
  ASSERT_EQ(r.instance_label.size(), 3u);
  const std::set<int> ids = {InstanceOf(r, base), InstanceOf(r, wall), InstanceOf(r, chair)};
  EXPECT_EQ(ids.size(), 3u);
}

TEST(ScanNetInstancesTest, SmallPiecesAloneAreNoiseButJoinAnObjectNearThem) {
  LabelledMesh mesh;
  const int chair = mesh.AddBox({0, 0, 0}, {0.4f, 0.4f, 0.9f}, kChair);
  const int sliver = mesh.AddBox({0.42f, 0, 0}, {0.44f, 0.02f, 0.02f}, kChair, 1);  // 24 vertices, 2 cm away
  const int lone = mesh.AddBox({3, 3, 0}, {3.02f, 3.02f, 0.02f}, kChair, 1);        // 24 vertices, alone
  mesh.labels.push_back(0);  // an unlabelled vertex
  mesh.points.emplace_back(5, 5, 0);
  const InferredInstances r = mesh.Infer();
  ASSERT_EQ(r.instance_label.size(), 1u);
  EXPECT_EQ(InstanceOf(r, chair), 0);
  EXPECT_EQ(InstanceOf(r, sliver), 0);
  EXPECT_EQ(InstanceOf(r, lone), -1);
  EXPECT_EQ(r.vertex_instance.back(), -1);
}

TEST(ScanNetInstancesTest, InstancesAreNumberedByTheirFirstVertex) {
  LabelledMesh mesh;
  mesh.AddBox({2, 0, 0}, {2.4f, 0.4f, 0.9f}, kTable);
  mesh.AddBox({0, 0, 0}, {0.4f, 0.4f, 0.9f}, kChair);
  const InferredInstances r = mesh.Infer();
  ASSERT_EQ(r.instance_label.size(), 2u);
  EXPECT_EQ(r.instance_label[0], kTable);
  EXPECT_EQ(r.instance_label[1], kChair);
}

}  // namespace
}  // namespace objscan::io
