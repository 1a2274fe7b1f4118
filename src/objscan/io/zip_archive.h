#pragma once
// A small reader of zip archives (PKWARE APPNOTE): the end-of-central-directory record, the central
// directory and each entry's local header; entries stored (method 0) or deflated (method 8, raw
// inflate through zlib), their CRC-32 checked. No zip64, no encryption, no multi-disk archives.
// What Sweet Home 3D's furniture catalogs (.sh3f) need (io/sweethome3d.h).
//
// Every damage (missing or truncated file, bad signature, bad CRC, unsupported method, missing
// entry) throws InputError, one line naming the archive and, where there is one, the entry.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace objscan::io {

struct ZipEntry {
  std::string name;  // path inside the archive as stored ("dir/file.obj"; folders end with '/')
  std::uint16_t method = 0;  // 0 stored, 8 deflated
  std::uint16_t flags = 0;   // general purpose bit flag (bit 0: encrypted)
  std::uint32_t crc32 = 0;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint64_t local_header_offset = 0;

  bool IsDirectory() const { return !name.empty() && name.back() == '/'; }
};

class ZipArchive {
 public:
  // Reads the central directory of the archive at `path`; throws InputError naming it when it is
  // missing, not a zip archive, truncated or uses what this reader does not support (zip64,
  // several disks).
  static ZipArchive Open(const std::string& path);

  const std::string& path() const { return path_; }
  // In central-directory order.
  const std::vector<ZipEntry>& entries() const { return entries_; }
  // The entry of this exact name, or null.
  const ZipEntry* Find(const std::string& name) const;
  bool Contains(const std::string& name) const { return Find(name) != nullptr; }

  // The entry's bytes, inflated and CRC-checked. Throws InputError naming the archive and the entry
  // when it is missing, damaged, encrypted or compressed with another method than stored/deflate.
  // Opens the file for each call, so several threads may read from one archive.
  std::string Read(const std::string& name) const;
  std::string Read(const ZipEntry& entry) const;

 private:
  std::string path_;
  std::uint64_t file_size_ = 0;
  std::vector<ZipEntry> entries_;
  std::unordered_map<std::string, std::size_t> index_;
};

// CRC-32 (ISO-HDLC, as zip and zlib use) of `data`.
std::uint32_t Crc32(const std::string& data);

}  // namespace objscan::io
