// Writes the seeds of the model_database fuzz target (fuzz/corpus/model_database/): tiny databases
// saved by ModelDatabase::Save, as payloads (the bytes after the header, what the harness wraps) and
// one whole file. Usage: fuzz_make_database_seeds OUT_DIR (built with -DOBJSCAN_FUZZ=ON).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "objscan/recognition/model_database.h"

namespace {
using objscan::recognition::DatabaseEntry;
using objscan::recognition::DatabaseModel;
using objscan::recognition::EntryKind;
using objscan::recognition::ModelDatabase;
using objscan::world::Category;

// A box's eight corners as the model's surface points, normals pointing out of the box.
void BoxPoints(float sx, float sy, float sz, std::vector<Eigen::Vector3f>* points, std::vector<Eigen::Vector3f>* normals) {
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3f p((i & 1 ? 0.5f : -0.5f) * sx, (i & 2 ? 0.5f : -0.5f) * sy, (i & 4 ? sz : 0.f));
    points->push_back(p);
    normals->push_back(Eigen::Vector3f(p.x(), p.y(), p.z() - sz / 2).normalized());
  }
}

DatabaseEntry Entry(EntryKind kind, Category category, const std::string& name, int model, std::uint32_t first_bin) {
  DatabaseEntry e;
  e.kind = kind;
  e.category = category;
  e.name = name;
  e.model_index = model;
  e.keypoints = {{0.f, 0.f, 0.1f}, {0.2f, 0.f, 0.4f}, {-0.2f, 0.1f, 0.7f}};
  e.keypoint_normals = {{0.f, 0.f, 1.f}, {1.f, 0.f, 0.f}, {0.f, -1.f, 0.f}};
  e.bow = {{first_bin, 0.5f}, {first_bin + 3, 0.25f}, {first_bin + 40, 0.25f}};
  return e;
}

ModelDatabase TinyDatabase(bool two_models) {
  ModelDatabase db;
  const int dim = 33;  // FPFH
  std::vector<float> words(2 * dim);
  for (int i = 0; i < 2 * dim; ++i) words[i] = 0.1f * static_cast<float>(i % 7);
  db.set_vocabulary(objscan::recognition::Vocabulary(dim, std::move(words), 0.5f, 2));

  DatabaseModel chair;
  chair.name = "chair_a";
  chair.category = Category::kChair;
  chair.source = "procedural/chair/1";
  chair.full_entry = 0;
  chair.support_heights_m = {0.f};
  // Its stored mesh (format 5): the box of its points.
  chair.mesh = objscan::geometry::MakeBox(Eigen::Vector3d(-0.25, -0.25, 0.0), Eigen::Vector3d(0.25, 0.25, 0.9));
  db.mutable_models().push_back(chair);
  DatabaseEntry full = Entry(EntryKind::kFullModel, Category::kChair, "chair_a", 0, 0);
  BoxPoints(0.5f, 0.5f, 0.9f, &full.points, &full.normals);
  db.mutable_entries().push_back(full);
  DatabaseEntry component = Entry(EntryKind::kComponent, Category::kChair, "chair_a/c1", 0, 2);
  component.point_indices = {0, 1, 2, 3};
  db.mutable_entries().push_back(component);
  DatabaseEntry pair = Entry(EntryKind::kPair, Category::kChair, "chair_a/p1-2", 0, 5);
  pair.point_indices = {0, 1, 2, 3, 4, 5};
  db.mutable_entries().push_back(pair);
  if (two_models) {
    DatabaseModel lamp;
    lamp.name = "lamp_b";
    lamp.category = Category::kLamp;
    lamp.source = "sweethome3d:/usr/share/sweethome3d/furniture/Test.sh3f#Test#lamp";
    lamp.full_entry = 3;  // support heights unknown, no stored mesh
    lamp.creator = "Jos\xc3\xa9";  // credits (format 4)
    lamp.license = "CC-BY 3.0";
    db.mutable_models().push_back(lamp);
    DatabaseEntry lamp_full = Entry(EntryKind::kFullModel, Category::kLamp, "lamp_b", 1, 7);
    BoxPoints(0.3f, 0.3f, 1.6f, &lamp_full.points, &lamp_full.normals);
    db.mutable_entries().push_back(lamp_full);
  }
  db.Finalize();
  return db;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteFile(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  constexpr std::size_t kHeaderSize = 8 + 4 + 8 + 8;  // magic, version, payload size, checksum
  for (const bool two : {false, true}) {
    const std::string tmp = (out / "tmp.db").string();
    TinyDatabase(two).Save(tmp);
    const std::string file = ReadFile(tmp);
    std::filesystem::remove(tmp);
    WriteFile(out / (two ? "two_models.payload" : "one_model.payload"), file.substr(kHeaderSize));
    if (!two) WriteFile(out / "one_model.db", file);
  }
  // The same database with its settings changed to other valid values.
  ModelDatabase db = TinyDatabase(true);
  db.mutable_settings().bow.absolute_height_edges_m = {0.5, 1.0};
  db.mutable_settings().bow.height_bands = 2;
  db.mutable_settings().descriptor.support_radius_m = 0.2;
  const std::string tmp = (out / "tmp.db").string();
  db.Save(tmp);
  WriteFile(out / "other_settings.payload", ReadFile(tmp).substr(kHeaderSize));
  std::filesystem::remove(tmp);
  return 0;
}
