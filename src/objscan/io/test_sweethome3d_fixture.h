#pragma once
// A small Sweet Home 3D furniture catalog (.sh3f) for tests (sweethome3d_test, the db build CLI test):
//  1. "Double bed" (Bedroom): a unit cube OBJ (Y-up, quads, deflated), 200 x 160 x 50 cm (W x D x H);
//  2. "Fridge" (Kitchen): a Z-up pyramid made Y-up by modelRotation "1 0 0 0 0 1 0 -1 0" (rows
//     (1,0,0), (0,0,1), (0,-1,0)), negative indices and v/vt/vn corners; 70 x 65 x 180 cm; its apex
//     (model +Z, the only vertex at the top) must come out on top;
//  3. "Wall cabinet" (Kitchen): name split by a `\` continuation, creator with a \u00e9 escape,
//     elevation 150 cm; the unit cube, 80 x 35 x 60 cm;
//  4. "Sports car" (Vehicles): a unit cube, 400 x 180 x 130 cm (left out by the category map).
// Plus catalog keys (id, name, license with a \u00a9 escape) and LICENSE.TXT.
#include <string>

#include "objscan/io/test_zip_writer.h"

namespace objscan::io::testing {

// A unit cube [0,1]^3 with quad faces, `v/vt/vn` corners.
inline std::string UnitCubeObj() {
  return "# unit cube\nmtllib cube.mtl\no Cube\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "vt 0 0\nvn 0 0 1\ng sides\nusemtl wood\ns off\n"
         "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5/1/1 6/1/1 7/1/1 8/1/1\nf 1/1/1 2/1/1 6/1/1 5/1/1\n"
         "g other_sides\n"
         "f 2//1 3//1 7//1 6//1\nf 3 4 8 7\nf 4/1 1/1 5/1 8/1\n";
}

// A square pyramid in a Z-up model frame: base [0,2]x[0,3] at z = 0, apex (1, 1.5, 5). Faces use
// negative (relative) indices.
inline std::string ZUpPyramidObj() {
  return "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nv 1 1.5 5\nvn 0 0 1\n"
         "f -5//1 -2//1 -3//1 -4//1\nf -5 -4 -1\nf -4 -3 -1\nf -3 -2 -1\nf -2 -5 -1\n";
}

inline std::string SweetHome3dFixtureProperties() {
  return "# PluginFurnitureCatalog.properties of a test catalog\n"
         "id=Test#Catalog\n"
         "name=Test catalog\n"
         "license=CC-BY 4.0 \\u00a9 Test Makers\n"
         "\n"
         "id#1=Test#bed 1\n"
         "name#1=Double bed\n"
         "category#1=Bedroom\n"
         "model#1=/test/bed/bed.obj\n"
         "width#1=200\n"
         "depth#1=160\n"
         "height#1=50\n"
         "doorOrWindow#1=false\n"
         "creator#1=Alice\n"
         "\n"
         "id#2=Test#fridge\n"
         "name#2 = Fridge\n"
         "category#2=Kitchen\n"
         "model#2=/test/fridge.obj\n"
         "modelRotation#2=1 0 0 0 0 1 0 -1 0\n"
         "width#2=70\n"
         "depth#2=65\n"
         "height#2=180.0\n"
         "creator#2=Bob\n"
         "\n"
         "! a comment of the other kind\n"
         "id#3=Test#wall-cabinet\n"
         "name#3=Wall \\\n"
         "      cabinet\n"
         "category#3=Kitchen\n"
         "model#3=/test/bed/bed.obj\n"
         "width#3=80\n"
         "depth#3=35\n"
         "height#3=60\n"
         "elevation#3=150\n"
         "creator#3=Jos\\u00e9\n"
         "\n"
         "id#4=Test#car\n"
         "name#4=Sports car\n"
         "category#4=Vehicles\n"
         "model#4=/test/bed/bed.obj\n"
         "width#4=400\n"
         "depth#4=180\n"
         "height#4=130\n"
         "creator#4=Carol\n";
}

inline void WriteSweetHome3dFixture(const std::string& path) {
  ZipWriter zip;
  zip.Add("LICENSE.TXT", "Test models under CC-BY 4.0\n");
  zip.Add("PluginFurnitureCatalog.properties", SweetHome3dFixtureProperties(), /*deflate=*/true);
  zip.Add("test/", "");
  zip.Add("test/bed/bed.obj", UnitCubeObj(), /*deflate=*/true);
  zip.Add("test/bed/cube.mtl", "newmtl wood\nKd 0.5 0.3 0.1\n");
  zip.Add("test/fridge.obj", ZUpPyramidObj());
  zip.Write(path);
}

}  // namespace objscan::io::testing
