#pragma once
// The trained category recognizer kept as a cache file: training reads every model of its databases
// (tens of thousands of samples with the built-in libraries, a minute and more of CPU), and every run
// on the same databases with the same options trains the same classifier (training is deterministic
// from its seed). The file's name is a key over all that decides the result: the training samples'
// content (keypoints, normals, categories, support heights of every database), the classifier's
// options (threads aside: the forest is the same at any count), the shape features' revision and
// what ShapeFeatures computes on a fixed shape (so a changed feature never reads an old file). A
// damaged file (truncated, bit-flipped, an older format) is trained again and replaced, never used.
#include <string>
#include <vector>

#include "objscan/recognition/category_classifier.h"

namespace objscan::recognition {

class ModelDatabase;

// Bump when training changes what it computes from the same samples and options.
constexpr int kClassifierTrainingRevision = 1;

// 16 hex digits naming what a classifier trained on `databases` with `options` depends on.
std::string ClassifierCacheKey(const std::vector<const ModelDatabase*>& databases,
                               const CategoryClassifierOptions& options);

struct CachedClassifierStatus {
  std::string path;         // the cache file used or written
  bool loaded = false;      // read from the file (no training)
  std::string damage;       // why an existing file was rejected and trained again; "" if not
  std::string write_error;  // why the trained classifier could not be kept ("" if it was)
};

// What a user is told of `status`, one line each (no "objscan:" prefix): that a damaged cache file
// was trained again, that the trained classifier could not be kept; none when all went well. The
// CLI prints them, the Python module raises them as warnings.
std::vector<std::string> ClassifierCacheMessages(const CachedClassifierStatus& status);

// The classifier CategoryClassifier::Train(databases, options) returns, read from
// `cache_dir`/classifier-<key>.bin when a valid file is there, else trained and saved there
// atomically (the folder is created). A failed save leaves the result as trained and says why in
// status->write_error: the cache saves time, never changes a result.
CategoryClassifier TrainOrLoadClassifier(const std::vector<const ModelDatabase*>& databases,
                                         const CategoryClassifierOptions& options, const std::string& cache_dir,
                                         CachedClassifierStatus* status = nullptr);

}  // namespace objscan::recognition
