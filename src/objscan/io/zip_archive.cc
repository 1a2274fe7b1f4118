#include "objscan/io/zip_archive.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>

#include "objscan/common/error.h"

namespace objscan::io {
namespace {

constexpr std::uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr std::uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr std::uint32_t kEndOfCentralDirectorySignature = 0x06054b50;
constexpr std::size_t kLocalHeaderSize = 30;
constexpr std::size_t kCentralHeaderSize = 46;
constexpr std::size_t kEndOfCentralDirectorySize = 22;
constexpr std::size_t kMaxCommentSize = 0xffff;

std::uint16_t U16(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}
std::uint32_t U32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
         (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}

// `size` bytes at `offset` of the open file; throws naming `where` when the file ends first.
std::string ReadAt(std::ifstream& in, std::uint64_t offset, std::uint64_t size, const std::string& where) {
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (size == 0) return bytes;
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (!in || static_cast<std::uint64_t>(in.gcount()) != size) throw InputError(where + ": truncated zip archive");
  return bytes;
}

std::ifstream OpenFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open zip archive");
  return in;
}

}  // namespace

std::uint32_t Crc32(const std::string& data) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto* bytes = reinterpret_cast<const Bytef*>(data.data());
  std::size_t left = data.size();
  while (left > 0) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(left, std::numeric_limits<uInt>::max()));
    crc = crc32(crc, bytes, chunk);
    bytes += chunk;
    left -= chunk;
  }
  return static_cast<std::uint32_t>(crc);
}

ZipArchive ZipArchive::Open(const std::string& path) {
  ZipArchive archive;
  archive.path_ = path;
  std::ifstream in = OpenFile(path);
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) throw InputError(path + ": cannot read zip archive");
  archive.file_size_ = static_cast<std::uint64_t>(end);
  if (archive.file_size_ < kEndOfCentralDirectorySize) {
    throw InputError(path + ": not a zip archive (too short for an end-of-central-directory record)");
  }
  // The end-of-central-directory record is the last 22 bytes plus a comment of up to 64 KiB.
  const std::uint64_t tail_size =
      std::min<std::uint64_t>(archive.file_size_, kEndOfCentralDirectorySize + kMaxCommentSize);
  const std::string tail = ReadAt(in, archive.file_size_ - tail_size, tail_size, path);
  std::size_t eocd = std::string::npos;
  for (std::size_t i = tail.size() - kEndOfCentralDirectorySize + 1; i-- > 0;) {
    if (U32(tail.data() + i) == kEndOfCentralDirectorySignature &&
        i + kEndOfCentralDirectorySize + U16(tail.data() + i + 20) == tail.size()) {
      eocd = i;
      break;
    }
  }
  if (eocd == std::string::npos) {
    throw InputError(path + ": not a zip archive or truncated (no end-of-central-directory record)");
  }
  const char* e = tail.data() + eocd;
  const std::uint16_t disk = U16(e + 4), cd_disk = U16(e + 6);
  const std::uint16_t entries_on_disk = U16(e + 8), num_entries = U16(e + 10);
  const std::uint32_t cd_size = U32(e + 12), cd_offset = U32(e + 16);
  if (num_entries == 0xffff || cd_size == 0xffffffffu || cd_offset == 0xffffffffu) {
    throw InputError(path + ": zip64 archives are not supported");
  }
  if (disk != 0 || cd_disk != 0 || entries_on_disk != num_entries) {
    throw InputError(path + ": multi-disk zip archives are not supported");
  }
  const std::uint64_t eocd_offset = archive.file_size_ - tail_size + eocd;
  if (static_cast<std::uint64_t>(cd_offset) + cd_size > eocd_offset) {
    throw InputError(path + ": truncated or corrupt zip archive (central directory outside the file)");
  }
  const std::string cd = ReadAt(in, cd_offset, cd_size, path);
  std::size_t pos = 0;
  for (std::uint32_t k = 0; k < num_entries; ++k) {
    const std::string where = path + ": central directory entry " + std::to_string(k + 1);
    if (pos + kCentralHeaderSize > cd.size() || U32(cd.data() + pos) != kCentralHeaderSignature) {
      throw InputError(where + ": bad signature (corrupt zip archive)");
    }
    const char* h = cd.data() + pos;
    ZipEntry entry;
    entry.flags = U16(h + 8);
    entry.method = U16(h + 10);
    entry.crc32 = U32(h + 16);
    entry.compressed_size = U32(h + 20);
    entry.uncompressed_size = U32(h + 24);
    const std::size_t name_length = U16(h + 28), extra_length = U16(h + 30), comment_length = U16(h + 32);
    entry.local_header_offset = U32(h + 42);
    if (pos + kCentralHeaderSize + name_length + extra_length + comment_length > cd.size()) {
      throw InputError(where + ": runs past the central directory (corrupt zip archive)");
    }
    entry.name.assign(h + kCentralHeaderSize, name_length);
    if (entry.compressed_size == 0xffffffffu || entry.uncompressed_size == 0xffffffffu ||
        entry.local_header_offset == 0xffffffffu) {
      throw InputError(path + ": " + entry.name + ": zip64 entries are not supported");
    }
    if (entry.local_header_offset + kLocalHeaderSize + entry.compressed_size > cd_offset) {
      throw InputError(path + ": " + entry.name + ": entry data outside the file (truncated or corrupt zip archive)");
    }
    pos += kCentralHeaderSize + name_length + extra_length + comment_length;
    archive.index_.emplace(entry.name, archive.entries_.size());  // the first of duplicate names wins
    archive.entries_.push_back(std::move(entry));
  }
  return archive;
}

const ZipEntry* ZipArchive::Find(const std::string& name) const {
  const auto it = index_.find(name);
  return it == index_.end() ? nullptr : &entries_[it->second];
}

std::string ZipArchive::Read(const std::string& name) const {
  const ZipEntry* entry = Find(name);
  if (entry == nullptr) throw InputError(path_ + ": no entry '" + name + "' in the zip archive");
  return Read(*entry);
}

std::string ZipArchive::Read(const ZipEntry& entry) const {
  const std::string where = path_ + ": " + entry.name;
  if (entry.flags & 0x1) throw InputError(where + ": encrypted zip entries are not supported");
  if (entry.method != 0 && entry.method != 8) {
    throw InputError(where + ": unsupported zip compression method " + std::to_string(entry.method) +
                     " (stored and deflate only)");
  }
  std::ifstream in = OpenFile(path_);
  const std::string header = ReadAt(in, entry.local_header_offset, kLocalHeaderSize, where);
  if (U32(header.data()) != kLocalHeaderSignature) throw InputError(where + ": bad local header signature (corrupt zip archive)");
  const std::uint64_t data_offset =
      entry.local_header_offset + kLocalHeaderSize + U16(header.data() + 26) + U16(header.data() + 28);
  if (data_offset + entry.compressed_size > file_size_) throw InputError(where + ": truncated zip archive");
  const std::string compressed = ReadAt(in, data_offset, entry.compressed_size, where);

  std::string data;
  if (entry.method == 0) {
    if (entry.compressed_size != entry.uncompressed_size) {
      throw InputError(where + ": stored entry with different compressed and uncompressed sizes (corrupt zip archive)");
    }
    data = compressed;
  } else {
    z_stream stream{};
    if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) throw InputError(where + ": zlib inflateInit2 failed");
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
    stream.avail_in = static_cast<uInt>(compressed.size());
    // One spare byte: data longer than the declared size ends in Z_OK/Z_BUF_ERROR, not Z_STREAM_END.
    std::string out(static_cast<std::size_t>(entry.uncompressed_size) + 1, '\0');
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&stream, Z_FINISH);
    const std::uint64_t produced = stream.total_out;
    inflateEnd(&stream);
    if (status != Z_STREAM_END) {
      const char* reason = status == Z_DATA_ERROR ? "corrupt deflate data" : "deflate data ends early or runs long";
      throw InputError(where + ": " + reason + " (damaged zip archive)");
    }
    if (produced != entry.uncompressed_size) {
      throw InputError(where + ": inflated to " + std::to_string(produced) + " bytes, the directory says " +
                       std::to_string(entry.uncompressed_size) + " (damaged zip archive)");
    }
    out.resize(static_cast<std::size_t>(produced));
    data = std::move(out);
  }
  if (Crc32(data) != entry.crc32) throw InputError(where + ": CRC-32 mismatch (damaged zip archive)");
  return data;
}

}  // namespace objscan::io
