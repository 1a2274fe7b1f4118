#pragma once
// Building the model database (paper §4.2 "3D model database"): each source model is normalised
// (metres, Z up, standing on z = 0, centred in XY), scanned virtually from rings of views, fused and
// pre-segmented like the live system; its full scan, every component and every adjacent pair become
// entries carrying the model's category. Then the vocabulary is trained on the entries' descriptors
// and every entry gets its spatial bag-of-words histogram.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/progress.h"
#include "objscan/geometry/mesh.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/virtual_scan.h"

namespace objscan::recognition {

// Bump whenever a change to the builder changes the databases it builds (the cached default database
// of objscan run is named after it and the build options, so a stale cache is never reused).
// 2: models carry support heights (procedural ones from rooms the database generates).
// 3: models carry their decimated mesh (DatabaseModel::mesh).
constexpr int kDatabaseBuilderRevision = 3;

struct DatabaseBuildOptions {
  VirtualScanOptions scan;
  // Database scans are noise-free: the models are clean and their points should describe the
  // shape itself; live queries carry sensor noise, which the fused map mostly averages out.
  bool scan_noise = false;
  double store_voxel_m = 0.03;   // stored entry points (for consumers: NBV, model replacement)
  int min_entry_points = 40;     // components with fewer surface elements are not entries
  // Each model's mesh is stored in the database (DatabaseModel::mesh) with at most this many
  // triangles: kept as it is when it has that few, else clustered on the finest grid of
  // stored_mesh_min_cell_m * 1.25^k that fits (geometry::DecimateToTriangleBudget).
  int stored_mesh_max_triangles = 3000;
  double stored_mesh_min_cell_m = 0.01;
  bool include_components = true;
  bool include_pairs = true;
  KeypointOptions keypoints;
  std::uint64_t keypoint_seed = 1;
  DescriptorOptions descriptor;
  VocabularyOptions vocabulary;
  SpatialBowOptions bow;
  std::uint64_t seed = 1;  // vocabulary sampling and seeding, scan noise when on
  int threads = 0;         // models scanned in parallel; 0 = hardware concurrency. Same result.

  template <class V>
  void Visit(V& v) {
    v("scan", scan);
    v("scan_noise", scan_noise);
    v("store_voxel_m", store_voxel_m);
    v("min_entry_points", min_entry_points);
    v("stored_mesh_max_triangles", stored_mesh_max_triangles);
    v("stored_mesh_min_cell_m", stored_mesh_min_cell_m);
    v("include_components", include_components);
    v("include_pairs", include_pairs);
    v("keypoints", keypoints);
    v("keypoint_seed", keypoint_seed);
    v("descriptor", descriptor);
    v("vocabulary", vocabulary);
    v("bow", bow);
    v("seed", seed);
    v("threads", threads);
  }
  void Validate() const;
};

// One model to put into the database.
struct ModelSource {
  world::Category category = world::Category::kOther;
  std::string name;    // unique in the database, e.g. "chair/chair_armless_s17" or "chair/0042"
  std::string source;  // "procedural/<category>/<model seed>" or the mesh file path
  // Returns the mesh in metres with Z up (any placement: the builder normalises it). Called once,
  // possibly on a worker thread; throws InputError naming the file on failure.
  std::function<geometry::TriangleMesh()> load_mesh;
  // Heights above the floor at which the model (or, for procedural models, its category) stands in
  // the scenes it comes from (DatabaseModel::support_heights_m); empty when unknown.
  std::vector<float> support_heights_m;
  // Credits carried into DatabaseModel (creator and licence of a catalog's model; empty when unknown).
  std::string creator;
  std::string license;
};

// Models of a folder: <category>/<name>.<ext> and ModelNet-style <category>/{train,test}/<name>.<ext>
// for every mesh extension io::LoadMesh reads. Folder names are category names (as in
// world::ParseCategory, plus a few common aliases such as "bookshelf" and "bathroom_sink"); folders
// with other names are listed in *skipped_folders. Throws InputError naming the folder when it is
// missing or yields no model.
std::vector<ModelSource> ModelSourcesFromFolder(const std::string& folder, std::vector<std::string>* skipped_folders);

// How a procedural database draws its models of each category.
enum class ProceduralSampling {
  // The first `variants` database seeds: DatabaseModelSeed(first_index) ... (+ variants - 1).
  kFirstSeeds,
  // `variants` models that spread over the category's shapes: from a pool of the first
  // variants * kSamplingPoolPerVariant seeds, greedy k-medoids on the models' bounding-box size
  // (height, width, depth, each over its spread in the pool). Eight random draws of a category
  // with six styles miss some of them (the first eight cabinets hold no filing cabinet and no
  // pantry); medoids cover every part of the shape range in proportion to how common it is.
  kSpread,
  // Every style of the generator in turn: the style is the first word of a model's name after its
  // category ("cabinet_filing_s7" -> "filing"); each model is the first unused one of the pool
  // (the first variants * kSamplingPoolPerVariant seeds) among the styles drawn least so far, styles
  // taken in the order they first appear in the pool.
  kStyles,
  // As kStyles, the same number of models per style, but each style's are the greedy size medoids
  // (as kSpread) of its models in the pool.
  kStyleMedoids,
};
constexpr int kSamplingPoolPerVariant = 4;
// "first-seeds" / "spread" / "styles" / "style-medoids"; ParseProceduralSampling throws InputError naming `field` otherwise.
const char* ProceduralSamplingName(ProceduralSampling sampling);
ProceduralSampling ParseProceduralSampling(const std::string& name, const std::string& field);

// `variants` procedural models per furniture category, named "<category>/<k>" for the model of seed
// DatabaseModelSeed(first_index + k). Their support heights are those of their category in
// ProceduralSupportHeights().
std::vector<ModelSource> ProceduralModelSources(int variants, std::uint64_t first_index = 0,
                                                ProceduralSampling sampling = ProceduralSampling::kFirstSeeds);

// Where the procedural generator stands each furniture category: the heights above the floor of the
// bottoms of its objects in kSupportRoomsPerCategory rooms of every room category, drawn from scene
// seeds with the top bit set (no benchmark room's seed), indexed by world::CategoryId.
constexpr int kSupportRoomsPerCategory = 3;
std::vector<std::vector<float>> ProceduralSupportHeights();

// Greedy k-medoids: `count` indices into `features` (rows of equal length), ascending. Each step adds
// the row that most lowers the summed distance of all rows to their nearest chosen one (the lowest
// index on ties), so the same rows give the same choice.
std::vector<int> GreedyMedoids(const std::vector<std::vector<double>>& features, int count);

// The mesh of a database model in the database frame: the one stored in the database
// (DatabaseModel::mesh, decimated) when there is one, else loaded from its `source` string
// (procedural, a Sweet Home 3D piece or a mesh file) and normalised the way the builder does. Throws
// InputError naming the model and its source when it has no stored mesh and the source cannot be
// loaded (a world's object, "<world>#<object>", or a file that is gone).
geometry::TriangleMesh LoadModelSourceMesh(const DatabaseModel& model);

// Builds (and finalizes) the database. Throws InputError when a model cannot be loaded or no entry
// results. Models whose scan has fewer than min_entry_points points are left out.
ModelDatabase BuildDatabase(const std::vector<ModelSource>& sources, const DatabaseBuildOptions& options,
                            const ProgressCallback& progress = nullptr);

// The same from models scanned already (surface with normals and per-point component labels, and the
// component graph; an empty graph gives full-model entries only). `scan` options are unused.
struct ScannedModel {
  world::Category category = world::Category::kOther;
  std::string name;
  std::string source;
  ModelScan scan;  // in the database frame (Z up, standing on z = 0)
  std::vector<float> support_heights_m;
};
ModelDatabase BuildDatabaseFromScans(const std::vector<ScannedModel>& models, const DatabaseBuildOptions& options,
                                     const ProgressCallback& progress = nullptr);

}  // namespace objscan::recognition
