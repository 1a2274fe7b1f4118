#pragma once
// A tiny zip writer for tests: entries stored (method 0) or deflated (method 8, raw deflate through
// zlib, window bits -15), local headers, central directory and end-of-central-directory record.
// Used to make archive fixtures (zip_archive_test, sweethome3d_test, the Sweet Home 3D CLI test).
#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace objscan::io::testing {

class ZipWriter {
 public:
  // Adds an entry; `deflate` compresses it with raw deflate, else it is stored.
  void Add(const std::string& name, const std::string& data, bool deflate = false) {
    Entry e;
    e.name = name;
    e.crc = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(data.data()),
                                             static_cast<uInt>(data.size())));
    e.size = static_cast<std::uint32_t>(data.size());
    e.method = deflate ? 8 : 0;
    e.data = deflate ? Deflate(data) : data;
    entries_.push_back(std::move(e));
  }

  // The archive's bytes.
  std::string Bytes() const {
    std::string out, cd;
    for (const Entry& e : entries_) {
      const auto offset = static_cast<std::uint32_t>(out.size());
      Put32(&out, 0x04034b50);
      Put16(&out, 20);  // version needed
      Put16(&out, 0);   // flags
      Put16(&out, e.method);
      Put16(&out, 0);   // time
      Put16(&out, 0x21);  // date (1980-01-01)
      Put32(&out, e.crc);
      Put32(&out, static_cast<std::uint32_t>(e.data.size()));
      Put32(&out, e.size);
      Put16(&out, static_cast<std::uint16_t>(e.name.size()));
      Put16(&out, 0);  // extra
      out += e.name;
      out += e.data;

      Put32(&cd, 0x02014b50);
      Put16(&cd, 20);  // version made by
      Put16(&cd, 20);  // version needed
      Put16(&cd, 0);
      Put16(&cd, e.method);
      Put16(&cd, 0);
      Put16(&cd, 0x21);
      Put32(&cd, e.crc);
      Put32(&cd, static_cast<std::uint32_t>(e.data.size()));
      Put32(&cd, e.size);
      Put16(&cd, static_cast<std::uint16_t>(e.name.size()));
      Put16(&cd, 0);  // extra
      Put16(&cd, 0);  // comment
      Put16(&cd, 0);  // disk
      Put16(&cd, 0);  // internal attributes
      Put32(&cd, 0);  // external attributes
      Put32(&cd, offset);
      cd += e.name;
    }
    const auto cd_offset = static_cast<std::uint32_t>(out.size());
    out += cd;
    Put32(&out, 0x06054b50);
    Put16(&out, 0);
    Put16(&out, 0);
    Put16(&out, static_cast<std::uint16_t>(entries_.size()));
    Put16(&out, static_cast<std::uint16_t>(entries_.size()));
    Put32(&out, static_cast<std::uint32_t>(cd.size()));
    Put32(&out, cd_offset);
    Put16(&out, 0);  // comment
    return out;
  }

  void Write(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    const std::string bytes = Bytes();
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("ZipWriter: cannot write " + path);
  }

 private:
  struct Entry {
    std::string name, data;
    std::uint32_t crc = 0, size = 0;
    std::uint16_t method = 0;
  };

  static void Put16(std::string* out, std::uint16_t v) {
    out->push_back(static_cast<char>(v & 0xff));
    out->push_back(static_cast<char>(v >> 8));
  }
  static void Put32(std::string* out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  static std::string Deflate(const std::string& data) {
    z_stream s{};
    if (deflateInit2(&s, Z_BEST_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
      throw std::runtime_error("ZipWriter: deflateInit2 failed");
    }
    std::string out(deflateBound(&s, static_cast<uLong>(data.size())), '\0');
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    s.avail_in = static_cast<uInt>(data.size());
    s.next_out = reinterpret_cast<Bytef*>(out.data());
    s.avail_out = static_cast<uInt>(out.size());
    const int status = deflate(&s, Z_FINISH);
    out.resize(s.total_out);
    deflateEnd(&s);
    if (status != Z_STREAM_END) throw std::runtime_error("ZipWriter: deflate failed");
    return out;
  }

  std::vector<Entry> entries_;
};

}  // namespace objscan::io::testing
