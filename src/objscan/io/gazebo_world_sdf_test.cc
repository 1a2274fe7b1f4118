// SDF features of the Gazebo world loader, each on a small world the test writes: <include> at any
// depth, nested models, <pose relative_to>, <frame>, placement frames, <static>, <scale>, upper-case
// mesh extensions, file:// and model:// URIs, <state> poses of nested models, and the malformed
// cases (each one line naming the file and element).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "objscan/common/error.h"
#include "objscan/io/gazebo_world.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::ByName;
using testing::ScopedEnv;
using testing::ExpectBox;
using testing::WriteText;

std::string World(const std::string& body, const std::string& version = "1.7") {
  return "<?xml version='1.0'?>\n<sdf version='" + version + "'><world name='default'>\n" + body + "</world></sdf>\n";
}

// A model whose one link shows a box of `size` at the link origin.
std::string BoxModel(const std::string& name, const std::string& pose, const std::string& size = "0.2 0.2 0.2") {
  return "<model name='" + name + "'>" + pose + "<link name='link'><visual name='v'><geometry><box><size>" + size +
         "</size></box></geometry></visual></link></model>\n";
}

// A COLLADA cube of 100 x 100 x 100 units in centimetres (as the AWS models are): 1 m in the world.
std::string ColladaCube() {
  std::string positions;
  for (int i = 0; i < 8; ++i) {
    positions += std::to_string(100 * (i & 1)) + " " + std::to_string(100 * ((i >> 1) & 1)) + " " +
                 std::to_string(100 * ((i >> 2) & 1)) + " ";
  }
  return "<?xml version='1.0' encoding='utf-8'?>\n"
         "<COLLADA xmlns='http://www.collada.org/2005/11/COLLADASchema' version='1.4.1'>"
         "<asset><unit meter='0.01' name='centimeter'/><up_axis>Z_UP</up_axis></asset>"
         "<library_geometries><geometry id='g' name='g'><mesh>"
         "<source id='g-pos'><float_array id='g-pos-array' count='24'>" + positions + "</float_array>"
         "<technique_common><accessor source='#g-pos-array' count='8' stride='3'><param name='X' type='float'/>"
         "<param name='Y' type='float'/><param name='Z' type='float'/></accessor></technique_common></source>"
         "<vertices id='g-vtx'><input semantic='POSITION' source='#g-pos'/></vertices>"
         "<triangles count='12'><input semantic='VERTEX' source='#g-vtx' offset='0'/>"
         "<p>0 2 3 0 3 1 4 5 7 4 7 6 0 1 5 0 5 4 2 6 7 2 7 3 0 4 6 0 6 2 1 3 7 1 7 5</p></triangles>"
         "</mesh></geometry></library_geometries>"
         "<library_visual_scenes><visual_scene id='s'><node id='n'><instance_geometry url='#g'/></node>"
         "</visual_scene></library_visual_scenes><scene><instance_visual_scene url='#s'/></scene></COLLADA>\n";
}

// A model folder as the AWS small house has them: model.config naming model.sdf, a mesh with an
// upper-case extension.
void WriteAwsStyleModel(const std::string& models_dir, const std::string& name, const std::string& model_pose = "") {
  WriteText(models_dir + "/" + name + "/model.config",
            "<?xml version='1.0'?><model><name>" + name + "</name><sdf version='1.6'>model.sdf</sdf></model>\n");
  WriteText(models_dir + "/" + name + "/model.sdf",
            "<?xml version='1.0'?><sdf version='1.6'><model name='" + name + "'>" + model_pose +
                "<link name='link'><collision name='collision'><geometry><box><size>5 5 5</size></box></geometry>"
                "</collision><visual name='visual'><geometry><mesh><uri>model://" + name + "/meshes/" + name +
                "_visual.DAE</uri></mesh></geometry></visual></link><static>1</static></model></sdf>\n");
  WriteText(models_dir + "/" + name + "/meshes/" + name + "_visual.DAE", ColladaCube());
}

// A model folder as the AWS RoboMaker bookstore has them: its mesh named by a file:// URI relative to
// the package root (file://models/NAME/meshes/NAME_visual.DAE), which Gazebo finds through
// GAZEBO_RESOURCE_PATH. The mesh is written below `mesh_root` (the package root, usually the parent
// of `models_dir`).
void WriteBookstoreStyleModel(const std::string& models_dir, const std::string& name, const std::string& mesh_root) {
  WriteText(models_dir + "/" + name + "/model.config",
            "<?xml version='1.0'?><model><name>" + name + "</name><sdf version='1.6'>model.sdf</sdf></model>\n");
  WriteText(models_dir + "/" + name + "/model.sdf",
            "<?xml version=\"1.0\" ?>\n<sdf version=\"1.6\">\n  <model name=\"" + name +
                "\">\n    <link name=\"link\">\n      <visual name=\"visual\">\n        <geometry>\n          <mesh>\n"
                "            <uri>file://models/" + name + "/meshes/" + name + "_visual.DAE</uri>\n"
                "          </mesh>\n        </geometry>\n      </visual>\n    </link>\n    <static>1</static>\n"
                "  </model>\n</sdf>\n");
  WriteText(mesh_root + "/models/" + name + "/meshes/" + name + "_visual.DAE", ColladaCube());
}

// The bookstore's world: two models wrapping an include (<pose frame=''> after it), one bare include.
std::string BookstoreWorld() {
  return World("<model name='ground_plane'><static>1</static><link name='link'><visual name='visual'><geometry>"
               "<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></visual></link></model>\n"
               "<model name='AirConditionerC_01_001'><include><uri>model://aws_robomaker_retail_AirConditionerC_01"
               "</uri></include><pose frame=''>7 1 2 0 0 0</pose></model>\n"
               "<model name='BookE_01_001'><include><uri>model://aws_robomaker_retail_BookE_01</uri></include>"
               "<pose frame=''>5 -2 0.9 0 0 0</pose></model>\n"
               "<include><uri>model://aws_robomaker_retail_BookE_01</uri><name>BookE_01_002</name>"
               "<pose>-5 3 0.9 0 0 0</pose></include>\n",
               "1.6");
}

// No Gazebo path variable of the machine running the tests may change what they find.
struct CleanGazeboEnv {
  ScopedEnv resource{"GAZEBO_RESOURCE_PATH", std::nullopt};
  ScopedEnv model{"GAZEBO_MODEL_PATH", std::nullopt};
  ScopedEnv objscan{"OBJSCAN_MODEL_PATH", std::nullopt};
};

// The world's bounds of model `name` (which must exist).
geometry::Aabb3 BoundsOf(const world::Scene& scene, const std::string& name) {
  const world::SceneObject* o = ByName(scene, name);
  if (o == nullptr) {
    ADD_FAILURE() << "no object '" << name << "'";
    return {};
  }
  return scene.ObjectBounds(*o);
}

TEST(GazeboSdfTest, IncludeNestedInsideAModelAsTheAwsHouseDoes) {
  TempDir dir;
  WriteAwsStyleModel(dir.File("models"), "aws_robomaker_residential_Bed_01");
  // The wrapper model's pose places the included model (whose own pose is identity).
  WriteText(dir.File("worlds/house.world"),
            World("<model name='Bed_01_001'><static>true</static><include>"
                  "<uri>model://aws_robomaker_residential_Bed_01</uri></include>"
                  "<pose frame=''>2 3 0.5 0 -0 1.5707963267948966</pose></model>\n",
                  "1.6"));
  SceneLoadOptions options;
  options.model_path = dir.File("models");
  const world::Scene scene = LoadGazeboWorld(dir.File("worlds/house.world"), options);
  ASSERT_EQ(scene.objects().size(), 2u);  // floor + the bed
  const world::SceneObject* bed = ByName(scene, "Bed_01_001");
  ASSERT_NE(bed, nullptr);
  // The 1 m cube (centimetre COLLADA, upper-case .DAE) turned by 90 deg about z at (2, 3, 0.5).
  ExpectBox(scene.ObjectBounds(*bed), {1, 3, 0.5}, {2, 4, 1.5});
  EXPECT_EQ(bed->model_name, "aws_robomaker_residential_Bed_01");
  EXPECT_EQ(bed->category, world::Category::kBed);  // from the default map's AWS rules
  EXPECT_NEAR(bed->T_world_object.translation().x(), 2.0, 1e-12);
  EXPECT_TRUE(scene.unmapped_models().empty());
}

TEST(GazeboSdfTest, IncludeInsideAnIncludedModelAndIncludeOverrides) {
  TempDir dir;
  WriteAwsStyleModel(dir.File("models"), "aws_robomaker_residential_ChairA_01", "<pose>0 0 1 0 0 0</pose>");
  // A model that itself includes the chair twice, under new names and poses.
  WriteText(dir.File("models/pair/model.sdf"),
            "<?xml version='1.0'?><sdf version='1.7'><model name='pair'>"
            "<include><uri>model://aws_robomaker_residential_ChairA_01</uri><name>left</name>"
            "<pose>-2 0 0 0 0 0</pose><static>true</static></include>"
            "<include><uri>model://aws_robomaker_residential_ChairA_01</uri><name>right</name></include>"
            "</model></sdf>\n");
  WriteText(dir.File("w.world"),
            World("<include><uri>model://pair</uri><name>chairs</name><pose>10 0 0 0 0 0</pose></include>\n"));
  SceneLoadOptions options;
  options.model_path = dir.File("models");
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), options);
  ASSERT_EQ(scene.objects().size(), 2u);
  // left: the include pose replaces the chair's own pose; right keeps its model pose (z = 1).
  ExpectBox(BoundsOf(scene, "chairs"), {8, 0, 0}, {11, 1, 2});
  EXPECT_EQ(ByName(scene, "chairs")->category, world::Category::kChair);
}

TEST(GazeboSdfTest, NestedModelsComposeTheirPoses) {
  TempDir dir;
  WriteText(dir.File("w.world"),
            World("<model name='table_1'><pose>1 0 0 0 0 1.5707963267948966</pose>"
                  "<model name='top'><pose>0 2 0 0 0 0</pose>" +
                  BoxModel("leg", "<pose>0 0 0.5 0 0 0</pose>", "0.2 0.2 1") + "</model></model>\n"));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  // (0, 2, 0.5) in the table frame, turned by 90 deg: (-2, 0, 0.5) + (1, 0, 0).
  ExpectBox(BoundsOf(scene, "table_1"), {-1.1, -0.1, 0}, {-0.9, 0.1, 1});
  EXPECT_EQ(ByName(scene, "table_1")->category, world::Category::kTable);  // named after a category
}

TEST(GazeboSdfTest, PoseRelativeToFramesLinksNestedLinksAndOtherModels) {
  TempDir dir;
  WriteText(
      dir.File("w.world"),
      World("<frame name='corner'><pose>5 5 0 0 0 0</pose></frame>\n"
            "<model name='a'><pose relative_to='corner'>1 0 0 0 0 0</pose>"
            "<frame name='f' attached_to='base'><pose>0 0 1 0 0 0</pose></frame>"
            "<link name='base'><pose>0 1 0 0 0 0</pose></link>"
            // link2 relative to frame f (itself relative to link base): (0, 1, 1) + (1, 0, 0)
            "<link name='link2'><pose relative_to='f'>1 0 0 0 0 0</pose>"
            "<visual name='v'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></visual></link>"
            // a visual placed relative to another frame than its link
            "<link name='link3'><visual name='v'><pose relative_to='inner::l'>0 0 0 0 0 0</pose>"
            "<geometry><box><size>0.2 0.2 0.2</size></box></geometry></visual></link>"
            "<model name='inner'><pose relative_to='base'>0 0 2 0 0 0</pose><link name='l'>"
            "<pose>0 0 1 0 0 0</pose></link></model>"
            "</model>\n" +
            BoxModel("b", "<pose relative_to='a'>0 0 0 0 0 0</pose>")));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  // Model a at (6, 5, 0); link2 box centred at a + (1, 1, 1); link3 box at a + base (0, 1, 0) + (0, 0, 3).
  const geometry::Aabb3 a = BoundsOf(scene, "a");
  ExpectBox(a, {5.9, 5.9, 0.9}, {7.1, 6.1, 3.1});
  ExpectBox(BoundsOf(scene, "b"), {5.9, 4.9, -0.1}, {6.1, 5.1, 0.1});
}

TEST(GazeboSdfTest, PlacementFramePlacesTheNamedFrame) {
  TempDir dir;
  WriteText(dir.File("models/shelf/model.sdf"),
            "<?xml version='1.0'?><sdf version='1.8'><model name='shelf'>"
            "<frame name='bottom'><pose>0 0 -0.5 0 0 0</pose></frame>"
            "<link name='body'><visual name='v'><geometry><box><size>1 1 1</size></box></geometry></visual>"
                "</link></model></sdf>\n");
  WriteText(dir.File("w.world"), World("<include><uri>model://shelf</uri><placement_frame>bottom</placement_frame>"
                                       "<pose>3 0 0 0 0 0</pose></include>\n"));
  SceneLoadOptions options;
  options.model_path = dir.File("models");
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), options);
  // The shelf's bottom frame is put at (3, 0, 0): the cube spans z in [0, 1].
  ExpectBox(BoundsOf(scene, "shelf"), {2.5, -0.5, 0}, {3.5, 0.5, 1});
}

TEST(GazeboSdfTest, BookstoreFileUrisResolveFromTheParentOfTheModelPath) {
  CleanGazeboEnv env;
  TempDir dir;
  const std::string pkg = dir.File("aws-robomaker-bookstore-world");
  for (const char* name : {"aws_robomaker_retail_AirConditionerC_01", "aws_robomaker_retail_BookE_01"}) {
    WriteBookstoreStyleModel(pkg + "/models", name, pkg);
  }
  WriteText(pkg + "/worlds/bookstore.world", BookstoreWorld());
  SceneLoadOptions options;
  options.model_path = pkg + "/models";  // as the launch file sets GAZEBO_MODEL_PATH
  const world::Scene scene = LoadGazeboWorld(pkg + "/worlds/bookstore.world", options);
  EXPECT_TRUE(scene.missing_meshes().empty());
  ASSERT_EQ(scene.objects().size(), 4u);  // the floor and three models
  ExpectBox(BoundsOf(scene, "AirConditionerC_01_001"), {7, 1, 2}, {8, 2, 3});
  ExpectBox(BoundsOf(scene, "BookE_01_001"), {5, -2, 0.9}, {6, -1, 1.9});
  ExpectBox(BoundsOf(scene, "BookE_01_002"), {-5, 3, 0.9}, {-4, 4, 1.9});
  // The model path given twice over (repeated --model-path), or through $GAZEBO_MODEL_PATH: the same.
  options.model_path = dir.File("nowhere") + ":" + pkg + "/models";
  EXPECT_EQ(LoadGazeboWorld(pkg + "/worlds/bookstore.world", options).objects().size(), 4u);
  ScopedEnv model_path("GAZEBO_MODEL_PATH", pkg + "/models");
  EXPECT_EQ(LoadGazeboWorld(pkg + "/worlds/bookstore.world", SceneLoadOptions()).objects().size(), 4u);
}

TEST(GazeboSdfTest, BookstoreFileUrisResolveThroughResourcePathAndPackageRoot) {
  CleanGazeboEnv env;
  TempDir dir;
  // The model folders (model.sdf) in one place, the meshes under another root: only that root's rule
  // can find them.
  const auto write = [&](const std::string& mesh_root) {
    for (const char* name : {"aws_robomaker_retail_AirConditionerC_01", "aws_robomaker_retail_BookE_01"}) {
      WriteBookstoreStyleModel(dir.File("sdf/models"), name, mesh_root);
    }
  };
  SceneLoadOptions options;
  options.model_path = dir.File("sdf/models");
  {
    // $GAZEBO_RESOURCE_PATH (colon-separated, searched in order).
    write(dir.File("resources"));
    WriteText(dir.File("plain/bookstore.world"), BookstoreWorld());
    ScopedEnv resource("GAZEBO_RESOURCE_PATH", dir.File("empty") + ":" + dir.File("resources"));
    EXPECT_EQ(LoadGazeboWorld(dir.File("plain/bookstore.world"), options).objects().size(), 4u);
  }
  {
    // The world's package root: the nearest folder above the world holding a package.xml.
    write(dir.File("pkg"));
    WriteText(dir.File("pkg/package.xml"), "<package format='2'><name>bookstore</name></package>\n");
    WriteText(dir.File("pkg/worlds/deeper/bookstore.world"), BookstoreWorld());
    EXPECT_EQ(LoadGazeboWorld(dir.File("pkg/worlds/deeper/bookstore.world"), options).objects().size(), 4u);
  }
  {
    // Without a package.xml: the parent of the world's folder (PKG of PKG/worlds/x.world).
    write(dir.File("nopkg"));
    WriteText(dir.File("nopkg/worlds/bookstore.world"), BookstoreWorld());
    EXPECT_EQ(LoadGazeboWorld(dir.File("nopkg/worlds/bookstore.world"), options).objects().size(), 4u);
  }
}

TEST(GazeboSdfTest, UnresolvableUriNamesTheFileTheElementAndEveryFolderSearched) {
  CleanGazeboEnv env;
  TempDir dir;
  const std::string pkg = dir.File("pkg");
  WriteBookstoreStyleModel(pkg + "/models", "aws_robomaker_retail_AirConditionerC_01", dir.File("elsewhere"));
  WriteBookstoreStyleModel(pkg + "/models", "aws_robomaker_retail_BookE_01", dir.File("elsewhere"));
  WriteText(pkg + "/worlds/bookstore.world", BookstoreWorld());
  ScopedEnv resource("GAZEBO_RESOURCE_PATH", dir.File("res"));
  SceneLoadOptions options;
  options.model_path = pkg + "/models";
  const std::string world = pkg + "/worlds/bookstore.world";
  const std::string model_sdf = pkg + "/models/aws_robomaker_retail_AirConditionerC_01/model.sdf";
  for (const std::string& needle :
       {world + ": model 'AirConditionerC_01_001' visual 'visual': cannot resolve <mesh><uri> "
                "file://models/aws_robomaker_retail_AirConditionerC_01/meshes/aws_robomaker_retail_AirConditionerC_01_"
                "visual.DAE (in " + model_sdf + ", line 8); searched " + pkg +
                "/models/aws_robomaker_retail_AirConditionerC_01, " + dir.File("res") + ", " + pkg + " (the naming"}) {
    ExpectInputError([&] { LoadGazeboWorld(world, options); }, needle);
  }
  // An include: the model path's folders, in order.
  WriteText(dir.File("w.world"), World("<include><uri>model://nowhere</uri></include>\n"));
  ExpectInputError([&] { LoadGazeboWorld(dir.File("w.world"), options); },
                   "cannot resolve <include><uri> model://nowhere; searched " + dir.path().string() + ", " + pkg +
                       "/models (the world's folder, --model-path");
}

TEST(GazeboSdfTest, AllowMissingFailsWhenFewerThanHalfTheModelsAreLeft) {
  CleanGazeboEnv env;
  TempDir dir;
  const std::string pkg = dir.File("pkg");
  for (const char* name : {"aws_robomaker_retail_AirConditionerC_01", "aws_robomaker_retail_BookE_01"}) {
    WriteBookstoreStyleModel(pkg + "/models", name, dir.File("elsewhere"));
  }
  WriteText(pkg + "/worlds/bookstore.world", BookstoreWorld());
  SceneLoadOptions options;
  options.model_path = pkg + "/models";
  options.allow_missing = true;
  const std::string world = pkg + "/worlds/bookstore.world";
  ExpectInputError([&] { LoadGazeboWorld(world, options); },
                   "bookstore.world: only 0 of 3 models could be loaded (3 meshes or includes missing; the first: ");
  ExpectInputError([&] { LoadGazeboWorld(world, options); }, "--allow-missing given twice");
  // Insisting loads the floor alone and lists every mesh it skipped.
  options.min_loaded_model_fraction = 0.0;
  const world::Scene scene = LoadGazeboWorld(world, options);
  EXPECT_EQ(scene.objects().size(), 1u);
  EXPECT_EQ(scene.missing_meshes().size(), 3u);
  // Half of them is enough: two of three models found.
  WriteBookstoreStyleModel(pkg + "/models", "aws_robomaker_retail_BookE_01", pkg);
  options.min_loaded_model_fraction = 0.5;
  const world::Scene most = LoadGazeboWorld(world, options);
  EXPECT_EQ(most.objects().size(), 3u);
  ASSERT_EQ(most.missing_meshes().size(), 1u);
  EXPECT_NE(most.missing_meshes()[0].find("AirConditionerC_01_001"), std::string::npos) << most.missing_meshes()[0];
}

TEST(GazeboSdfTest, FileUrisPlainPathsAndUpperCaseExtensions) {
  TempDir dir;
  WriteText(dir.File("meshes/CUBE.DAE"), ColladaCube());
  WriteText(dir.File("lib/m/model.sdf"),
            "<?xml version='1.0'?><sdf version='1.6'><model name='m'><link name='l'><visual name='v'><geometry>"
            "<mesh><uri>meshes/part.DAE</uri><scale>2 1 1</scale></mesh></geometry></visual></link></model></sdf>\n");
  WriteText(dir.File("lib/m/meshes/part.DAE"), ColladaCube());
  WriteText(dir.File("w.world"),
            World("<model name='abs'><link name='l'><visual name='v'><geometry><mesh><uri>file://" +
                  dir.File("meshes/CUBE.DAE") +
                  "</uri></mesh></geometry></visual></link></model>\n"
                  "<model name='rel'><pose>5 0 0 0 0 0</pose><link name='l'><visual name='v'><geometry><mesh>"
                  "<uri>meshes/CUBE.DAE</uri><scale>1 1 0.5</scale></mesh></geometry></visual></link></model>\n"
                  // an include by path: relative mesh URIs inside resolve from the included file's folder
                  "<include><uri>file://" +
                  dir.File("lib/m") + "</uri><name>inc</name><pose>0 5 0 0 0 0</pose></include>\n"));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  ExpectBox(BoundsOf(scene, "abs"), {0, 0, 0}, {1, 1, 1});
  ExpectBox(BoundsOf(scene, "rel"), {5, 0, 0}, {6, 1, 0.5});
  ExpectBox(BoundsOf(scene, "inc"), {0, 5, 0}, {2, 6, 1});
}

TEST(GazeboSdfTest, StatePosesOfIncludedAndNestedModelsWin) {
  TempDir dir;
  WriteText(dir.File("w.world"),
            World("<model name='outer'><pose>0 0 0 0 0 0</pose>" + BoxModel("inner", "<pose>1 0 0 0 0 0</pose>") +
                      "</model>\n"
                      "<state world_name='default'><model name='outer'><pose>10 0 0 0 0 0</pose>"
                      "<model name='inner'><pose>10 4 0 0 0 0</pose><link name='link'><pose>10 4 2 0 0 0</pose>"
                      "</link></model></model></state>\n",
                  "1.6"));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  // The state's world-frame poses: the nested model's link at (10, 4, 2).
  ExpectBox(BoundsOf(scene, "outer"), {9.9, 3.9, 1.9}, {10.1, 4.1, 2.1});
  EXPECT_NEAR(ByName(scene, "outer")->T_world_object.translation().x(), 10.0, 1e-12);
}

TEST(GazeboSdfTest, CapsuleAndEllipsoidAreLoaded) {
  TempDir dir;
  WriteText(dir.File("w.world"),
            World("<model name='c'><link name='l'><visual name='v'><geometry><capsule><radius>0.5</radius>"
                  "<length>2</length></capsule></geometry></visual></link></model>\n"
                  "<model name='e'><link name='l'><visual name='v'><geometry><ellipsoid><radii>1 2 3</radii>"
                  "</ellipsoid></geometry></visual></link></model>\n",
                  "1.8"));
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), SceneLoadOptions());
  EXPECT_NEAR(BoundsOf(scene, "c").max_m.z(), 1.5, 1e-3);
  EXPECT_NEAR(BoundsOf(scene, "e").max_m.z(), 3.0, 1e-3);
  EXPECT_NEAR(BoundsOf(scene, "e").max_m.y(), 2.0, 0.05);  // a 16-segment sphere, stretched
}

TEST(GazeboSdfTest, CategoryMapFromOptionsAndUnmappedModelsAreListed) {
  TempDir dir;
  WriteText(dir.File("map.yaml"),
            "rules:\n  - {name: '^Sofa', category: sofa}\n  - {uri: 'ceiling', category: ceiling}\n");
  WriteText(dir.File("w.world"),
            World(BoxModel("SofaB_01_001", "") + BoxModel("mystery_box", "<pose>3 0 0 0 0 0</pose>") +
                  "<model name='top'><link name='l'><visual name='v'><geometry><mesh><uri>file://" +
                  dir.File("ceiling.obj") + "</uri></mesh></geometry></visual></link></model>\n"));
  WriteText(dir.File("ceiling.obj"), "v 0 0 2.5\nv 4 0 2.5\nv 4 4 2.5\nf 1 2 3\n");
  SceneLoadOptions options;
  options.category_map = dir.File("map.yaml");
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), options);
  EXPECT_EQ(ByName(scene, "SofaB_01_001")->category, world::Category::kSofa);
  EXPECT_EQ(ByName(scene, "top")->category, world::Category::kCeiling);
  EXPECT_TRUE(ByName(scene, "top")->IsStructural());
  EXPECT_EQ(ByName(scene, "mystery_box")->category, world::Category::kOther);
  ASSERT_EQ(scene.unmapped_models().size(), 1u);
  EXPECT_NE(scene.unmapped_models()[0].find("mystery_box"), std::string::npos);
}

TEST(GazeboSdfTest, MalformedWorldsGiveOneLineNamingFileAndElement) {
  TempDir dir;
  WriteAwsStyleModel(dir.File("models"), "thing");
  WriteText(dir.File("models/selfie/model.sdf"),
            "<?xml version='1.0'?><sdf version='1.6'><model name='selfie'><include><uri>model://selfie</uri>"
            "</include></model></sdf>\n");
  WriteText(dir.File("models/empty_folder/readme.txt"), "no sdf here\n");
  SceneLoadOptions options;
  options.model_path = dir.File("models");
  const struct {
    std::string body;
    std::string needle;
    bool names_world = true;  // false: the error is in an included model's file, which it names
  } cases[] = {
      {"<model name='a'><include></include></model>", "<include> without <uri>"},
      {"<model name='a'><include><uri>model://nowhere</uri></include></model>", "model://nowhere"},
      {"<model name='a'><include><uri>model://thing</uri><pose>1 2</pose></include></model>", "<pose> '1 2'"},
      {"<model name='a'><include><uri>model://empty_folder</uri></include></model>", "model.sdf"},
      {"<model name='a'><include><uri>model://selfie</uri></include></model>", "nest deeper", false},
      {"<model name='a'><static>maybe</static></model>", "<static> 'maybe'"},
      {"<model name='a'><link name='l'><pose relative_to='nope'>0 0 0 0 0 0</pose></link></model>",
       "'nope' names no frame"},
      {"<model name='a'><frame name='f1'><pose relative_to='f2'>0 0 0 0 0 0</pose></frame>"
       "<frame name='f2'><pose relative_to='f1'>0 0 0 0 0 0</pose></frame>"
       "<link name='l'><pose relative_to='f1'>0 0 0 0 0 0</pose></link></model>",
       "cycle"},
      {"<actor name='walker'><skin><filename>walk.dae</filename></skin></actor>", "<actor> 'walker'"},
      {"<model name='a'><link name='l'><visual name='v'><geometry><heightmap><uri>h.png</uri></heightmap>"
       "</geometry></visual></link></model>",
       "unsupported geometry <heightmap>"},
      {"<model name='a'><link name='l'><visual name='v'><geometry><mesh><uri>model://thing/meshes/"
       "thing_visual.DAE</uri><submesh><name>x</name></submesh></mesh></geometry></visual></link></model>",
       "<submesh>"},
      {"<model name='a'><link name='l'><visual name='v'><geometry><mesh><uri>model://thing/meshes/"
       "thing_visual.DAE</uri><scale>1 0 1</scale></mesh></geometry></visual></link></model>",
       "<scale> '1 0 1'"},
      {BoxModel("dup", "") + BoxModel("dup", ""), "duplicate model name"},
      {"<model name='a'><link name='l'><visual name='v'><geometry><mesh><uri>file:///no/such/mesh.DAE</uri>"
       "</mesh></geometry></visual></link></model>",
       "file:///no/such/mesh.DAE"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string world = dir.File("bad" + std::to_string(i++) + ".world");
    WriteText(world, World(c.body));
    SCOPED_TRACE(c.body);
    ExpectInputError([&] { LoadGazeboWorld(world, options); }, c.needle);
    if (c.names_world) ExpectInputError([&] { LoadGazeboWorld(world, options); }, world.substr(world.rfind('/') + 1));
  }
}

TEST(GazeboSdfTest, AllowMissingListsWhatCouldNotBeLoaded) {
  TempDir dir;
  WriteText(dir.File("w.world"),
            World(BoxModel("box_1", "") + "<actor name='walker'><skin><filename>walk.dae</filename></skin></actor>\n"
                  "<model name='a'><include><uri>model://nowhere</uri></include></model>\n"));
  SceneLoadOptions options;
  options.allow_missing = true;
  const world::Scene scene = LoadGazeboWorld(dir.File("w.world"), options);
  EXPECT_NE(ByName(scene, "box_1"), nullptr);
  ASSERT_EQ(scene.missing_meshes().size(), 2u);
  EXPECT_NE(scene.missing_meshes()[0].find("<actor> 'walker'"), std::string::npos) << scene.missing_meshes()[0];
  EXPECT_NE(scene.missing_meshes()[1].find("model://nowhere"), std::string::npos) << scene.missing_meshes()[1];
}

}  // namespace
}  // namespace objscan::io
