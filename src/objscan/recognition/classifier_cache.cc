#include "objscan/recognition/classifier_cache.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/io/binary_file.h"
#include "objscan/recognition/model_database.h"

namespace objscan::recognition {

namespace {

// Streams values into one 64-bit key (io::Checksum per piece, chained).
class KeyHasher {
 public:
  template <class T>
  void Pod(const T& v) {
    Bytes(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void String(const std::string& s) {
    Pod(static_cast<std::uint64_t>(s.size()));
    Bytes(s.data(), s.size());
  }
  void Points(const std::vector<Eigen::Vector3f>& points) {
    Pod(static_cast<std::uint64_t>(points.size()));
    Bytes(reinterpret_cast<const char*>(points.data()), points.size() * sizeof(Eigen::Vector3f));
  }
  void Bytes(const char* data, std::size_t size) {
    hash_ = (hash_ ^ io::Checksum(data, size)) * 0x100000001b3ull;
    hash_ ^= hash_ >> 31;
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

// ShapeFeatures of a fixed shape (a chair-like set of points: a seat, a back and four legs), so a
// change to what the features compute changes every key.
std::array<float, kNumShapeFeatures> FeatureProbe() {
  std::vector<Eigen::Vector3f> points, normals;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const float u = 0.05f * static_cast<float>(i) - 0.22f, v = 0.05f * static_cast<float>(j) - 0.22f;
      points.emplace_back(u, v, 0.45f);  // seat
      normals.emplace_back(0.f, 0.f, 1.f);
      points.emplace_back(u, -0.25f, 0.5f + 0.05f * static_cast<float>(j));  // back
      normals.emplace_back(0.f, 1.f, 0.f);
    }
  }
  for (int leg = 0; leg < 4; ++leg) {
    for (int k = 0; k < 9; ++k) {
      points.emplace_back(leg % 2 ? 0.22f : -0.22f, leg / 2 ? 0.22f : -0.22f, 0.05f * static_cast<float>(k));
      normals.emplace_back(leg % 2 ? 1.f : -1.f, 0.f, 0.f);
    }
  }
  return ShapeFeatures(points, normals, 0.0);
}

}  // namespace

std::string ClassifierCacheKey(const std::vector<const ModelDatabase*>& databases,
                               const CategoryClassifierOptions& options) {
  KeyHasher key;
  key.Pod(static_cast<std::int32_t>(kClassifierTrainingRevision));
  key.Pod(static_cast<std::int32_t>(kNumShapeFeatures));
  const std::array<float, kNumShapeFeatures> probe = FeatureProbe();
  key.Bytes(reinterpret_cast<const char*>(probe.data()), sizeof(probe));
  CategoryClassifierOptions keyed = options;
  keyed.forest.threads = 0;  // the same forest at any thread count
  keyed.network.threads = 0;  // the same network too
  keyed.extra_training_databases.clear();  // already in `databases`
  keyed.cache = true;
  key.String(config::ToYaml(config::Dump(keyed)));
  key.Pod(static_cast<std::uint64_t>(databases.size()));
  for (const ModelDatabase* db : databases) {
    key.Pod(static_cast<std::uint64_t>(db->models().size()));
    for (const DatabaseModel& m : db->models()) {
      key.Pod(static_cast<std::int32_t>(world::CategoryId(m.category)));
      key.Pod(static_cast<std::uint64_t>(m.support_heights_m.size()));
      key.Bytes(reinterpret_cast<const char*>(m.support_heights_m.data()), m.support_heights_m.size() * sizeof(float));
    }
    key.Pod(static_cast<std::uint64_t>(db->entries().size()));
    for (const DatabaseEntry& e : db->entries()) {
      key.Pod(static_cast<std::int32_t>(e.kind));
      key.Pod(static_cast<std::int32_t>(world::CategoryId(e.category)));
      key.Pod(e.model_index);
      key.Points(e.keypoints);
      key.Points(e.keypoint_normals);
    }
  }
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(key.hash()));
  return buf;
}

std::vector<std::string> ClassifierCacheMessages(const CachedClassifierStatus& status) {
  std::vector<std::string> messages;
  // The damage names the file.
  if (!status.damage.empty()) messages.push_back("the cached category recognizer is damaged, trained it again: " + status.damage);
  if (!status.write_error.empty()) {
    messages.push_back("could not keep the trained category recognizer in the cache: " + status.write_error);
  }
  return messages;
}

CategoryClassifier TrainOrLoadClassifier(const std::vector<const ModelDatabase*>& databases,
                                         const CategoryClassifierOptions& options, const std::string& cache_dir,
                                         CachedClassifierStatus* status) {
  CachedClassifierStatus local;
  CachedClassifierStatus& s = status ? *status : local;
  s = CachedClassifierStatus{};
  s.path = cache_dir + "/classifier-" + ClassifierCacheKey(databases, options) + ".bin";
  std::error_code ec;
  if (std::filesystem::exists(s.path, ec)) {
    try {
      CategoryClassifier c = CategoryClassifier::Load(s.path);
      s.loaded = true;
      return c;
    } catch (const InputError& e) {
      s.damage = e.what();
    }
  }
  CategoryClassifier c = CategoryClassifier::Train(databases, options);
  try {
    std::filesystem::create_directories(cache_dir, ec);
    if (ec) throw InputError(cache_dir + ": cannot create the cache folder (" + ec.message() + ")");
    c.Save(s.path);
  } catch (const InputError& e) {
    s.write_error = e.what();
  }
  return c;
}

}  // namespace objscan::recognition
