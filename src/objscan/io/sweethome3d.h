#pragma once
// Sweet Home 3D furniture catalogs (.sh3f, e.g. Debian's sweethome3d-furniture package in
// /usr/share/sweethome3d/furniture): a zip archive of OBJ models (with their MTL files and textures)
// and PluginFurnitureCatalog.properties, a Java properties file whose entries N describe the pieces
// of furniture (id#N, name#N, category#N, model#N, width#N, depth#N, height#N, elevation#N,
// modelRotation#N, doorOrWindow#N, creator#N) plus the catalog's id=, name= and license= keys.
// Localized PluginFurnitureCatalog_<lang>.properties files are not read: names are English.
//
// Sweet Home 3D's convention: the model, once multiplied by modelRotation (row-major 3x3, applied to
// column vectors), is Y-up, and is scaled so that its bounding box is exactly width (X) x height (Y)
// x depth (Z) centimetres. objscan's frame is Z-up in metres: (x, y, z) -> (x, -z, y) / 100, a
// proper rotation (+90 deg about X), so a piece of W x D x H cm comes out W/100 along X, D/100 along
// Y and H/100 along Z, centred in X and Y, its bottom on z = 0.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "objscan/geometry/mesh.h"

namespace objscan::io {

class ZipArchive;

// Parses a Java .properties file as java.util.Properties.load does: ISO-8859-1 bytes (returned as
// UTF-8), `#`/`!` comment lines, key and value separated by `=`, `:` or white space, `\` at the end
// of a line continuing it (the next line's leading white space dropped), escapes \uXXXX (UTF-16,
// surrogate pairs joined), \t \n \r \f and \<char> for the char itself. The last of duplicate keys
// wins. Throws InputError naming `where` and the line on a malformed \u escape.
std::map<std::string, std::string> ParseJavaProperties(const std::string& bytes, const std::string& where);

// One piece of furniture of a catalog.
struct SweetHome3dPiece {
  int index = 0;              // N of its keys (key#N)
  std::string id;             // id#N, e.g. "Kator Legaz#fridge" (N when the catalog gives none)
  std::string name;           // English name, e.g. "Fridge"
  std::string category;       // Sweet Home 3D category (the room), e.g. "Kitchen", "Doors and windows"
  std::string model;          // path of the model inside the archive, without the leading '/'
  double width_cm = 0.0, depth_cm = 0.0, height_cm = 0.0;
  double elevation_cm = 0.0;  // of its bottom above the floor
  // Row-major 3x3 matrix making the model Y-up; identity when absent.
  std::array<double, 9> model_rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  bool door_or_window = false;
  std::string creator;
};

struct SweetHome3dCatalog {
  std::string file;          // the .sh3f path as given
  std::string id;            // id=
  std::string name;          // name=, e.g. "Kator Legaz catalog"
  std::string license;       // license=
  std::string license_text;  // LICENSE.TXT of the archive ("" when absent)
  std::vector<SweetHome3dPiece> pieces;  // in index order

  // The piece of this id, or null.
  const SweetHome3dPiece* Find(const std::string& id) const;
};

// Reads a catalog's properties (and LICENSE.TXT). Throws InputError naming the file (and the piece)
// when the archive is damaged, has no PluginFurnitureCatalog.properties, or a piece lacks its model
// or has a size that is not a positive number.
SweetHome3dCatalog LoadSweetHome3dCatalog(const std::string& path);

// The mesh of a piece in objscan's frame (see above): OBJ models through ParseObj, other formats
// (.3ds, .dae, ...) through Assimp from memory. Throws InputError naming the archive and the model
// when the model is missing, damaged or has no triangles.
geometry::TriangleMesh LoadSweetHome3dMesh(const ZipArchive& archive, const SweetHome3dPiece& piece);
// The same from the catalog file and a piece id (opens and reads the catalog).
geometry::TriangleMesh LoadSweetHome3dMesh(const std::string& catalog_path, const std::string& piece_id);

// The triangles of an OBJ text: `v` and `f` lines (polygons fan-triangulated; `i`, `i/t`, `i//n`,
// `i/t/n` corners; negative indices relative to the vertices read so far); everything else (groups,
// materials, texture coordinates, normals, lines) ignored. Coordinates as in the file. Throws
// InputError naming `where` and the line on a malformed number or an index out of range.
geometry::TriangleMesh ParseObj(const std::string& text, const std::string& where);

// A mesh in Sweet Home 3D's model frame placed as the catalog says: multiplied by `rotation`
// (row-major), scaled per axis to width x height x depth cm (an axis of zero extent stays flat),
// converted to objscan's frame (Z up, metres), centred in X and Y with its bottom on z = 0.
geometry::TriangleMesh PlaceSweetHome3dModel(const geometry::TriangleMesh& model, const SweetHome3dPiece& piece);

// A piece as one string, as model databases store a model's source: "sweethome3d:<catalog path>#<id>"
// (the id may itself hold '#': the catalog path ends at the first ".sh3f#", case ignored).
std::string SweetHome3dSource(const std::string& catalog_path, const std::string& piece_id);
bool IsSweetHome3dSource(const std::string& source);
// The catalog path of a SweetHome3dSource string; "" for another string.
std::string SweetHome3dSourceCatalog(const std::string& source);
// The mesh of a SweetHome3dSource string (LoadSweetHome3dMesh); throws InputError naming the source
// when it is malformed, or as LoadSweetHome3dMesh.
geometry::TriangleMesh LoadSweetHome3dSource(const std::string& source);

// Folder of the catalogs: $OBJSCAN_SWEETHOME3D_DIR when set and not empty, else Debian's
// /usr/share/sweethome3d/furniture.
std::string SweetHome3dCatalogDir();
// The *.sh3f files of `dir`, sorted. Throws InputError naming the folder when it is missing or holds
// none (pointing to the sweethome3d-furniture package and $OBJSCAN_SWEETHOME3D_DIR).
std::vector<std::string> SweetHome3dCatalogFiles(const std::string& dir);

}  // namespace objscan::io
