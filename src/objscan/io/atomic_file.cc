#include "objscan/io/atomic_file.h"

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

void AtomicFile::Commit() {
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    throw InputError(path_ + ": cannot write (" + reason + ")");
  }
  committed_ = true;
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
