#include "objscan/io/gazebo_world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::ByName;
using testing::ExpectBox;
using testing::WriteText;

// A unit cube [0,1]^3 as OBJ, scaled by `size` (so a folder's copy can be told apart).
std::string CubeObj(double size) {
  std::string s;
  for (int i = 0; i < 8; ++i) {
    s += "v " + std::to_string(size * (i & 1)) + " " + std::to_string(size * ((i >> 1) & 1)) + " " +
         std::to_string(size * ((i >> 2) & 1)) + "\n";
  }
  s += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return s;
}

std::string Model(const std::string& name, const std::string& pose, const std::string& link_pose,
                  const std::string& visual_pose, const std::string& geometry) {
  return "<model name='" + name + "'><static>1</static>" + (pose.empty() ? "" : "<pose>" + pose + "</pose>") +
         "<link name='link'>" + (link_pose.empty() ? "" : "<pose>" + link_pose + "</pose>") +
         "<visual name='visual'>" + (visual_pose.empty() ? "" : "<pose>" + visual_pose + "</pose>") + "<geometry>" +
         geometry + "</geometry></visual></link></model>\n";
}

std::string World(const std::string& body) {
  return "<?xml version='1.0'?>\n<sdf version='1.4'><world name='default'>\n"
         "<model name='ground_plane'><static>1</static><link name='link'><visual name='visual'><geometry>"
         "<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></visual></link></model>\n" +
         body + "</world></sdf>\n";
}

TEST(GazeboWorldTest, ComposesModelLinkAndVisualPosesForPrimitives) {
  TempDir dir;
  // Box 0.2 x 0.4 x 0.5; visual raised by 0.25, link shifted +0.5 in x, model at (1, 2, 0) turned by
  // 90 deg: in the world the box spans x in [1 - 0.2, 1 + 0.2], y in [2 + 0.5 - 0.1, 2 + 0.5 + 0.1].
  WriteText(dir.File("w.world"),
            World(Model("box_1", "1 2 0 0 0 1.5707963267948966", "0.5 0 0 0 0 0", "0 0 0.25 0 0 0",
                        "<box><size>0.2 0.4 0.5</size></box>") +
                  Model("cyl", "-1 0 0 0 0 0", "", "0 0 0.5 0 0 0",
                        "<cylinder><radius>0.1</radius><length>1</length></cylinder>") +
                  Model("ball", "0 -1 0.3 0 0 0", "", "", "<sphere><radius>0.3</radius></sphere>")));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  ASSERT_EQ(scene.objects().size(), 4u);  // floor + 3 models; ground_plane is replaced by the floor
  EXPECT_EQ(scene.objects()[0].category, world::Category::kFloor);
  const world::SceneObject* box = ByName(scene, "box_1");
  ASSERT_NE(box, nullptr);
  ExpectBox(scene.ObjectBounds(*box), {0.8, 2.4, 0.0}, {1.2, 2.6, 0.5});
  EXPECT_NEAR(box->T_world_object.translation().x(), 1.0, 1e-12);  // object frame = model frame
  const world::SceneObject* cyl = ByName(scene, "cyl");
  ASSERT_NE(cyl, nullptr);
  const geometry::Aabb3 cb = scene.ObjectBounds(*cyl);
  EXPECT_NEAR(cb.min_m.z(), 0.0, 1e-6);
  EXPECT_NEAR(cb.max_m.z(), 1.0, 1e-6);
  EXPECT_NEAR(cb.Center().x(), -1.0, 1e-6);
  EXPECT_NEAR(scene.ObjectBounds(*ByName(scene, "ball")).max_m.z(), 0.6, 1e-3);
  // Without walls the floor covers the furniture plus the margin, at z = 0.
  ExpectBox(scene.ObjectBounds(scene.objects()[0]), {-1.1 - kFloorMarginM, -1.3 - kFloorMarginM, 0},
            {1.2 + kFloorMarginM, 2.6 + kFloorMarginM, 0}, 1e-3);
  EXPECT_TRUE(scene.missing_meshes().empty());
}

TEST(GazeboWorldTest, MeshScaleAndStatePosesWin) {
  TempDir dir;
  WriteText(dir.File("cube/cube.obj"), CubeObj(1.0));
  // The <state> block (as saved by Gazebo) moves the model to (5, 0, 0); its link pose is in world.
  WriteText(dir.File("w.world"),
            World(Model("cube_0", "0 0 0 0 0 0", "", "",
                        "<mesh><uri>model://cube/cube.obj</uri><scale>2 1 0.5</scale></mesh>") +
                  "<state world_name='default'><model name='cube_0'><pose>5 0 0 0 0 0</pose>"
                  "<link name='link'><pose>5 0 1 0 0 0</pose></link></model></state>"));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  const world::SceneObject* cube = ByName(scene, "cube_0");
  ASSERT_NE(cube, nullptr);
  ExpectBox(scene.ObjectBounds(*cube), {5, 0, 1}, {7, 1, 1.5});
  EXPECT_EQ(cube->model_name, "cube");
}

TEST(GazeboWorldTest, ModelUrisResolveWorldFolderFirstThenModelPathThenEnvironment) {
  TempDir dir;
  WriteText(dir.File("scene/a/a.obj"), CubeObj(1.0));     // world folder: wins for 'a'
  WriteText(dir.File("lib1/a/a.obj"), CubeObj(2.0));
  WriteText(dir.File("lib1/b/b.obj"), CubeObj(2.0));      // model path: wins for 'b'
  WriteText(dir.File("lib2/b/b.obj"), CubeObj(3.0));
  WriteText(dir.File("lib2/c/c.obj"), CubeObj(3.0));      // $OBJSCAN_MODEL_PATH: wins for 'c'
  WriteText(dir.File("lib3/c/c.obj"), CubeObj(4.0));
  WriteText(dir.File("lib3/d/d.obj"), CubeObj(4.0));      // $GAZEBO_MODEL_PATH: last
  std::string body;
  for (const char* id : {"a", "b", "c", "d"}) {
    body += Model(std::string(id) + "_0", "", "", "", "<mesh><uri>model://" + std::string(id) + "/" + id + ".obj</uri></mesh>");
  }
  WriteText(dir.File("scene/w.world"), World(body));
  SceneLoadOptions options;
  options.model_path = dir.File("empty") + ":" + dir.File("lib1");
  const world::Scene scene = [&] {
    const testing::ScopedEnv objscan_path("OBJSCAN_MODEL_PATH", dir.File("nowhere") + ":" + dir.File("lib2"));
    const testing::ScopedEnv gazebo_path("GAZEBO_MODEL_PATH", dir.File("lib3"));
    return LoadGazeboWorld(dir.File("scene/w.world"), options);
  }();
  const double expected[] = {1.0, 2.0, 3.0, 4.0};
  const char* names[] = {"a_0", "b_0", "c_0", "d_0"};
  for (int i = 0; i < 4; ++i) {
    const world::SceneObject* o = ByName(scene, names[i]);
    ASSERT_NE(o, nullptr) << names[i];
    EXPECT_NEAR(scene.ObjectBounds(*o).Size().x(), expected[i], 1e-5) << names[i];
  }
}

TEST(GazeboWorldTest, UnresolvedMeshFailsOrIsListedWithAllowMissing) {
  TempDir dir;
  WriteText(dir.File("ok/ok.obj"), CubeObj(1.0));
  WriteText(dir.File("room.world"),
            World(Model("403_0", "", "", "", "<mesh><uri>model://403/403.dae</uri></mesh>") +
                  Model("ok_0", "", "", "", "<mesh><uri>model://ok/ok.obj</uri></mesh>")));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("room.world"), SceneLoadOptions()); },
                   "room.world: model '403_0'");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("room.world"), SceneLoadOptions()); },
                   "cannot resolve <mesh><uri> model://403/403.dae");
  SceneLoadOptions options;
  options.allow_missing = true;
  const world::Scene scene = LoadGazeboWorld(dir.File("room.world"), options);
  ASSERT_EQ(scene.missing_meshes().size(), 1u);
  EXPECT_NE(scene.missing_meshes()[0].find("model://403/403.dae"), std::string::npos);
  EXPECT_EQ(ByName(scene, "403_0"), nullptr);
  EXPECT_NE(ByName(scene, "ok_0"), nullptr);
  EXPECT_EQ(scene.objects().size(), 2u);  // floor + ok_0
}

TEST(GazeboWorldTest, BadInputNamesFileAndElement) {
  TempDir dir;
  ExpectInputError([&] { LoadGazeboWorld(dir.File("none.world"), SceneLoadOptions()); }, "none.world");
  WriteText(dir.File("broken.world"), "<sdf><world><model name='a'></world></sdf>");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("broken.world"), SceneLoadOptions()); }, "broken.world: malformed XML");
  WriteText(dir.File("pose.world"), World(Model("m", "1 2 three 0 0 0", "", "", "<box><size>1 1 1</size></box>")));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("pose.world"), SceneLoadOptions()); }, "pose.world: model 'm'");
  WriteText(dir.File("bad/bad.dae"), "<COLLADA version='1.4.1'><asset>");
  WriteText(dir.File("mesh.world"), World(Model("bad_0", "", "", "", "<mesh><uri>model://bad/bad.dae</uri></mesh>")));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("mesh.world"), SceneLoadOptions()); }, "bad.dae");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("mesh.world"), SceneLoadOptions()); }, "model 'bad_0'");
  WriteText(dir.File("flat/flat.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  WriteText(dir.File("empty.world"), World(Model("flat_0", "", "", "", "<mesh><uri>model://flat/flat.obj</uri></mesh>")));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("empty.world"), SceneLoadOptions()); }, "no triangles");
  WriteText(dir.File("scale.world"),
            World(Model("s", "", "", "", "<mesh><uri>model://flat/flat.obj</uri><scale>1 1</scale></mesh>")));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("scale.world"), SceneLoadOptions()); }, "<scale>");
  WriteText(dir.File("root.world"), "<world/>");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("root.world"), SceneLoadOptions()); }, "root.world");
}

TEST(GazeboWorldTest, CategoriesFromSuncgMappingAndModelNames) {
  TempDir dir;
  // ModelCategoryMapping.csv sits above the scene folder, as in the OASC layout.
  WriteText(dir.File("ModelCategoryMapping.csv"),
            "index,model_id,fine_grained_class,coarse_grained_class,empty_struct_obj,nyuv2_40class,wnsynsetid,wnsynsetkey\n"
            "1,m1,armchair,chair,2,chair,n1,x\n"
            "2,m2,new_kind_of_lamp,indoor_lamp,2,lamp,n2,y\n"
            "3,m3,never_seen,never_seen,2,never_seen,n3,z\n");
  WriteText(dir.File("house/room/m1/m1.obj"), CubeObj(1.0));
  WriteText(dir.File("house/room/m2/m2.obj"), CubeObj(1.0));
  WriteText(dir.File("house/room/m3/m3.obj"), CubeObj(1.0));
  WriteText(dir.File("house/room/room.world"),
            World(Model("m1_0", "", "", "", "<mesh><uri>model://m1/m1.obj</uri></mesh>") +
                  Model("m2_0", "", "", "", "<mesh><uri>model://m2/m2.obj</uri></mesh>") +
                  Model("m3_0", "", "", "", "<mesh><uri>model://m3/m3.obj</uri></mesh>") +
                  Model("sofa_2", "", "", "", "<box><size>1 1 1</size></box>") +
                  Model("thing", "", "", "", "<box><size>1 1 1</size></box>")));
  const world::Scene scene = LoadGazeboWorld(dir.File("house/room/room.world"), SceneLoadOptions());
  EXPECT_EQ(ByName(scene, "m1_0")->category, world::Category::kChair);  // fine class row
  EXPECT_EQ(ByName(scene, "m2_0")->category, world::Category::kLamp);   // coarse class fallback
  EXPECT_EQ(ByName(scene, "m3_0")->category, world::Category::kOther);  // the '*' row
  EXPECT_EQ(ByName(scene, "sofa_2")->category, world::Category::kSofa);  // not in the mapping: by name
  EXPECT_EQ(ByName(scene, "thing")->category, world::Category::kOther);
  EXPECT_EQ(ByName(scene, "m1_0")->model_name, "m1");

  // A table naming a category objscan does not know is rejected with file and line.
  // The 'thing' is in no map: `other`, and listed.
  ASSERT_EQ(scene.unmapped_models().size(), 1u);
  EXPECT_EQ(scene.unmapped_models()[0], "thing (thing)");

  // A table naming a category objscan does not know is rejected with file and line; the table is
  // named by a category map's suncg rule.
  WriteText(dir.File("bad_table.csv"), "suncg_class,category\narmchair,throne\n");
  WriteText(dir.File("bad_map.yaml"), "rules:\n  - {suncg: bad_table.csv}\n");
  SceneLoadOptions options;
  options.category_map = dir.File("bad_map.yaml");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("house/room/room.world"), options); }, "bad_table.csv:2");
  // Without a '*' row an unmapped class is an error naming the model.
  WriteText(dir.File("small_table.csv"), "suncg_class,category\narmchair,chair\nlamp,lamp\n");
  WriteText(dir.File("small_map.yaml"), "rules:\n  - {suncg: small_table.csv}\n");
  options.category_map = dir.File("small_map.yaml");
  ExpectInputError([&] { LoadGazeboWorld(dir.File("house/room/room.world"), options); }, "model 'm3_0'");
}

TEST(GazeboWorldTest, WallsAreRecognisedAndSizeTheFloor) {
  TempDir dir;
  WriteText(dir.File("lib/drc_practice_valve_wall/meshes/wall.obj"), CubeObj(1.0));
  WriteText(dir.File("w.world"),
            World(Model("valve_wall", "0 0 0 0 0 0", "", "",
                        "<mesh><uri>model://drc_practice_valve_wall/meshes/wall.obj</uri><scale>4 0.01 2.4</scale></mesh>") +
                  Model("valve_wall_0", "0 3 0 0 0 0", "", "",
                        "<mesh><uri>model://drc_practice_valve_wall/meshes/wall.obj</uri><scale>4 0.01 2.4</scale></mesh>") +
                  Model("table_1", "1 1 0 0 0 0", "", "0 0 0.4 0 0 0", "<box><size>1 1 0.8</size></box>")));
  SceneLoadOptions options;
  options.model_path = dir.File("lib");
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), options);
  EXPECT_EQ(ByName(scene, "valve_wall")->category, world::Category::kWall);
  EXPECT_EQ(ByName(scene, "valve_wall_0")->category, world::Category::kWall);
  EXPECT_EQ(ByName(scene, "table_1")->category, world::Category::kTable);
  EXPECT_EQ(scene.NumFurniture(), 1u);
  ExpectBox(scene.ObjectBounds(scene.objects()[0]), {-kFloorMarginM, -kFloorMarginM, 0},
            {4 + kFloorMarginM, 3.01 + kFloorMarginM, 0}, 1e-4);
}

}  // namespace
}  // namespace objscan::io
