#include "objscan/io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "objscan/common/error.h"

namespace objscan::io {

namespace {

constexpr char kTempInfix[] = ".tmp.";

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // Hidden, beside the target (the rename must stay within one file system); the process id keeps
  // concurrent writers of the same target from sharing a temporary file and tells a later cleanup
  // whether its writer still runs.
  const std::filesystem::path target(path_);
  const std::string name = "." + target.filename().string() + kTempInfix + std::to_string(static_cast<long>(::getpid()));
  temp_path_ = (target.parent_path() / name).string();
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

AtomicFileWriter::AtomicFileWriter(std::string path) : file_(std::move(path)) {
  out_.open(file_.temp_path(), std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(file_.path() + ": cannot write (cannot create file)");
}

void AtomicFileWriter::Write(const char* data, std::size_t size) {
  out_.write(data, static_cast<std::streamsize>(size));
  if (!out_) throw InputError(file_.path() + ": write failed");
}

void AtomicFileWriter::Commit() {
  out_.flush();
  out_.close();
  if (!out_) throw InputError(file_.path() + ": write failed");
  file_.Commit();
}

void WriteFileAtomically(const std::string& path, const std::string& bytes) {
  AtomicFileWriter file(path);
  file.Write(bytes.data(), bytes.size());
  file.Commit();
}

bool IsAtomicTempName(const std::string& filename, long* pid) {
  if (filename.size() < 2 || filename[0] != '.') return false;
  const std::size_t infix = filename.rfind(kTempInfix);
  if (infix == std::string::npos || infix < 2) return false;  // ".<at least one character>.tmp.<pid>"
  const std::string digits = filename.substr(infix + sizeof(kTempInfix) - 1);
  if (digits.empty() || digits.size() > 18) return false;
  for (const char c : digits) {
    if (c < '0' || c > '9') return false;
  }
  if (pid) *pid = std::stol(digits);
  return true;
}

int RemoveStaleTempFiles(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    long pid = 0;
    if (!IsAtomicTempName(it->path().filename().string(), &pid)) continue;
    // A live writer (this process included) may still rename its file: keep it. kill(pid, 0) fails
    // with ESRCH only when no such process exists (EPERM: it exists, owned by someone else).
    // (Signal 0 only checks; a pid out of pid_t's range names no process.)
    const bool writer_alive =
        pid == static_cast<long>(::getpid()) ||
        (pid > 0 && pid <= INT_MAX && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH));
    if (writer_alive) continue;
    std::error_code remove_ec;
    if (fs::remove(it->path(), remove_ec)) ++removed;
  }
  return removed;
}

}  // namespace objscan::io
