#include "objscan/recognition/model_database.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "objscan/common/error.h"
#include "objscan/io/binary_file.h"

namespace objscan::recognition {

const char* EntryKindName(EntryKind kind) {
  switch (kind) {
    case EntryKind::kFullModel: return "model";
    case EntryKind::kComponent: return "component";
    case EntryKind::kPair: return "pair";
  }
  return "unknown";
}

namespace {

constexpr io::BinaryFileFormat kFormat = {"OBJSCDB\n", ModelDatabase::kFormatVersion, "model database",
                                          "rebuild it with objscan db build"};
using Writer = io::BinaryWriter;
using Reader = io::BinaryReader;

world::Category ReadCategory(Reader* r, const char* what) {
  const std::string name = r->String(what);
  const auto c = world::ParseCategory(name);
  if (!c) r->Fail(std::string("unknown category '") + name + "' in " + what);
  return *c;
}

}  // namespace

void ModelDatabase::Save(const std::string& path) const {
  Writer w;
  // Settings.
  w.Pod<std::int32_t>(settings_.keypoints.num_keypoints);
  w.Pod<std::int32_t>(settings_.keypoints.lloyd_iterations);
  w.Pod<double>(settings_.keypoints.density_voxel_m);
  w.Pod<std::int32_t>(settings_.keypoints.max_relaxation_points);
  w.Pod<std::uint64_t>(settings_.keypoint_seed);
  w.String(settings_.descriptor.type);
  w.Pod<double>(settings_.descriptor.support_radius_m);
  w.Pod<double>(settings_.descriptor.normal_radius_m);
  w.Pod<double>(settings_.descriptor.surface_voxel_m);
  w.Pod<std::int32_t>(settings_.bow.height_bands);
  w.Pod<std::int32_t>(settings_.bow.radial_rings);
  w.Pod<double>(settings_.bow.spatial_weight);
  w.Pod<std::uint32_t>(static_cast<std::uint32_t>(settings_.bow.absolute_height_edges_m.size()));
  w.Array(settings_.bow.absolute_height_edges_m.data(), settings_.bow.absolute_height_edges_m.size());
  w.Pod<double>(settings_.bow.absolute_weight);
  w.Pod<double>(settings_.bow.up_normal_min_z);
  w.Pod<double>(settings_.bow.size_weight);
  w.Pod<double>(settings_.bow.height_bin_ratio);
  w.Pod<double>(settings_.bow.floor_gap_bin_m);
  // Vocabulary.
  w.Pod<std::int32_t>(vocabulary_.dimension());
  w.Pod<std::int32_t>(vocabulary_.soft_assignments());
  w.Pod<float>(vocabulary_.sigma2());
  w.Pod<std::uint32_t>(static_cast<std::uint32_t>(vocabulary_.words().size()));
  w.Array(vocabulary_.words().data(), vocabulary_.words().size());
  // Models.
  w.Pod<std::uint32_t>(static_cast<std::uint32_t>(models_.size()));
  for (const auto& m : models_) {
    w.String(m.name);
    w.String(world::CategoryName(m.category));
    w.String(m.source);
    w.Pod<std::int32_t>(m.full_entry);
    w.Pod<std::uint32_t>(static_cast<std::uint32_t>(m.support_heights_m.size()));
    w.Array(m.support_heights_m.data(), m.support_heights_m.size());
    w.String(m.creator);
    w.String(m.license);
    w.Points(m.mesh.vertices);
    w.Pod<std::uint32_t>(static_cast<std::uint32_t>(m.mesh.triangles.size()));
    static_assert(sizeof(Eigen::Vector3i) == 3 * sizeof(std::int32_t), "Vector3i must be packed");
    w.Array(reinterpret_cast<const std::int32_t*>(m.mesh.triangles.data()), 3 * m.mesh.triangles.size());
  }
  // Entries.
  w.Pod<std::uint32_t>(static_cast<std::uint32_t>(entries_.size()));
  for (const auto& e : entries_) {
    w.Pod<std::uint8_t>(static_cast<std::uint8_t>(e.kind));
    w.String(world::CategoryName(e.category));
    w.String(e.name);
    w.Pod<std::int32_t>(e.model_index);
    if (e.kind == EntryKind::kFullModel) {
      w.Points(e.points);
      w.Points(e.normals);
    } else {
      // Components and pairs are subsets of their model's full scan: store indices only.
      w.Pod<std::uint32_t>(static_cast<std::uint32_t>(e.point_indices.size()));
      w.Array(e.point_indices.data(), e.point_indices.size());
    }
    w.Points(e.keypoints);
    w.Points(e.keypoint_normals);
    w.Pod<std::uint32_t>(static_cast<std::uint32_t>(e.bow.size()));
    for (const auto& b : e.bow) {
      w.Pod<std::uint32_t>(b.bin);
      w.Pod<float>(b.value);
    }
  }
  io::WriteBinaryFile(path, kFormat, w.buffer());
}

namespace {

std::vector<char> ReadVerifiedFile(const std::string& path, std::uint64_t max_memory_bytes) {
  return io::ReadVerifiedBinaryFile(path, kFormat, max_memory_bytes, ModelDatabase::kMemoryPerFileByte,
                                    "recognition.max_database_memory_mb");
}

}  // namespace

void ModelDatabase::Verify(const std::string& path, std::uint64_t max_memory_bytes) {
  ReadVerifiedFile(path, max_memory_bytes);
}

ModelDatabase ModelDatabase::Load(const std::string& path, std::uint64_t max_memory_bytes) {
  std::vector<char> bytes = ReadVerifiedFile(path, max_memory_bytes);
  ModelDatabase db = Parse(bytes.data() + io::kBinaryHeaderSize, bytes.size() - io::kBinaryHeaderSize, path);
  // The file's bytes are as large as the entries parsed from them: gone before the indices are built.
  std::vector<char>().swap(bytes);
  db.Finalize();
  return db;
}

ModelDatabase ModelDatabase::FromPayload(const char* payload, std::size_t size, const std::string& path) {
  ModelDatabase db = Parse(payload, size, path);
  db.Finalize();
  return db;
}

std::vector<Eigen::Vector3f> ModelDatabase::EntryPoints(int entry) const {
  if (entry < 0 || entry >= static_cast<int>(entries_.size())) return {};
  const DatabaseEntry& e = entries_[static_cast<std::size_t>(entry)];
  if (e.kind == EntryKind::kFullModel) return e.points;
  std::vector<Eigen::Vector3f> points;
  if (e.model_index < 0 || e.model_index >= static_cast<int>(models_.size())) return points;
  const int full_entry = models_[static_cast<std::size_t>(e.model_index)].full_entry;
  if (full_entry < 0 || full_entry >= static_cast<int>(entries_.size())) return points;
  const std::vector<Eigen::Vector3f>& full = entries_[static_cast<std::size_t>(full_entry)].points;
  points.reserve(e.point_indices.size());
  for (const std::int32_t j : e.point_indices) {
    if (j >= 0 && j < static_cast<std::int32_t>(full.size())) points.push_back(full[static_cast<std::size_t>(j)]);
  }
  return points;
}

ModelDatabase ModelDatabase::Parse(const char* payload, std::size_t size, const std::string& path) {
  Reader r(payload, size, path, kFormat.kind);
  ModelDatabase db;
  DatabaseSettings& s = db.settings_;
  s.keypoints.num_keypoints = r.Pod<std::int32_t>("settings");
  s.keypoints.lloyd_iterations = r.Pod<std::int32_t>("settings");
  s.keypoints.density_voxel_m = r.Pod<double>("settings");
  s.keypoints.max_relaxation_points = r.Pod<std::int32_t>("settings");
  s.keypoint_seed = r.Pod<std::uint64_t>("settings");
  s.descriptor.type = r.String("settings");
  s.descriptor.support_radius_m = r.Pod<double>("settings");
  s.descriptor.normal_radius_m = r.Pod<double>("settings");
  s.descriptor.surface_voxel_m = r.Pod<double>("settings");
  s.bow.height_bands = r.Pod<std::int32_t>("settings");
  s.bow.radial_rings = r.Pod<std::int32_t>("settings");
  s.bow.spatial_weight = r.Pod<double>("settings");
  s.bow.absolute_height_edges_m.resize(r.Count(8, "settings"));
  r.Array(s.bow.absolute_height_edges_m.data(), s.bow.absolute_height_edges_m.size(), "settings");
  s.bow.absolute_weight = r.Pod<double>("settings");
  s.bow.up_normal_min_z = r.Pod<double>("settings");
  s.bow.size_weight = r.Pod<double>("settings");
  s.bow.height_bin_ratio = r.Pod<double>("settings");
  s.bow.floor_gap_bin_m = r.Pod<double>("settings");
  try {
    s.keypoints.Validate();
    s.descriptor.Validate();
    s.bow.Validate();
  } catch (const ConfigError& e) {
    r.Fail(std::string("settings: ") + e.what());
  }

  const auto dim = r.Pod<std::int32_t>("vocabulary");
  const auto soft = r.Pod<std::int32_t>("vocabulary");
  const auto sigma2 = r.Pod<float>("vocabulary");
  const std::uint32_t n_words_floats = r.Count(4, "vocabulary");
  if (dim <= 0 || n_words_floats == 0 || n_words_floats % dim != 0 || soft < 1 || soft > 8 || !(sigma2 > 0.f))
    r.Fail("vocabulary");
  std::vector<float> words(n_words_floats);
  r.Array(words.data(), words.size(), "vocabulary");
  db.vocabulary_ = Vocabulary(dim, std::move(words), sigma2, soft);
  // Histogram bins are 32-bit: words x cells (the settings are validated, so NumCells() is small).
  if (static_cast<std::uint64_t>(db.vocabulary_.num_words()) * static_cast<std::uint64_t>(s.bow.NumCells()) >
      (std::uint64_t{1} << 31)) {
    r.Fail("vocabulary: too many words for 32-bit histogram bins");
  }
  const std::uint32_t num_bins = db.NumBins();

  // At least: name, category, source, full entry, support heights, creator, licence, mesh vertices
  // and triangles (a count each).
  const std::uint32_t n_models = r.Count(9 * 4, "models");
  db.models_.resize(n_models);
  for (auto& m : db.models_) {
    m.name = r.String("model name");
    m.category = ReadCategory(&r, "model category");
    m.source = r.String("model source");
    m.full_entry = r.Pod<std::int32_t>("model");
    m.support_heights_m.resize(r.Count(sizeof(float), "model support heights"));
    r.Array(m.support_heights_m.data(), m.support_heights_m.size(), "model support heights");
    for (float h : m.support_heights_m) {
      if (!std::isfinite(h)) r.Fail("model support heights");
    }
    m.creator = r.String("model creator");
    m.license = r.String("model license");
    m.mesh.vertices = r.Points("model mesh vertices");
    for (const auto& v : m.mesh.vertices) {
      if (!v.allFinite()) r.Fail("model mesh vertices");
    }
    const std::uint32_t n_triangles = r.Count(12, "model mesh triangles");
    m.mesh.triangles.resize(n_triangles);
    r.Array(reinterpret_cast<std::int32_t*>(m.mesh.triangles.data()), 3 * static_cast<std::size_t>(n_triangles),
            "model mesh triangles");
    const auto n_vertices = static_cast<std::int32_t>(m.mesh.vertices.size());
    for (const auto& t : m.mesh.triangles) {
      if ((t.array() < 0).any() || (t.array() >= n_vertices).any()) r.Fail("model mesh triangle index");
    }
  }
  const std::uint32_t n_entries = r.Count(1 + 4 + 4 + 4 + 4 + 4 + 4, "entries");
  db.entries_.resize(n_entries);
  for (std::uint32_t i = 0; i < n_entries; ++i) {
    DatabaseEntry& e = db.entries_[i];
    const auto kind = r.Pod<std::uint8_t>("entry kind");
    if (kind > 2) r.Fail("entry kind");
    e.kind = static_cast<EntryKind>(kind);
    e.category = ReadCategory(&r, "entry category");
    e.name = r.String("entry name");
    e.model_index = r.Pod<std::int32_t>("entry");
    if (e.model_index < 0 || e.model_index >= static_cast<std::int32_t>(n_models)) r.Fail("entry model index");
    if (e.kind == EntryKind::kFullModel) {
      e.points = r.Points("entry points");
      e.normals = r.Points("entry normals");
      if (e.normals.size() != e.points.size()) r.Fail("entry normals");
    } else {
      const std::uint32_t n = r.Count(4, "entry point indices");
      e.point_indices.resize(n);
      r.Array(e.point_indices.data(), n, "entry point indices");
    }
    e.keypoints = r.Points("entry keypoints");
    e.keypoint_normals = r.Points("entry keypoint normals");
    if (e.keypoint_normals.size() != e.keypoints.size()) r.Fail("entry keypoint normals");
    const std::uint32_t n_bins = r.Count(8, "entry histogram");
    e.bow.resize(n_bins);
    for (auto& b : e.bow) {
      b.bin = r.Pod<std::uint32_t>("entry histogram");
      b.value = r.Pod<float>("entry histogram");
      if (b.bin >= num_bins) r.Fail("histogram bin out of range");
    }
  }
  if (!r.AtEnd()) r.Fail("trailing data");
  // Resolve models, check the indices of components and pairs into their model's full scan.
  for (const auto& m : db.models_) {
    if (m.full_entry < 0 || m.full_entry >= static_cast<std::int32_t>(n_entries) ||
        db.entries_[m.full_entry].kind != EntryKind::kFullModel)
      r.Fail("model full entry");
  }
  for (const auto& e : db.entries_) {
    if (e.kind == EntryKind::kFullModel) continue;
    const DatabaseEntry& full = db.entries_[db.models_[e.model_index].full_entry];
    for (const std::int32_t j : e.point_indices) {
      if (j < 0 || j >= static_cast<std::int32_t>(full.points.size())) r.Fail("entry point index");
    }
  }
  return db;
}

void ModelDatabase::Finalize() {
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    DatabaseEntry& e = entries_[i];
    if (e.bounds.Empty()) {
      for (const auto& p : EntryPoints(static_cast<int>(i))) e.bounds.Extend(p.cast<double>());
    }
  }
  std::vector<const SparseHistogram*> all_h, full_h;
  std::vector<int> all_ids, full_ids;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    all_h.push_back(&entries_[i].bow);
    all_ids.push_back(static_cast<int>(i));
    if (entries_[i].kind == EntryKind::kFullModel) {
      full_h.push_back(&entries_[i].bow);
      full_ids.push_back(static_cast<int>(i));
    }
  }
  all_index_.Build(all_h, all_ids, NumBins());
  full_model_index_.Build(full_h, full_ids, NumBins());
  keypoint_targets_.clear();
  keypoint_targets_.reserve(entries_.size());
  for (const auto& e : entries_) {
    keypoint_targets_.emplace_back(e.keypoints);
    keypoint_targets_.back().EnableDistanceGrid(kGridTruncationM, kGridMaxVertices, kGridMinSpacingM);
    // The nearest grid costs about a millisecond to build and repays it over many alignments: full
    // models are aligned at every object query, most component and pair entries only a few times
    // in a run. (A fixed rule per entry kind, so results never depend on which query came first.)
    if (e.kind != EntryKind::kFullModel) keypoint_targets_.back().DisableNearestGrid();
  }
  finalized_ = true;
}

}  // namespace objscan::recognition
