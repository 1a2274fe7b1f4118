#include "objscan/io/scene_spec.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::WriteText;

TEST(SceneSpecTest, MeshFileBecomesOneObjectOnAFloor) {
  TempDir dir;
  WriteText(dir.File("tri.obj"), "v 0 0 0.5\nv 1 0 0.5\nv 0 1 1.5\nf 1 2 3\n");
  const world::Scene scene = LoadScene(dir.File("tri.obj"), SceneLoadOptions());
  ASSERT_EQ(scene.objects().size(), 2u);
  EXPECT_EQ(scene.objects()[0].category, world::Category::kFloor);
  EXPECT_EQ(scene.objects()[1].category, world::Category::kOther);
  EXPECT_EQ(scene.objects()[1].model_name, "tri");
  // The floor is under the mesh's lowest point.
  EXPECT_NEAR(scene.ObjectBounds(scene.objects()[0]).max_m.z(), 0.5, 1e-6);
}

TEST(SceneSpecTest, DispatchesWorldsAndSceneFiles) {
  TempDir dir;
  WriteText(dir.File("w.world"),
            "<sdf version='1.4'><world name='default'><model name='chair_1'><link name='l'><visual name='v'>"
            "<geometry><box><size>1 1 1</size></box></geometry></visual></link></model></world></sdf>");
  EXPECT_EQ(LoadScene(dir.File("w.world"), SceneLoadOptions()).NumFurniture(), 1u);
  WriteText(dir.File("s.yaml"), "objects:\n  - box: [1, 1, 1]\n    category: bed\n");
  const world::Scene s = LoadScene(dir.File("s.yaml"), SceneLoadOptions());
  ASSERT_EQ(s.NumFurniture(), 1u);
  EXPECT_EQ(s.objects().back().category, world::Category::kBed);
}

TEST(SceneSpecTest, ProceduralSpecs) {
  const world::Scene a = LoadScene("procedural:bedroom:3", SceneLoadOptions());
  const world::Scene b = LoadScene("procedural:bedroom:3", SceneLoadOptions());
  EXPECT_GT(a.NumFurniture(), 0u);
  ASSERT_EQ(a.objects().size(), b.objects().size());
  for (std::size_t i = 0; i < a.objects().size(); ++i) {
    EXPECT_EQ(a.objects()[i].category, b.objects()[i].category);
    EXPECT_EQ(a.objects()[i].mesh.vertices, b.objects()[i].mesh.vertices);
  }
  ExpectInputError([] { LoadScene("procedural:castle:1", SceneLoadOptions()); }, "castle");
  ExpectInputError([] { LoadScene("procedural:bedroom:x", SceneLoadOptions()); }, "seed 'x'");
  ExpectInputError([] { LoadScene("procedural:bedroom", SceneLoadOptions()); }, "procedural:CATEGORY:SEED");
}

TEST(SceneSpecTest, ScenesFarFromTheOriginAreRefusedInEveryFormat) {
  TempDir dir;
  // Finite coordinates, but beyond what the map's integer voxel grids can hold.
  WriteText(dir.File("w.world"),
            "<sdf version='1.4'><world name='default'><model name='chair_1'><pose>3e9 0 0 0 0 0</pose><link name='l'>"
            "<visual name='v'><geometry><box><size>1 1 1</size></box></geometry></visual></link></model></world></sdf>");
  ExpectInputError([&] { LoadScene(dir.File("w.world"), SceneLoadOptions()); },
                   "w.world: object 'chair_1' lies beyond 10000 m of the origin");
  WriteText(dir.File("s.yaml"), "objects:\n  - box: [1, 1, 1]\n    category: bed\n    pose: [0, -2e4, 0, 0, 0, 0]\n");
  ExpectInputError([&] { LoadScene(dir.File("s.yaml"), SceneLoadOptions()); }, "s.yaml: object");
  WriteText(dir.File("far.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 1e5\nf 1 2 3\n");
  ExpectInputError([&] { LoadScene(dir.File("far.obj"), SceneLoadOptions()); }, "beyond 10000 m of the origin");
  // A house-sized scene away from the origin is fine.
  WriteText(dir.File("near.yaml"), "objects:\n  - box: [1, 1, 1]\n    category: bed\n    pose: [9000, 0, 0, 0, 0, 0]\n");
  EXPECT_EQ(LoadScene(dir.File("near.yaml"), SceneLoadOptions()).NumFurniture(), 1u);
}

TEST(SceneSpecTest, UnknownSpecsAreRejected) {
  TempDir dir;
  ExpectInputError([&] { LoadScene(dir.File("nothing.world"), SceneLoadOptions()); }, "nothing.world");
  WriteText(dir.File("notes.txt"), "hello");
  ExpectInputError([&] { LoadScene(dir.File("notes.txt"), SceneLoadOptions()); }, "unsupported scene format");
}

}  // namespace
}  // namespace objscan::io
