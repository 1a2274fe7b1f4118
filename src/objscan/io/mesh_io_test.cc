#include "objscan/io/mesh_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <fstream>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/io/ply.h"
#include "objscan/io/test_util.h"
#include "shared_data.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::WriteText;

void ExpectBounds(const geometry::TriangleMesh& mesh, const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m,
                  double tol = 1e-5) {
  const geometry::Aabb3 b = geometry::Bounds(mesh);
  EXPECT_TRUE(b.min_m.isApprox(min_m, tol) || (b.min_m - min_m).norm() < tol) << b.min_m.transpose();
  EXPECT_TRUE(b.max_m.isApprox(max_m, tol) || (b.max_m - max_m).norm() < tol) << b.max_m.transpose();
}

// A COLLADA file with one triangle (0,0,0) (2,0,0) (0,3,0)... placed by a node translation.
std::string Collada(const std::string& unit_meter, const std::string& up_axis, const std::string& node_translate) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter=")" + unit_meter + R"(" name="u"/><up_axis>)" + up_axis + R"(</up_axis></asset>
  <library_geometries>
    <geometry id="g" name="g"><mesh>
      <source id="g-pos"><float_array id="g-pos-array" count="12">0 0 0 2 0 0 0 3 0 0 0 4</float_array>
        <technique_common><accessor source="#g-pos-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
      <triangles count="2"><input semantic="VERTEX" source="#g-vtx" offset="0"/><p>0 1 2 0 1 3</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s" name="s">
    <node id="n" name="n"><translate>)" + node_translate + R"(</translate><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

TEST(MeshIoTest, ObjQuadsAreTriangulatedAndVerticesKept) {
  TempDir dir;
  WriteText(dir.File("q.obj"), "v 0 0 0\nv 1 0 0\nv 1 2 0\nv 0 2 0\nv 0 0 3\nf 1 2 3 4\nf 1 2 5\n");
  const geometry::TriangleMesh m = LoadMesh(dir.File("q.obj"));
  EXPECT_EQ(m.NumTriangles(), 3u);
  EXPECT_EQ(m.vertices.size(), 5u);
  ExpectBounds(m, {0, 0, 0}, {1, 2, 3});  // OBJ is taken as Z-up, unchanged
  EXPECT_NEAR(geometry::SurfaceArea(m), 2.0 + 1.5, 1e-6);
}

TEST(MeshIoTest, ColladaUnitIsAppliedAndUpAxisIgnoredLikeGazebo) {
  TempDir dir;
  // Inches, Z_UP: Gazebo scales by 0.0254 (node translation included) and keeps the axes.
  WriteText(dir.File("inch.dae"), Collada("0.0254", "Z_UP", "10 0 0"));
  ExpectBounds(LoadMesh(dir.File("inch.dae")), {0.254, 0, 0}, {0.254 + 2 * 0.0254, 3 * 0.0254, 4 * 0.0254});
  // Y_UP is ignored too (SUNCG meshes declare Y_UP but store Z-up data).
  WriteText(dir.File("yup.dae"), Collada("1", "Y_UP", "0 0 1"));
  ExpectBounds(LoadMesh(dir.File("yup.dae")), {0, 0, 1}, {2, 3, 5});
  // An explicit "y" convention rotates +Y to +Z: (x, y, z) -> (x, -z, y).
  MeshLoadOptions y_up;
  y_up.up_axis = "y";
  ExpectBounds(LoadMesh(dir.File("yup.dae"), y_up), {0, -5, 0}, {2, -1, 3});
}

TEST(MeshIoTest, GltfIsRotatedFromYUpToZUp) {
  TempDir dir;
  // One triangle (0,0,0) (1,0,0) (0,1,0) as an embedded base64 buffer (36 bytes of float32).
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string bytes(reinterpret_cast<const char*>(v), sizeof(v));
  static const char* kB64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned n = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) b64 += kB64[(n >> (6 * k)) & 63];
  }
  WriteText(dir.File("t.gltf"),
            R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
            R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" + b64 + R"("}],)"
            R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],)"
            R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]})");
  const geometry::TriangleMesh m = LoadMesh(dir.File("t.gltf"));
  ASSERT_EQ(m.NumTriangles(), 1u);
  ExpectBounds(m, {0, 0, 0}, {1, 0, 1});  // the file's +Y is our +Z
}

TEST(MeshIoTest, StlOffAndPlyLoad) {
  TempDir dir;
  WriteText(dir.File("a.stl"),
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
            "endsolid t\n");
  ExpectBounds(LoadMesh(dir.File("a.stl")), {0, 0, 0}, {1, 1, 0});
  WriteText(dir.File("a.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(LoadMesh(dir.File("a.off")).NumTriangles(), 2u);
  PlyData ply;
  ply.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 2}};
  ply.triangles = {{0, 1, 2}};
  WritePly(dir.File("a.ply"), ply);
  ExpectBounds(LoadMesh(dir.File("a.ply")), {0, 0, 0}, {1, 0, 2});
  MeshLoadOptions scaled;
  scaled.scale = 2.0;
  ExpectBounds(LoadMesh(dir.File("a.ply"), scaled), {0, 0, 0}, {2, 0, 4});
}

TEST(MeshIoTest, BadFilesNameTheFile) {
  TempDir dir;
  ExpectInputError([&] { LoadMesh(dir.File("nothing.obj")); }, "nothing.obj");
  WriteText(dir.File("junk.dae"), "<COLLADA><oops");
  ExpectInputError([&] { LoadMesh(dir.File("junk.dae")); }, "junk.dae");
  WriteText(dir.File("junk.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nend_header\nxx\n");
  ExpectInputError([&] { LoadMesh(dir.File("junk.ply")); }, "junk.ply");
  WriteText(dir.File("empty.obj"), "v 0 0 0\nv 1 0 0\n");
  ExpectInputError([&] { LoadMesh(dir.File("empty.obj")); }, "empty.obj");
  WriteText(dir.File("a.xyz"), "0 0 0\n");
  ExpectInputError([&] { LoadMesh(dir.File("a.xyz")); }, "unsupported mesh format");
  EXPECT_TRUE(IsMeshFile("A.DAE"));
  EXPECT_FALSE(IsMeshFile("room.world"));
}

TEST(MeshIoTest, ValveWallIsUprightInMetres) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  // drc_practice_valve_wall: a Z_UP COLLADA file in inches, 1.2192 m x 2.4384 m (its model.sdf's
  // collision box is 1.2192 x 0.00952 x 2.4384 centred at (0.6096, 0.00476, 1.2192)).
  const geometry::TriangleMesh m = LoadMesh(data + "/gazebo-models/drc_practice_valve_wall/meshes/five_dice_wall.dae");
  const geometry::Aabb3 b = geometry::Bounds(m);
  EXPECT_NEAR(b.Size().x(), 1.2192, 1e-3);
  EXPECT_NEAR(b.Size().y(), 0.00952, 1e-3);
  EXPECT_NEAR(b.Size().z(), 2.4384, 1e-3);
  EXPECT_NEAR(b.min_m.z(), 0.0, 1e-3);
}

TEST(MeshIoTest, SuncgMeshFootprintsMatchTheirCollisionBoxes) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  // Every SUNCG model folder beside a world has ID/ID.sdf with a collision <box><size>sx sy 2</size>
  // whose x, y are the mesh footprint in Gazebo's (Z-up) frame; no mesh reaches below its origin.
  const std::regex size_re("<size>\\s*([-0-9.e]+)\\s+([-0-9.e]+)\\s+([-0-9.e]+)\\s*</size>");
  int checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(data + "/oasc-dev/SUNCG")) {
    if (entry.path().extension() != ".sdf") continue;
    const std::filesystem::path dae = entry.path().parent_path() / (entry.path().stem().string() + ".dae");
    if (!std::filesystem::exists(dae)) continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    std::smatch match;
    const std::string sdf = text.str();
    ASSERT_TRUE(std::regex_search(sdf, match, size_re)) << entry.path();
    const double sx = std::stod(match[1]), sy = std::stod(match[2]);
    const geometry::Aabb3 b = geometry::Bounds(LoadMesh(dae.string()));
    EXPECT_NEAR(b.Size().x(), sx, 0.02 + 0.02 * sx) << dae;
    EXPECT_NEAR(b.Size().y(), sy, 0.02 + 0.02 * sy) << dae;
    EXPECT_GE(b.min_m.z(), -0.03) << dae;  // nothing below the model origin (wall sinks hang higher)
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace objscan::io
