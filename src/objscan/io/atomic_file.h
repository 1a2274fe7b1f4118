#pragma once
// Atomic file writes: data goes to a temporary file beside the target, which is synced to disk and
// renamed over the target only once it is complete (then the folder is synced), so a failed write or
// a crash never leaves a half-written file behind. The temporary file is hidden
// (".<name>.tmp.<pid>"): a writer killed before the rename leaves no file that looks like an output,
// and RemoveStaleTempFiles() clears such leftovers the next time the folder is written.
#include <cstddef>
#include <fstream>
#include <string>

namespace objscan::io {

class AtomicFile {
 public:
  // Picks a temporary name beside `path` (nothing is created yet).
  explicit AtomicFile(std::string path);
  // Removes the temporary file unless Commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temp_path() const { return temp_path_; }
  const std::string& path() const { return path_; }
  // Syncs the temporary file, renames it to the target and syncs the folder; throws InputError naming
  // the target on failure.
  void Commit();

 private:
  std::string path_;
  std::string temp_path_;
  bool committed_ = false;
};

// An AtomicFile written as a stream: the temporary file is created at construction, Write() appends,
// Commit() makes it the target. Without Commit() (an exception on the way) nothing is left. Throws
// InputError naming the target on failure.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::string path);
  void Write(const char* data, std::size_t size);
  void Commit();
  const std::string& path() const { return file_.path(); }

 private:
  AtomicFile file_;
  std::ofstream out_;
};

// Writes `bytes` to `path` atomically; throws InputError naming the path on failure.
void WriteFileAtomically(const std::string& path, const std::string& bytes);

// True when `filename` (no folder) is an AtomicFile temporary name; *pid (when given) is its writer.
bool IsAtomicTempName(const std::string& filename, long* pid = nullptr);

// Removes the AtomicFile temporaries in `folder` (not below it) whose writer process no longer
// exists, i.e. leftovers of a killed writer; a live writer's file is kept. Returns how many were
// removed. Best effort: never throws (a missing folder removes nothing).
int RemoveStaleTempFiles(const std::string& folder);

}  // namespace objscan::io
