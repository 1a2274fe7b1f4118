#pragma once
// Sweet Home 3D furniture catalogs (.sh3f, io/sweethome3d.h) as model-database sources:
// `objscan db build --models sweethome3d` (every catalog of io::SweetHome3dCatalogDir()) or
// `--models X.sh3f`. Each piece a category map gives a category becomes a ModelSource named
// "<category>/sh3d-<catalog file stem>-<piece id after its last '#'>" (lower case, other characters
// than [a-z0-9._-] as '-'; "-<N>" appended on a clash), whose source is
// io::SweetHome3dSource(<absolute catalog path>, <piece id>) so LoadModelSourceMesh loads it anywhere
// the catalog is, standing at its catalog elevation (support_heights_m {elevation m}, {0} on the
// floor), credited to the piece's creator under its catalog's licence.
#include <map>
#include <string>
#include <vector>

#include "objscan/io/category_map.h"
#include "objscan/recognition/database_builder.h"

namespace objscan::recognition {

// The category map --models sweethome3d uses unless --category-map is given (in config/).
constexpr const char* kSweetHome3dCategoryMap = "categories/sweethome3d.yaml";

// True for "sweethome3d" and for a path ending in .sh3f (case ignored).
bool IsSweetHome3dSpec(const std::string& spec);
// The catalog files of a spec: every *.sh3f of io::SweetHome3dCatalogDir() for "sweethome3d", else
// the file itself. Throws InputError as io::SweetHome3dCatalogFiles, or naming a missing file.
std::vector<std::string> SweetHome3dCatalogsOf(const std::string& spec);

struct SweetHome3dCatalogSummary {
  std::string file;          // absolute path
  std::string name;          // catalog name= ("Kator Legaz catalog")
  std::string license;       // license=
  std::string license_text;  // LICENSE.TXT
  int pieces = 0;            // in the catalog
  int models = 0;            // made sources
};

struct SweetHome3dSources {
  std::vector<ModelSource> sources;
  std::vector<SweetHome3dCatalogSummary> catalogs;
  // "<catalog stem>: <id> (<name>, <sh3d category>)" of the pieces a `skip` rule left out, and of
  // those no rule matched (also left out: the map should say what they are).
  std::vector<std::string> skipped;
  std::vector<std::string> unmatched;
  std::map<std::string, int> models_per_category;
};

// Sources of the pieces of `catalog_files` under `map`: each piece is looked up with its English
// name as ModelIdentity::name, its Sweet Home 3D category as the one label, its model path as the
// one URI and its id as model_id. Throws InputError as io::LoadSweetHome3dCatalog.
SweetHome3dSources SweetHome3dModelSources(const std::vector<std::string>& catalog_files, const io::CategoryMap& map);

}  // namespace objscan::recognition
