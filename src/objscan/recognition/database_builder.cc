#include "objscan/recognition/database_builder.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/geometry/mesh_decimation.h"
#include "objscan/io/mesh_io.h"
#include "objscan/io/sweethome3d.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/common/parallel_for.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::recognition {

void DatabaseBuildOptions::Validate() const {
  scan.Validate();
  config::RequirePositive("recognition.database.store_voxel_m", store_voxel_m);
  config::Require(min_entry_points >= 3, "recognition.database.min_entry_points", "must be at least 3");
  config::Require(stored_mesh_max_triangles >= 1, "recognition.database.stored_mesh_max_triangles",
                  "must be at least 1");
  config::RequirePositive("recognition.database.stored_mesh_min_cell_m", stored_mesh_min_cell_m);
  keypoints.Validate();
  descriptor.Validate();
  vocabulary.Validate();
  bow.Validate();
  config::RequireNonNegative("recognition.database.threads", threads);
}

namespace {

namespace fs = std::filesystem;

std::optional<world::Category> CategoryOfFolder(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  static const std::map<std::string, std::string> kAliases = {
      {"bookshelf", "shelves"}, {"bookcase", "shelves"},     {"shelf", "shelves"},
      {"nightstand", "night_stand"}, {"tvstand", "tv_stand"}, {"bathroom_sink", "sink"},
      {"couch", "sofa"},        {"fridge", "refrigerator"},   {"wardrobe", "cabinet"},
      {"tv", "monitor"},        {"television", "monitor"},    {"bath", "bathtub"}};
  if (auto it = kAliases.find(name); it != kAliases.end()) name = it->second;
  const auto c = world::ParseCategory(name);
  if (c && !world::IsStructural(*c)) return c;
  return std::nullopt;
}

std::vector<fs::path> SortedEntries(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Database entry under construction (before the vocabulary exists).
struct PendingEntry {
  DatabaseEntry entry;
  std::vector<std::uint8_t> descriptors;  // quantised, keypoints x dimension
  std::vector<Eigen::Vector3f> keypoint_normals;
  geometry::Aabb3 bow_bounds;             // bounds of the full-resolution points (like a query's)
};

struct PendingModel {
  bool ok = false;
  std::vector<PendingEntry> entries;  // full model first
};

constexpr float kDescriptorQuantum = 2.5f;  // FPFH bins are in [0, 100]: 0.4 resolution in a byte

std::vector<Eigen::Vector3f> Select(const std::vector<Eigen::Vector3f>& pts, const std::vector<int>& idx) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(idx.size());
  for (int i : idx) out.push_back(pts[i]);
  return out;
}

PendingModel DescribeScan(const ModelScan& scan, world::Category category, const std::string& name,
                          int model_index, const DatabaseBuildOptions& options, const DescriptorExtractor& descriptor) {
  PendingModel result;
  const geometry::PointCloud& surface = scan.surface;
  if (static_cast<int>(surface.size()) < options.min_entry_points) return result;

  // Point sets of the entries (full resolution) and the labels each covers.
  struct Part {
    EntryKind kind;
    std::string suffix;
    std::vector<std::int32_t> labels;  // empty = everything
    const std::vector<Eigen::Vector3f>* points;
    const std::vector<Eigen::Vector3f>* normals;
    std::vector<Eigen::Vector3f> owned, owned_normals;
  };
  std::vector<Part> parts;
  parts.push_back({EntryKind::kFullModel, "", {}, &surface.points, &surface.normals, {}, {}});
  std::vector<std::int32_t> kept_labels;
  if (options.include_components) {
    for (const auto& c : scan.components.components()) {
      if (static_cast<int>(c.points.size()) < options.min_entry_points) continue;
      kept_labels.push_back(c.label);
      parts.push_back({EntryKind::kComponent, "/c" + std::to_string(c.label), {c.label}, &c.points, &c.normals, {}, {}});
    }
  }
  if (options.include_pairs) {
    for (const auto& [a, b] : scan.components.Edges()) {
      if (!std::binary_search(kept_labels.begin(), kept_labels.end(), a) ||
          !std::binary_search(kept_labels.begin(), kept_labels.end(), b))
        continue;
      Part p{EntryKind::kPair, "/p" + std::to_string(a) + "-" + std::to_string(b), {a, b}, nullptr, nullptr, {}, {}};
      const auto* ca = scan.components.Find(a);
      const auto* cb = scan.components.Find(b);
      p.owned = ca->points;
      p.owned.insert(p.owned.end(), cb->points.begin(), cb->points.end());
      p.owned_normals = ca->normals;
      p.owned_normals.insert(p.owned_normals.end(), cb->normals.begin(), cb->normals.end());
      parts.push_back(std::move(p));
    }
  }
  for (auto& p : parts) {
    if (!p.points) {
      p.points = &p.owned;
      p.normals = &p.owned_normals;
    }
  }

  // Stored points: the full scan thinned; components and pairs index into it.
  const std::vector<int> thinned = VoxelThin(surface.points, options.store_voxel_m);
  std::vector<Eigen::Vector3f> stored_points = Select(surface.points, thinned);
  std::vector<Eigen::Vector3f> stored_normals = Select(surface.normals, thinned);

  // Keypoints per entry, then all descriptors of the model in one batch (shared support surface:
  // the full scan, as a live component is described within the scene surface around it).
  std::vector<Eigen::Vector3f> all_keypoints;
  std::vector<std::size_t> first_keypoint;
  for (auto& p : parts) {
    PendingEntry pe;
    DatabaseEntry& e = pe.entry;
    e.kind = p.kind;
    e.category = category;
    e.name = name + p.suffix;
    e.model_index = model_index;
    Rng rng(options.keypoint_seed);  // the same seed a query uses
    const std::vector<int> keypoint_indices = SampleKeypointsLloyd(*p.points, options.keypoints, &rng);
    e.keypoints = Select(*p.points, keypoint_indices);
    pe.keypoint_normals = Select(*p.normals, keypoint_indices);
    for (const auto& q : *p.points) pe.bow_bounds.Extend(q.cast<double>());
    if (p.kind == EntryKind::kFullModel) {
      e.points = stored_points;
      e.normals = stored_normals;
      for (const auto& q : e.points) e.bounds.Extend(q.cast<double>());
    } else {
      for (std::size_t k = 0; k < thinned.size(); ++k) {
        const std::int32_t label = surface.labels[thinned[k]];
        if (std::find(p.labels.begin(), p.labels.end(), label) != p.labels.end()) {
          e.point_indices.push_back(static_cast<std::int32_t>(k));
          e.bounds.Extend(stored_points[k].cast<double>());
        }
      }
    }
    first_keypoint.push_back(all_keypoints.size());
    all_keypoints.insert(all_keypoints.end(), e.keypoints.begin(), e.keypoints.end());
    result.entries.push_back(std::move(pe));
  }
  std::vector<float> descriptors;
  descriptor.Compute(surface, all_keypoints, &descriptors);
  const int dim = descriptor.Dimension();
  for (std::size_t i = 0; i < result.entries.size(); ++i) {
    PendingEntry& pe = result.entries[i];
    const std::size_t n = pe.entry.keypoints.size() * dim;
    pe.descriptors.resize(n);
    const float* src = &descriptors[first_keypoint[i] * dim];
    for (std::size_t k = 0; k < n; ++k)
      pe.descriptors[k] = static_cast<std::uint8_t>(std::clamp(std::lround(src[k] * kDescriptorQuantum), 0L, 255L));
  }
  // Drop component/pair entries that ended up without stored points (all smaller than a store voxel).
  result.entries.erase(std::remove_if(result.entries.begin() + 1, result.entries.end(),
                                      [](const PendingEntry& pe) { return pe.entry.point_indices.empty(); }),
                       result.entries.end());
  result.ok = true;
  return result;
}

}  // namespace

std::vector<ModelSource> ModelSourcesFromFolder(const std::string& folder, std::vector<std::string>* skipped_folders) {
  const fs::path root(folder);
  if (!fs::is_directory(root)) throw InputError(folder + ": model folder not found");
  std::vector<ModelSource> sources;
  for (const fs::path& category_dir : SortedEntries(root)) {
    if (!fs::is_directory(category_dir)) continue;
    const std::string folder_name = category_dir.filename().string();
    const auto category = CategoryOfFolder(folder_name);
    if (!category) {
      if (skipped_folders) skipped_folders->push_back(category_dir.string());
      continue;
    }
    std::vector<std::pair<fs::path, std::string>> files;  // path, name prefix
    for (const fs::path& p : SortedEntries(category_dir)) {
      if (fs::is_directory(p) && (p.filename() == "train" || p.filename() == "test")) {
        for (const fs::path& q : SortedEntries(p)) {
          if (fs::is_regular_file(q) && io::IsMeshFile(q.string()))
            files.emplace_back(q, p.filename().string() + "/");
        }
      } else if (fs::is_regular_file(p) && io::IsMeshFile(p.string())) {
        files.emplace_back(p, "");
      }
    }
    for (const auto& [path, prefix] : files) {
      ModelSource s;
      s.category = *category;
      s.name = std::string(world::CategoryName(*category)) + "/" + prefix + path.stem().string();
      s.source = path.string();
      const std::string file = path.string();
      s.load_mesh = [file] { return io::LoadMesh(file); };
      sources.push_back(std::move(s));
    }
  }
  if (sources.empty()) throw InputError(folder + ": no models found (expected <category>/<name>.obj|off|ply|dae|stl|glb)");
  return sources;
}

const char* ProceduralSamplingName(ProceduralSampling sampling) {
  switch (sampling) {
    case ProceduralSampling::kSpread: return "spread";
    case ProceduralSampling::kStyles: return "styles";
    case ProceduralSampling::kStyleMedoids: return "style-medoids";
    default: return "first-seeds";
  }
}

ProceduralSampling ParseProceduralSampling(const std::string& name, const std::string& field) {
  if (name == "spread") return ProceduralSampling::kSpread;
  if (name == "styles") return ProceduralSampling::kStyles;
  if (name == "style-medoids") return ProceduralSampling::kStyleMedoids;
  if (name == "first-seeds") return ProceduralSampling::kFirstSeeds;
  throw InputError(field + ": unknown procedural sampling '" + name + "' (expected styles, style-medoids, spread or first-seeds)");
}

std::vector<int> GreedyMedoids(const std::vector<std::vector<double>>& features, int count) {
  const int n = static_cast<int>(features.size());
  count = std::clamp(count, 0, n);
  std::vector<double> dist(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double d2 = 0.0;
      for (std::size_t f = 0; f < features[i].size(); ++f) d2 += std::pow(features[i][f] - features[j][f], 2);
      dist[static_cast<std::size_t>(i) * n + j] = std::sqrt(d2);
    }
  }
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  std::vector<char> chosen(n, 0);
  std::vector<int> out;
  for (int step = 0; step < count; ++step) {
    int best = -1;
    double best_cost = std::numeric_limits<double>::infinity();
    for (int j = 0; j < n; ++j) {
      if (chosen[j]) continue;
      double cost = 0.0;
      for (int i = 0; i < n; ++i) cost += std::min(nearest[i], dist[static_cast<std::size_t>(i) * n + j]);
      if (cost < best_cost) {
        best_cost = cost;
        best = j;
      }
    }
    chosen[best] = 1;
    out.push_back(best);
    for (int i = 0; i < n; ++i) nearest[i] = std::min(nearest[i], dist[static_cast<std::size_t>(i) * n + best]);
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

// The pool a sampling draws a category's models from: the models of the first
// variants * kSamplingPoolPerVariant database seeds, in seed order.
std::vector<world::procedural::FurnitureModel> SamplingPool(world::Category category, int variants,
                                                            std::uint64_t first_index) {
  std::vector<world::procedural::FurnitureModel> pool;
  for (int k = 0; k < variants * kSamplingPoolPerVariant; ++k) {
    pool.push_back(world::procedural::GenerateFurniture(category, world::procedural::DatabaseModelSeed(first_index + k)));
  }
  return pool;
}

// Each model's bounding-box size (height, width, depth; the front faces +X), each dimension over
// its standard deviation in the pool (a constant one drops out).
std::vector<std::vector<double>> NormalisedSizes(const std::vector<world::procedural::FurnitureModel>& models) {
  const int pool = static_cast<int>(models.size());
  std::vector<std::vector<double>> size(pool);
  for (int k = 0; k < pool; ++k) {
    const geometry::Aabb3 box = geometry::Bounds(models[k].mesh);
    const Eigen::Vector3d extent = box.max_m - box.min_m;
    size[k] = {extent.z(), extent.y(), extent.x()};
  }
  for (int f = 0; f < 3; ++f) {
    double mean = 0.0, var = 0.0;
    for (const auto& s : size) mean += s[f] / pool;
    for (const auto& s : size) var += (s[f] - mean) * (s[f] - mean) / pool;
    const double sd = std::sqrt(var);
    for (auto& s : size) s[f] = sd > 1e-9 ? s[f] / sd : 0.0;
  }
  return size;
}

// The pool indices (offsets from first_index) of a category's spread sample.
std::vector<int> SpreadIndices(world::Category category, int variants, std::uint64_t first_index) {
  return GreedyMedoids(NormalisedSizes(SamplingPool(category, variants, first_index)), variants);
}

// The pool indices of a category's style-stratified sample; with `medoids`, each style's models are
// the size medoids of its pool models instead of its first ones.
std::vector<int> StyleIndices(world::Category category, int variants, std::uint64_t first_index, bool medoids) {
  const std::vector<world::procedural::FurnitureModel> models = SamplingPool(category, variants, first_index);
  const int pool = static_cast<int>(models.size());
  const std::string prefix = std::string(world::CategoryName(category)) + "_";
  std::vector<int> style_of(pool);
  std::vector<std::string> styles;  // in order of first appearance
  for (int k = 0; k < pool; ++k) {
    std::string name = models[k].name;
    if (name.compare(0, prefix.size(), prefix) == 0) name = name.substr(prefix.size());
    const std::string style = name.substr(0, name.find('_'));
    auto it = std::find(styles.begin(), styles.end(), style);
    if (it == styles.end()) it = styles.insert(styles.end(), style);
    style_of[k] = static_cast<int>(it - styles.begin());
  }
  std::vector<int> drawn(styles.size(), 0);
  std::vector<char> used(pool, 0);
  std::vector<int> out;
  for (int slot = 0; slot < variants; ++slot) {
    int best = -1;
    for (int k = 0; k < pool; ++k) {
      if (used[k]) continue;
      if (best < 0 || drawn[style_of[k]] < drawn[style_of[best]] ||
          (drawn[style_of[k]] == drawn[style_of[best]] && style_of[k] < style_of[best])) {
        best = k;
      }
    }
    used[best] = 1;
    ++drawn[style_of[best]];
    out.push_back(best);
  }
  if (medoids) {
    // Same count per style, drawn as the medoids of the style's models: a style whose sizes spread
    // wide (filing cabinets 0.7-1.35 m tall) gets its middle, not whichever came first.
    const std::vector<std::vector<double>> size = NormalisedSizes(models);
    out.clear();
    for (int style = 0; style < static_cast<int>(styles.size()); ++style) {
      if (drawn[style] == 0) continue;
      std::vector<int> members;
      std::vector<std::vector<double>> member_size;
      for (int k = 0; k < pool; ++k) {
        if (style_of[k] != style) continue;
        members.push_back(k);
        member_size.push_back(size[k]);
      }
      for (int m : GreedyMedoids(member_size, drawn[style])) out.push_back(members[m]);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The pool indices (offsets from first_index) of a category's sample.
std::vector<int> SampledIndices(world::Category category, int variants, std::uint64_t first_index,
                                ProceduralSampling sampling) {
  switch (sampling) {
    case ProceduralSampling::kSpread:
      return SpreadIndices(category, variants, first_index);
    case ProceduralSampling::kStyles:
      return StyleIndices(category, variants, first_index, false);
    case ProceduralSampling::kStyleMedoids:
      return StyleIndices(category, variants, first_index, true);
    case ProceduralSampling::kFirstSeeds:
      break;
  }
  std::vector<int> first(static_cast<std::size_t>(std::max(0, variants)));
  std::iota(first.begin(), first.end(), 0);
  return first;
}

}  // namespace

std::vector<std::vector<float>> ProceduralSupportHeights() {
  std::vector<std::vector<float>> heights(world::kNumCategories);
  for (const std::string& room : world::procedural::RoomCategories()) {
    for (int k = 1; k <= kSupportRoomsPerCategory; ++k) {
      const world::Scene scene = world::procedural::GenerateRoom(room, world::procedural::kDatabaseSeedBit | k);
      for (const world::SceneObject& o : scene.objects()) {
        if (o.IsStructural() || o.mesh.triangles.empty()) continue;
        // Procedural rooms have their floor at z = 0.
        heights[static_cast<std::size_t>(world::CategoryId(o.category))].push_back(
            static_cast<float>(scene.ObjectBounds(o).min_m.z()));
      }
    }
  }
  for (auto& h : heights) std::sort(h.begin(), h.end());
  return heights;
}

std::vector<ModelSource> ProceduralModelSources(int variants, std::uint64_t first_index,
                                                ProceduralSampling sampling) {
  std::vector<ModelSource> sources;
  const std::vector<std::vector<float>> support = ProceduralSupportHeights();
  for (world::Category category : world::procedural::FurnitureCategories()) {
    for (int k : SampledIndices(category, variants, first_index, sampling)) {
      const std::uint64_t seed = world::procedural::DatabaseModelSeed(first_index + k);
      ModelSource s;
      s.category = category;
      s.name = std::string(world::CategoryName(category)) + "/" + std::to_string(first_index + k);
      s.source = "procedural/" + std::string(world::CategoryName(category)) + "/" + std::to_string(seed);
      s.load_mesh = [category, seed] { return world::procedural::GenerateFurniture(category, seed).mesh; };
      s.support_heights_m = support[static_cast<std::size_t>(world::CategoryId(category))];
      sources.push_back(std::move(s));
    }
  }
  return sources;
}

namespace {

// The mesh of a model's source string, normalised; throws InputError when it cannot be loaded.
geometry::TriangleMesh LoadMeshOfSource(const DatabaseModel& model) {
  const std::string prefix = "procedural/";
  geometry::TriangleMesh mesh;
  if (model.source.rfind(prefix, 0) == 0) {
    const std::string rest = model.source.substr(prefix.size());
    const auto slash = rest.find('/');
    const auto category = slash == std::string::npos ? std::nullopt : world::ParseCategory(rest.substr(0, slash));
    if (!category) throw InputError("model source '" + model.source + "': unknown procedural category");
    std::uint64_t seed = 0;
    try {
      seed = std::stoull(rest.substr(slash + 1));
    } catch (const std::exception&) {
      throw InputError("model source '" + model.source + "': bad procedural seed");
    }
    mesh = world::procedural::GenerateFurniture(*category, seed).mesh;
  } else if (io::IsSweetHome3dSource(model.source)) {
    mesh = io::LoadSweetHome3dSource(model.source);
  } else {
    mesh = io::LoadMesh(model.source);
  }
  return NormalizeModel(mesh, TypicalHeight(model.category));
}

}  // namespace

geometry::TriangleMesh LoadModelSourceMesh(const DatabaseModel& model) {
  if (!model.mesh.Empty()) return model.mesh;
  try {
    return LoadMeshOfSource(model);
  } catch (const InputError& e) {
    throw InputError("model " + model.name + ": no mesh in the database and its source cannot be loaded: " +
                     e.what());
  }
}

namespace {

struct ModelInfo {
  world::Category category;
  std::string name;
  std::string source;
  std::vector<float> support_heights_m;
  std::string creator;
  std::string license;
  geometry::TriangleMesh mesh;  // normalised and decimated; empty when built from scans
};

// Vocabulary, histograms and index from described models.
ModelDatabase Assemble(std::vector<PendingModel>* pending_models, std::vector<ModelInfo>* infos,
                       const DatabaseBuildOptions& options, const DescriptorExtractor& descriptor,
                       const ProgressCallback& progress) {
  std::vector<PendingModel>& pending = *pending_models;
  std::vector<ModelInfo>& info = *infos;
  const int n_models = static_cast<int>(pending.size());

  ModelDatabase db;
  DatabaseSettings& settings = db.mutable_settings();
  settings.keypoints = options.keypoints;
  settings.keypoint_seed = options.keypoint_seed;
  settings.descriptor = options.descriptor;
  settings.bow = options.bow;

  // Vocabulary from a seeded sample of all entries' descriptors.
  const int dim = descriptor.Dimension();
  std::vector<const std::uint8_t*> rows;
  for (const auto& pm : pending) {
    for (const auto& pe : pm.entries) {
      for (std::size_t k = 0; k < pe.entry.keypoints.size(); ++k) rows.push_back(&pe.descriptors[k * dim]);
    }
  }
  if (rows.empty()) throw InputError("model database: no model produced any points to describe");
  Rng rng(DeriveSeed(options.seed, 0x70CAB));
  const std::size_t n_sample = std::min<std::size_t>(rows.size(), options.vocabulary.max_training_descriptors);
  for (std::size_t i = 0; i < n_sample; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(rng.Uniform01() * (rows.size() - i));
    std::swap(rows[i], rows[std::min(j, rows.size() - 1)]);
  }
  std::vector<float> training(n_sample * dim);
  for (std::size_t i = 0; i < n_sample; ++i) {
    for (int d = 0; d < dim; ++d) training[i * dim + d] = rows[i][d] / kDescriptorQuantum;
  }
  ReportProgress(progress, 0.88, "vocabulary");
  db.set_vocabulary(Vocabulary::Train(training, dim, options.vocabulary, &rng));

  // Entries with their histograms.
  std::vector<float> descriptors;
  for (int m = 0; m < n_models; ++m) {
    if (!pending[m].ok) continue;
    DatabaseModel model;
    model.name = info[m].name;
    model.category = info[m].category;
    model.source = info[m].source;
    model.support_heights_m = info[m].support_heights_m;
    model.creator = info[m].creator;
    model.license = info[m].license;
    model.mesh = std::move(info[m].mesh);
    const int model_index = static_cast<int>(db.models().size());
    for (auto& pe : pending[m].entries) {
      descriptors.resize(pe.descriptors.size());
      for (std::size_t k = 0; k < descriptors.size(); ++k) descriptors[k] = pe.descriptors[k] / kDescriptorQuantum;
      pe.entry.bow = ComputeSpatialBow(db.vocabulary(), pe.entry.keypoints, pe.keypoint_normals, descriptors,
                                       pe.bow_bounds, options.bow);
      pe.entry.keypoint_normals = std::move(pe.keypoint_normals);
      pe.entry.model_index = model_index;
      if (pe.entry.kind == EntryKind::kFullModel) model.full_entry = static_cast<int>(db.entries().size());
      db.mutable_entries().push_back(std::move(pe.entry));
    }
    db.mutable_models().push_back(std::move(model));
    pending[m] = PendingModel();
  }
  ReportProgress(progress, 0.97, "index");
  db.Finalize();
  ReportProgress(progress, 1.0, "done");
  return db;
}

}  // namespace

ModelDatabase BuildDatabase(const std::vector<ModelSource>& sources, const DatabaseBuildOptions& options,
                            const ProgressCallback& progress) {
  options.Validate();
  const auto descriptor = MakeDescriptorExtractor(options.descriptor);
  const int n_models = static_cast<int>(sources.size());
  const int workers = std::min(ResolveThreadCount(options.threads), std::max(1, n_models));
  VirtualScanOptions scan_options = options.scan;
  if (workers > 1) scan_options.sensor.threads = 1;  // parallel over models instead of image rows

  std::vector<PendingModel> pending(n_models);
  std::vector<ModelInfo> info(n_models);
  std::mutex progress_mutex;
  int done = 0;
  ParallelForBlocks(n_models, workers, [&](int m) {
    const ModelSource& source = sources[m];
    info[m] = {source.category, source.name, source.source, source.support_heights_m, source.creator, source.license, {}};
    const geometry::TriangleMesh mesh = NormalizeModel(source.load_mesh(), TypicalHeight(source.category));
    // The mesh as scanned, kept in the database (bounded in size) so the model's mesh comes back
    // without its source files.
    info[m].mesh =
        geometry::DecimateToTriangleBudget(mesh, options.stored_mesh_max_triangles, options.stored_mesh_min_cell_m).mesh;
    if (!mesh.Empty()) {
      Rng noise_rng(DeriveSeed(options.seed, static_cast<std::uint64_t>(m)));
      const ModelScan scan = ScanModel(mesh, RingViews(geometry::Bounds(mesh), scan_options), scan_options,
                                       options.scan_noise, &noise_rng);
      pending[m] = DescribeScan(scan, source.category, source.name, m, options, *descriptor);
    }
    std::lock_guard<std::mutex> lock(progress_mutex);
    ++done;
    ReportProgress(progress, 0.85 * done / n_models, source.name);
  });
  return Assemble(&pending, &info, options, *descriptor, progress);
}

ModelDatabase BuildDatabaseFromScans(const std::vector<ScannedModel>& models, const DatabaseBuildOptions& options,
                                     const ProgressCallback& progress) {
  options.Validate();
  const auto descriptor = MakeDescriptorExtractor(options.descriptor);
  const int n_models = static_cast<int>(models.size());
  std::vector<PendingModel> pending(n_models);
  std::vector<ModelInfo> info(n_models);
  ParallelForBlocks(n_models, options.threads, [&](int m) {
    info[m] = {models[m].category, models[m].name, models[m].source, models[m].support_heights_m, {}, {}, {}};
    pending[m] = DescribeScan(models[m].scan, models[m].category, models[m].name, m, options, *descriptor);
  });
  return Assemble(&pending, &info, options, *descriptor, progress);
}

}  // namespace objscan::recognition
