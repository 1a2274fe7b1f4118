#include "objscan/io/sweethome3d.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/io/test_sweethome3d_fixture.h"
#include "objscan/io/test_util.h"
#include "objscan/io/zip_archive.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

constexpr double kTol = 1e-5;

void ExpectBounds(const geometry::TriangleMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const geometry::Aabb3 box = geometry::Bounds(mesh);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min_m[k], lo[k], kTol) << "axis " << k;
    EXPECT_NEAR(box.max_m[k], hi[k], kTol) << "axis " << k;
  }
}

TEST(JavaPropertiesTest, SeparatorsCommentsEscapesAndContinuations) {
  const std::string text =
      "# comment\n"
      "! other comment\n"
      "   \n"
      "a=1\n"
      "b = two words \n"
      "c:3\n"
      "d 4\n"
      "e\n"
      "key\\ with\\=odd\\:chars=v\n"
      "long=first \\\n"
      "     second\\\n"
      "\tthird\n"
      "even=ends with a backslash\\\\\n"
      "next=x\r\n"
      "unicode=caf\\u00e9 \\u20ac \\ud83d\\ude00\n"
      "latin1=\xe9t\xe9\n"
      "tabs=a\\tb\\nc\n"
      "a=last wins";
  const auto props = ParseJavaProperties(text, "t.properties");
  EXPECT_EQ(props.at("a"), "last wins");
  EXPECT_EQ(props.at("b"), "two words ");
  EXPECT_EQ(props.at("c"), "3");
  EXPECT_EQ(props.at("d"), "4");
  EXPECT_EQ(props.at("e"), "");
  EXPECT_EQ(props.at("key with=odd:chars"), "v");
  EXPECT_EQ(props.at("long"), "first secondthird");
  EXPECT_EQ(props.at("even"), "ends with a backslash\\");
  EXPECT_EQ(props.at("next"), "x");
  EXPECT_EQ(props.at("unicode"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80");
  EXPECT_EQ(props.at("latin1"), "\xc3\xa9t\xc3\xa9");
  EXPECT_EQ(props.at("tabs"), "a\tb\nc");
  EXPECT_EQ(props.count("# comment"), 0u);
  ExpectInputError([] { ParseJavaProperties("x=\\u12g4\n", "bad.properties"); }, "bad.properties: line 1: malformed");
}

TEST(ObjTest, FacesFanTriangulatedWithAllCornerForms) {
  const geometry::TriangleMesh cube = ParseObj(testing::UnitCubeObj(), "cube.obj");
  EXPECT_EQ(cube.vertices.size(), 8u);
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_NEAR(geometry::SurfaceArea(cube), 6.0, 1e-6);
  const geometry::TriangleMesh pyramid = ParseObj(testing::ZUpPyramidObj(), "p.obj");
  EXPECT_EQ(pyramid.triangles.size(), 6u);
  EXPECT_EQ(pyramid.triangles[0], Eigen::Vector3i(0, 3, 2));  // "f -5 -2 -3 -4" after 5 vertices
  ExpectInputError([] { ParseObj("v 0 0 0\nf 1 2 3\n", "x.obj"); }, "x.obj: line 2: face index 2 out of range");
  ExpectInputError([] { ParseObj("v 0 zero 0\n", "y.obj"); }, "y.obj: line 1: malformed vertex");
}

TEST(SweetHome3dTest, PlacementMapsYUpCentimetresToZUpMetres) {
  // A tetrahedron in Sweet Home 3D's frame: origin, +X, +Y (up) and +Z (front).
  geometry::TriangleMesh model;
  model.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  model.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  SweetHome3dPiece piece;
  piece.width_cm = 100;
  piece.height_cm = 300;
  piece.depth_cm = 50;
  const geometry::TriangleMesh mesh = PlaceSweetHome3dModel(model, piece);
  ExpectBounds(mesh, {-0.5, -0.25, 0.0}, {0.5, 0.25, 3.0});
  EXPECT_TRUE(mesh.vertices[2].isApprox(Eigen::Vector3f(-0.5f, 0.25f, 3.0f)));   // up -> +Z
  EXPECT_TRUE(mesh.vertices[3].isApprox(Eigen::Vector3f(-0.5f, -0.25f, 0.0f)));  // front (+Z) -> -Y
  EXPECT_TRUE(mesh.vertices[1].isApprox(Eigen::Vector3f(0.5f, 0.25f, 0.0f)));    // +X stays +X
  // A proper rotation: the outward normal of a face stays outward (signed volume kept positive).
  double volume_model = 0, volume_mesh = 0;
  for (const auto& t : model.triangles) {
    volume_model += model.vertices[t[0]].cast<double>().dot(
        model.vertices[t[1]].cast<double>().cross(model.vertices[t[2]].cast<double>()));
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    volume_mesh += a.dot(b.cross(c));
  }
  EXPECT_GT(volume_model * volume_mesh, 0.0);
}

TEST(SweetHome3dTest, ReadsTheFixtureCatalog) {
  TempDir dir;
  const std::string path = dir.File("test.sh3f");
  testing::WriteSweetHome3dFixture(path);
  const SweetHome3dCatalog catalog = LoadSweetHome3dCatalog(path);
  EXPECT_EQ(catalog.file, path);
  EXPECT_EQ(catalog.id, "Test#Catalog");
  EXPECT_EQ(catalog.name, "Test catalog");
  EXPECT_EQ(catalog.license, "CC-BY 4.0 \xc2\xa9 Test Makers");
  EXPECT_EQ(catalog.license_text, "Test models under CC-BY 4.0\n");
  ASSERT_EQ(catalog.pieces.size(), 4u);
  const SweetHome3dPiece& bed = catalog.pieces[0];
  EXPECT_EQ(bed.index, 1);
  EXPECT_EQ(bed.id, "Test#bed 1");
  EXPECT_EQ(bed.name, "Double bed");
  EXPECT_EQ(bed.category, "Bedroom");
  EXPECT_EQ(bed.model, "test/bed/bed.obj");
  EXPECT_DOUBLE_EQ(bed.width_cm, 200);
  EXPECT_DOUBLE_EQ(bed.depth_cm, 160);
  EXPECT_DOUBLE_EQ(bed.height_cm, 50);
  EXPECT_DOUBLE_EQ(bed.elevation_cm, 0);
  EXPECT_EQ(bed.creator, "Alice");
  EXPECT_FALSE(bed.door_or_window);
  const SweetHome3dPiece& fridge = catalog.pieces[1];
  EXPECT_EQ(fridge.name, "Fridge");
  EXPECT_EQ(fridge.model_rotation, (std::array<double, 9>{1, 0, 0, 0, 0, 1, 0, -1, 0}));
  const SweetHome3dPiece& cabinet = catalog.pieces[2];
  EXPECT_EQ(cabinet.name, "Wall cabinet");
  EXPECT_EQ(cabinet.creator, "Jos\xc3\xa9");
  EXPECT_DOUBLE_EQ(cabinet.elevation_cm, 150);
  EXPECT_EQ(catalog.Find("Test#car"), &catalog.pieces[3]);
  EXPECT_EQ(catalog.Find("nope"), nullptr);
}

TEST(SweetHome3dTest, MeshesScaledToTheCatalogSizeZUp) {
  TempDir dir;
  const std::string path = dir.File("test.sh3f");
  testing::WriteSweetHome3dFixture(path);
  const SweetHome3dCatalog catalog = LoadSweetHome3dCatalog(path);
  const ZipArchive archive = ZipArchive::Open(path);

  const geometry::TriangleMesh bed = LoadSweetHome3dMesh(archive, catalog.pieces[0]);
  EXPECT_EQ(bed.triangles.size(), 12u);
  ExpectBounds(bed, {-1.0, -0.8, 0.0}, {1.0, 0.8, 0.5});  // 200 (X) x 160 (Y) x 50 (Z) cm

  const geometry::TriangleMesh fridge = LoadSweetHome3dMesh(archive, catalog.pieces[1]);
  ExpectBounds(fridge, {-0.35, -0.325, 0.0}, {0.35, 0.325, 1.8});
  // modelRotation made the Z-up pyramid stand: its apex alone is on top, over the base's centre.
  int on_top = 0;
  for (const auto& v : fridge.vertices) {
    if (std::abs(v.z() - 1.8f) < 1e-5f) {
      ++on_top;
      EXPECT_NEAR(v.x(), 0.0, kTol);
      EXPECT_NEAR(v.y(), 0.0, kTol);
    }
  }
  EXPECT_EQ(on_top, 1);

  // The catalog path + id form (what database sources use); the elevation is not part of the mesh.
  const geometry::TriangleMesh cabinet = LoadSweetHome3dMesh(path, "Test#wall-cabinet");
  ExpectBounds(cabinet, {-0.4, -0.175, 0.0}, {0.4, 0.175, 0.6});
  ExpectInputError([&] { LoadSweetHome3dMesh(path, "Test#sofa"); }, path + ": no piece of furniture with id 'Test#sofa'");
}

TEST(SweetHome3dTest, DamagedCatalogsAreInputErrorsNamingTheFile) {
  TempDir dir;
  ExpectInputError([&] { LoadSweetHome3dCatalog(dir.File("none.sh3f")); }, dir.File("none.sh3f") + ": ");

  const std::string good = dir.File("good.sh3f");
  testing::WriteSweetHome3dFixture(good);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string truncated = dir.File("truncated.sh3f");
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  ExpectInputError([&] { LoadSweetHome3dCatalog(truncated); }, truncated + ": ");

  testing::ZipWriter no_properties;
  no_properties.Add("a.obj", "v 0 0 0\n");
  no_properties.Write(dir.File("plain.sh3f"));
  ExpectInputError([&] { LoadSweetHome3dCatalog(dir.File("plain.sh3f")); },
                   "no PluginFurnitureCatalog.properties");

  testing::ZipWriter bad_size;
  bad_size.Add("PluginFurnitureCatalog.properties", "id#1=x\nname#1=Chair\nmodel#1=/c.obj\nwidth#1=wide\n");
  bad_size.Write(dir.File("bad.sh3f"));
  ExpectInputError([&] { LoadSweetHome3dCatalog(dir.File("bad.sh3f")); }, "piece 1 ('Chair'): width#1 'wide' is not a number");

  testing::ZipWriter missing_model;
  missing_model.Add("PluginFurnitureCatalog.properties",
                    "id#1=x\nname#1=Chair\nmodel#1=/c.obj\nwidth#1=1\ndepth#1=1\nheight#1=1\n");
  missing_model.Write(dir.File("missing.sh3f"));
  const SweetHome3dCatalog catalog = LoadSweetHome3dCatalog(dir.File("missing.sh3f"));
  ExpectInputError([&] { LoadSweetHome3dMesh(ZipArchive::Open(dir.File("missing.sh3f")), catalog.pieces[0]); },
                   dir.File("missing.sh3f") + ": no entry 'c.obj'");
}

TEST(SweetHome3dTest, CatalogFolder) {
  TempDir dir;
  ExpectInputError([&] { SweetHome3dCatalogFiles(dir.File("none")); }, "sweethome3d-furniture");
  ExpectInputError([&] { SweetHome3dCatalogFiles(dir.path().string()); }, "no .sh3f");
  testing::WriteSweetHome3dFixture(dir.File("b.sh3f"));
  testing::WriteSweetHome3dFixture(dir.File("a.SH3F"));
  const std::vector<std::string> files = SweetHome3dCatalogFiles(dir.path().string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], dir.File("a.SH3F"));
  EXPECT_EQ(files[1], dir.File("b.sh3f"));
}

// The real catalogs of Debian's sweethome3d-furniture: every piece's model loads with its size.
TEST(SweetHome3dTest, RealDebianCatalogs) {
  const std::string dir = "/usr/share/sweethome3d/furniture";
  if (!std::filesystem::is_directory(dir)) {
    GTEST_SKIP() << "SKIPPED: " << dir << " missing (install Debian's sweethome3d-furniture package)";
  }
  std::size_t pieces = 0;
  for (const std::string& file : SweetHome3dCatalogFiles(dir)) {
    const SweetHome3dCatalog catalog = LoadSweetHome3dCatalog(file);
    EXPECT_FALSE(catalog.license.empty()) << file;
    const ZipArchive archive = ZipArchive::Open(file);
    for (const SweetHome3dPiece& piece : catalog.pieces) {
      ++pieces;
      const geometry::TriangleMesh mesh = LoadSweetHome3dMesh(archive, piece);
      const geometry::Aabb3 box = geometry::Bounds(mesh);
      EXPECT_NEAR(box.Size().x(), piece.width_cm / 100, 1e-3) << file << " " << piece.id;
      EXPECT_NEAR(box.Size().y(), piece.depth_cm / 100, 1e-3) << file << " " << piece.id;
      EXPECT_NEAR(box.Size().z(), piece.height_cm / 100, 1e-3) << file << " " << piece.id;
    }
  }
  EXPECT_GT(pieces, 700u);
}

}  // namespace
}  // namespace objscan::io
