#include "objscan/io/binary_file.h"

#include <fstream>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"

namespace objscan::io {

std::uint64_t Checksum(const char* data, std::size_t size) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t word;
    std::memcpy(&word, data + i, 8);
    h = (h ^ word) * 0x100000001b3ull;
    h ^= h >> 29;
  }
  for (; i < size; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 0x100000001b3ull;
  return h;
}

void WriteBinaryFile(const std::string& path, const BinaryFileFormat& format, const std::vector<char>& payload) {
  const std::string kind = format.kind;
  // Atomically: a killed writer or a full disk never leaves a partial file under the target name, and
  // concurrent writers of the same cache file each write their own temporary.
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write " + kind);
    const std::uint32_t version = format.version;
    const std::uint64_t size = payload.size();
    const std::uint64_t checksum = Checksum(payload.data(), payload.size());
    out.write(format.magic, 8);
    out.write(reinterpret_cast<const char*>(&version), sizeof(version));
    out.write(reinterpret_cast<const char*>(&size), sizeof(size));
    out.write(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    out.flush();
    if (!out) throw InputError(path + ": failed writing " + kind);
  }
  file.Commit();
}

std::vector<char> ReadVerifiedBinaryFile(const std::string& path, const BinaryFileFormat& format,
                                         std::uint64_t max_memory_bytes, std::uint64_t memory_per_file_byte,
                                         const char* memory_option) {
  const std::string kind = format.kind;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path + ": cannot open " + kind);
  const std::streamoff file_size = in.tellg();
  if (file_size < 0) throw InputError(path + ": cannot read " + kind);
  const std::uint64_t need = static_cast<std::uint64_t>(file_size) * memory_per_file_byte;
  if (max_memory_bytes > 0 && need > max_memory_bytes) {
    const auto mb = [](std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20); };
    throw InputError(path + ": the " + kind + " needs about " + mb(need) + " MB of memory once loaded, more than the " +
                     "limit of " + mb(max_memory_bytes) + " MB (" + memory_option +
                     "; 0 means the memory available)");
  }
  std::vector<char> bytes(static_cast<std::size_t>(file_size));
  in.seekg(0);
  if (!in.read(bytes.data(), file_size)) throw InputError(path + ": cannot read " + kind);
  if (bytes.size() < 8 || std::memcmp(bytes.data(), format.magic, 8) != 0)
    throw InputError(path + ": not an objscan " + kind + " (bad magic)");
  if (bytes.size() < kBinaryHeaderSize) throw InputError(path + ": truncated " + kind + " (header)");
  std::uint32_t version = 0;
  std::uint64_t size = 0, checksum = 0;
  std::memcpy(&version, bytes.data() + 8, 4);
  std::memcpy(&size, bytes.data() + 12, 8);
  std::memcpy(&checksum, bytes.data() + 20, 8);
  if (version != format.version) {
    throw InputError(path + ": " + kind + " format version " + std::to_string(version) + ", this objscan reads version " +
                     std::to_string(format.version) + " (" + format.rebuild_hint + ")");
  }
  if (bytes.size() - kBinaryHeaderSize < size) throw InputError(path + ": truncated " + kind);
  if (bytes.size() - kBinaryHeaderSize > size) throw InputError(path + ": corrupt " + kind + " (trailing bytes)");
  if (Checksum(bytes.data() + kBinaryHeaderSize, size) != checksum) {
    throw InputError(path + ": corrupt " + kind + " (checksum mismatch)");
  }
  return bytes;
}

void BinaryReader::Fail(const std::string& what) const {
  throw InputError(path_ + ": corrupt " + kind_ + " (" + what + ")");
}

void BinaryReader::Truncated(const char* what) const {
  throw InputError(path_ + ": truncated or corrupt " + std::string(kind_) + " (at " + what + ")");
}

}  // namespace objscan::io
