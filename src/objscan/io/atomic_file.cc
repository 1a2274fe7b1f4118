#include "objscan/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "objscan/common/error.h"

namespace objscan::io {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // The process id keeps concurrent writers of the same target from sharing a temporary file.
  temp_path_ = path_ + ".tmp" + std::to_string(static_cast<long>(::getpid()));
}

AtomicFile::~AtomicFile() {
  if (!committed_) std::remove(temp_path_.c_str());
}

namespace {

// fsync of a file or folder by path; false (errno set) when it cannot be opened or synced.
bool SyncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  errno = saved;
  return ok;
}

}  // namespace

void AtomicFile::Commit() {
  // The data reaches the disk before the rename makes it the target, so a crash (power loss, a
  // killed machine) leaves the old file or the complete new one, never a renamed empty one.
  if (!SyncPath(temp_path_, O_RDONLY) || std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    throw InputError(path_ + ": cannot write (" + reason + ")");
  }
  committed_ = true;
  // The rename itself is durable once the folder is synced. Best effort: the file is complete either
  // way, and some file systems refuse to sync a folder.
  std::filesystem::path folder = std::filesystem::path(path_).parent_path();
  if (folder.empty()) folder = ".";
  SyncPath(folder.string(), O_RDONLY | O_DIRECTORY);
}

void WriteFileAtomically(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write (cannot create file)");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw InputError(path + ": write failed");
  }
  file.Commit();
}

}  // namespace objscan::io
