#include "objscan/io/scene_file.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::WriteText;

const char* kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";

TEST(SceneFileTest, YamlObjectsWallsAndFloor) {
  TempDir dir;
  WriteText(dir.File("models/cube.obj"), kCubeObj);
  WriteText(dir.File("room.yaml"),
            "name: test room\n"
            "walls:\n"
            "  - {min: [-2, -2, 0], max: [2, -1.9, 2.5]}\n"
            "objects:\n"
            "  - mesh: models/cube.obj\n"
            "    category: chair\n"
            "    pose: [1, 0, 0, 0, 0, 1.5707963267948966]\n"
            "    scale: [0.5, 1, 2]\n"
            "  - box: [0.8, 0.6, 0.75]\n"
            "    category: table\n"
            "    name: the_table\n"
            "    pose: [-1, 0.5, 0, 0, 0, 0]\n");
  const world::Scene scene = LoadSceneFile(dir.File("room.yaml"));
  EXPECT_EQ(scene.name(), "test room");
  ASSERT_EQ(scene.objects().size(), 4u);  // floor, wall, chair, table
  EXPECT_EQ(scene.objects()[0].category, world::Category::kFloor);
  EXPECT_EQ(scene.objects()[1].category, world::Category::kWall);
  const world::SceneObject& chair = scene.objects()[2];
  EXPECT_EQ(chair.category, world::Category::kChair);
  EXPECT_EQ(chair.model_name, "cube");
  EXPECT_EQ(chair.name, "cube_0");
  // Cube scaled to 0.5 x 1 x 2, turned by 90 deg about z and moved to x = 1.
  const geometry::Aabb3 cb = scene.ObjectBounds(chair);
  EXPECT_LT((cb.min_m - Eigen::Vector3d(0, 0, 0)).norm(), 1e-6) << cb.min_m.transpose();
  EXPECT_LT((cb.max_m - Eigen::Vector3d(1, 0.5, 2)).norm(), 1e-6) << cb.max_m.transpose();
  const world::SceneObject& table = scene.objects()[3];
  EXPECT_EQ(table.name, "the_table");
  const geometry::Aabb3 tb = scene.ObjectBounds(table);
  EXPECT_LT((tb.min_m - Eigen::Vector3d(-1.4, 0.2, 0)).norm(), 1e-6);
  EXPECT_LT((tb.max_m - Eigen::Vector3d(-0.6, 0.8, 0.75)).norm(), 1e-6);
  // The floor lies under the walls' extent plus the margin.
  const geometry::Aabb3 fb = scene.ObjectBounds(scene.objects()[0]);
  EXPECT_NEAR(fb.min_m.x(), -2.5, 1e-6);
  EXPECT_NEAR(fb.max_m.y(), -1.4, 1e-6);
}

TEST(SceneFileTest, JsonWithoutFloor) {
  TempDir dir;
  WriteText(dir.File("cube.obj"), kCubeObj);
  WriteText(dir.File("s.json"), R"({"floor": false, "objects": [{"mesh": "cube.obj", "scale": 2, "model": "m"}]})");
  const world::Scene scene = LoadSceneFile(dir.File("s.json"));
  ASSERT_EQ(scene.objects().size(), 1u);
  EXPECT_EQ(scene.objects()[0].category, world::Category::kOther);
  EXPECT_EQ(scene.objects()[0].model_name, "m");
  EXPECT_NEAR(scene.Bounds().max_m.z(), 2.0, 1e-6);
}

// One mesh file named by several objects is imported once, and each object still gets its own
// scale and axis: the shared import must not carry one object's transform to the next.
TEST(SceneFileTest, RepeatedMeshKeepsEachObjectsScaleAndAxis) {
  TempDir dir;
  WriteText(dir.File("m/box.obj"), "v 0 0 0\nv 1 0 0\nv 0 2 0\nv 0 0 3\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  WriteText(dir.File("r.yaml"),
            "floor: false\n"
            "objects:\n"
            "  - {mesh: m/box.obj, scale: 2}\n"
            "  - {mesh: ./m/box.obj}\n"
            "  - {mesh: m/box.obj, up_axis: y}\n"
            "  - {mesh: m/../m/box.obj}\n");
  const world::Scene scene = LoadSceneFile(dir.File("r.yaml"));
  ASSERT_EQ(scene.objects().size(), 4u);
  const auto extent = [&](std::size_t i) { return scene.ObjectBounds(scene.objects()[i]).max_m; };
  EXPECT_LT((extent(0) - Eigen::Vector3d(2, 4, 6)).norm(), 1e-6) << extent(0).transpose();
  EXPECT_LT((extent(1) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-6) << extent(1).transpose();
  // Y-up file: +Y (2) becomes +Z and +Z (3) becomes -Y.
  EXPECT_LT((extent(2) - Eigen::Vector3d(1, 0, 2)).norm(), 1e-6) << extent(2).transpose();
  EXPECT_NEAR(scene.ObjectBounds(scene.objects()[2]).min_m.y(), -3, 1e-6);
  EXPECT_LT((extent(3) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-6) << extent(3).transpose();
}

TEST(SceneFileTest, BadFilesNameTheKeyOrElement) {
  TempDir dir;
  WriteText(dir.File("cube.obj"), kCubeObj);
  ExpectInputError([&] { LoadSceneFile(dir.File("none.yaml")); }, "none.yaml");
  WriteText(dir.File("a.yaml"), "objects:\n  - mesh: cube.obj\n    rotation: [0, 0, 0]\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("a.yaml")); }, "a.yaml: objects[0]: unknown key 'rotation'");
  WriteText(dir.File("b.yaml"), "objects: []\nlights: 3\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("b.yaml")); }, "unknown key 'lights'");
  WriteText(dir.File("c.yaml"), "objects:\n  - mesh: cube.obj\n    category: throne\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("c.yaml")); }, "unknown category 'throne'");
  WriteText(dir.File("d.yaml"), "objects:\n  - mesh: missing.obj\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("d.yaml")); }, "missing.obj");
  WriteText(dir.File("e.yaml"), "objects:\n  - mesh: cube.obj\n    pose: [1, 2, 3]\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("e.yaml")); }, "objects[0].pose");
  WriteText(dir.File("f.yaml"), "objects: [ {mesh: cube.obj\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("f.yaml")); }, "f.yaml: malformed");
  WriteText(dir.File("g.yaml"), "objects:\n  - category: chair\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("g.yaml")); }, "needs mesh or box");
  WriteText(dir.File("h.yaml"), "objects:\n  - box: [1, 1, x]\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("h.yaml")); }, "objects[0].box[2]");
  WriteText(dir.File("i.yaml"), "walls:\n  - {min: [0, 0, 0], max: [1, 0, 1]}\nobjects: []\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("i.yaml")); }, "walls[0]");
  // A key that is a list (found by fuzzing: yaml-cpp's conversion exception escaped the loader).
  WriteText(dir.File("j.yaml"), "walls:\n  - { [m: 1]: 2, max: [3, 2, 2.5]}\nobjects: []\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("j.yaml")); }, "j.yaml: walls[0]: a key is not a name (a list or a mapping)");
  WriteText(dir.File("k.yaml"), "[a]: 1\nobjects: []\n");
  ExpectInputError([&] { LoadSceneFile(dir.File("k.yaml")); }, "k.yaml: top level: a key is not a name");
}

}  // namespace
}  // namespace objscan::io
