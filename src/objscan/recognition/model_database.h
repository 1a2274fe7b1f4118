#pragma once
// The 3D model database M (paper §4.2): for every source model its full virtual scan, every
// pre-segmented component and every pair of adjacent components, all labelled with the model's
// category, each with keypoints and a spatial bag-of-words histogram; plus the vocabulary and the
// settings used to describe them (queries must be described the same way). Stored as a versioned
// little-endian binary file.
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/geometry/aabb.h"
#include "objscan/geometry/mesh.h"
#include "objscan/recognition/alignment.h"
#include "objscan/recognition/descriptor.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/retrieval.h"
#include "objscan/recognition/spatial_bow.h"
#include "objscan/recognition/vocabulary.h"
#include "objscan/world/category.h"

namespace objscan::recognition {

enum class EntryKind : std::uint8_t { kFullModel = 0, kComponent = 1, kPair = 2 };
const char* EntryKindName(EntryKind kind);

// Which entries a query is compared with (paper §6.1): a pre-segmented component against every
// entry, a post-segmented object against full models only.
enum class RetrievalScope { kAllEntries, kFullModels };

struct DatabaseEntry {
  EntryKind kind = EntryKind::kFullModel;
  world::Category category = world::Category::kOther;
  std::string name;                        // model name, "+/c<k>" for a component, "+/p<a>-<b>" for a pair
  std::int32_t model_index = -1;           // into ModelDatabase::models()
  // Full models: surface points in the model frame (Z up, on z = 0) and one normal per point.
  // Components and pairs leave both empty: their points are the full entry's at `point_indices`
  // (ModelDatabase::EntryPoints), so a loaded database holds each surface point once.
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::int32_t> point_indices; // components and pairs: indices of `points` in the model's full entry
  std::vector<Eigen::Vector3f> keypoints;  // n_p Lloyd keypoints
  std::vector<Eigen::Vector3f> keypoint_normals;  // unit, outward, one per keypoint
  SparseHistogram bow;
  geometry::Aabb3 bounds;                  // of `points`: the upright frame of the spatial BoW
};

struct DatabaseModel {
  std::string name;
  world::Category category = world::Category::kOther;
  // Where the model came from (provenance): a mesh file path, "procedural/<category>/<seed>",
  // "sweethome3d:<catalog>#<piece id>" or "<world file>#<object>" (a world's object, loadable from
  // nowhere but `mesh`).
  std::string source;
  std::int32_t full_entry = -1;  // index of its full-model entry
  // Where models like it stand in the scenes the database comes from: the height of the bottom above
  // the floor, one per placement seen (a monitor on desks, a lamp on the floor and on night stands);
  // empty when unknown (models from a folder of meshes).
  std::vector<float> support_heights_m;
  // Credits of a model made by someone (Sweet Home 3D catalogs: the piece's creator and its catalog's
  // licence); empty when not known (procedural models, plain mesh folders).
  std::string creator;
  std::string license;
  // The mesh the builder scanned, in the database frame (normalised: Z up, standing on z = 0, centred
  // in XY), decimated to at most DatabaseBuildOptions::stored_mesh_max_triangles triangles
  // (geometry/mesh_decimation.h), so a database gives back every model's mesh without its source
  // files. Empty when built from scans (BuildDatabaseFromScans): LoadModelSourceMesh then loads
  // `source`.
  geometry::TriangleMesh mesh;
};

// How the entries were described; a query is described with the same settings.
struct DatabaseSettings {
  KeypointOptions keypoints;
  std::uint64_t keypoint_seed = 1;
  DescriptorOptions descriptor;
  SpatialBowOptions bow;
};

class ModelDatabase {
 public:
  // 2: spatial BoW with absolute-height, normal and size words (settings layout changed).
  // 3: each model's support heights.
  // 4: each model's creator and licence.
  // 5: each model's (decimated) mesh: u32 vertex count, float x y z per vertex, u32 triangle count,
  //    i32 a b c per triangle (indices checked on load); counts of 0 when none is stored.
  static constexpr std::uint32_t kFormatVersion = 5;

  ModelDatabase() = default;
  ModelDatabase(ModelDatabase&&) = default;
  ModelDatabase& operator=(ModelDatabase&&) = default;

  // Writes atomically (io/atomic_file.h: temporary file, fsync, rename, folder sync). The header
  // carries the payload's size and checksum. Throws InputError naming the path on failure.
  void Save(const std::string& path) const;
  // Throws InputError naming the path for a missing, foreign, old, corrupt or truncated file, and,
  // when max_memory_bytes > 0, for a database that would take more memory than that once loaded
  // (kMemoryPerFileByte times its file), before reading it (recognition.max_database_memory_mb).
  static ModelDatabase Load(const std::string& path, std::uint64_t max_memory_bytes = 0);
  // The part of Load after the header's checks: parses a payload (the file's bytes after the header)
  // already in memory; errors name `path`. What the loader fuzzer drives (fuzz/fuzz_input.h).
  static ModelDatabase FromPayload(const char* payload, std::size_t size, const std::string& path);
  // The checks of Load that need no parsing: magic, format version, size and checksum of the whole
  // payload (and the memory limit). Cheap next to Load (one pass over the bytes); throws the same
  // InputError Load would for a truncated, extended or bit-flipped file.
  static void Verify(const std::string& path, std::uint64_t max_memory_bytes = 0);
  // Memory of a loaded database per byte of its file, at most about: the file's bytes while it is
  // parsed, then the inverted indices and the keypoints' kd-trees (the built-in real database, 190 MB
  // on disk, reached 760 MB when components and pairs still copied their points out of the full
  // entry; see EntryPoints).
  static constexpr std::uint64_t kMemoryPerFileByte = 4;

  DatabaseSettings& mutable_settings() { return settings_; }
  const DatabaseSettings& settings() const { return settings_; }
  void set_vocabulary(Vocabulary vocabulary) { vocabulary_ = std::move(vocabulary); }
  const Vocabulary& vocabulary() const { return vocabulary_; }
  std::vector<DatabaseModel>& mutable_models() { return models_; }
  const std::vector<DatabaseModel>& models() const { return models_; }
  std::vector<DatabaseEntry>& mutable_entries() { return entries_; }
  const std::vector<DatabaseEntry>& entries() const { return entries_; }

  // The surface points of an entry in the model frame: a full model's own, a component's or a pair's
  // gathered from its model's full entry (empty for an index out of range).
  std::vector<Eigen::Vector3f> EntryPoints(int entry) const;

  // Builds the inverted indices and per-entry alignment targets (their distance grids are built on
  // first use, never stored); call after changing entries (Load calls it).
  void Finalize();
  // The entries' distance grids: truncated at this distance (the default initial_truncation_m), at
  // most this many one-byte vertices per entry (~15 MB for 2000 entries), spacing at least this.
  static constexpr float kGridTruncationM = 0.15f;
  static constexpr int kGridMaxVertices = 16384;
  static constexpr float kGridMinSpacingM = 0.03f;
  bool finalized() const { return finalized_; }
  const InvertedIndex& index(RetrievalScope scope) const {
    return scope == RetrievalScope::kFullModels ? full_model_index_ : all_index_;
  }
  // Kd-tree over an entry's keypoints (the target of alignment and of objectness).
  const AlignmentTarget& keypoint_target(int entry) const { return keypoint_targets_[entry]; }

  std::uint32_t NumBins() const {
    return settings_.bow.NumBins(vocabulary_.num_words());
  }

 private:
  // FromPayload without Finalize, so that Load can free the file's bytes before building indices.
  static ModelDatabase Parse(const char* payload, std::size_t size, const std::string& path);

  DatabaseSettings settings_;
  Vocabulary vocabulary_;
  std::vector<DatabaseModel> models_;
  std::vector<DatabaseEntry> entries_;
  bool finalized_ = false;
  InvertedIndex all_index_, full_model_index_;
  std::vector<AlignmentTarget> keypoint_targets_;
};

}  // namespace objscan::recognition
