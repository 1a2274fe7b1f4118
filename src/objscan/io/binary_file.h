#pragma once
// objscan's binary files (model databases, trained category classifiers): a header of an 8-byte
// magic, a u32 format version, the payload's u64 size and u64 checksum, then the payload, written
// little-endian and atomically (io/atomic_file.h). A truncated, extended or bit-flipped file is
// rejected before anything is parsed; every error is an InputError naming the file and the kind of
// file ("model database", "category classifier").
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

namespace objscan::io {

// FNV-1a over 64-bit little-endian words (then the tail bytes): fast enough to check a large file on
// every load, and any flipped or shifted byte changes it.
std::uint64_t Checksum(const char* data, std::size_t size);

// What a file of one kind starts with.
struct BinaryFileFormat {
  const char* magic;        // exactly 8 bytes
  std::uint32_t version;    // the format this objscan writes and reads
  const char* kind;         // for messages: "model database"
  const char* rebuild_hint; // for a version mismatch: "rebuild it with objscan db build"
};

constexpr std::size_t kBinaryHeaderSize = 8 + 4 + 8 + 8;

// Writes header and payload to `path` atomically; throws InputError naming the path on failure.
void WriteBinaryFile(const std::string& path, const BinaryFileFormat& format, const std::vector<char>& payload);

// The whole file with its header checked and its payload verified against the checksum; the payload
// starts at kBinaryHeaderSize. `memory_per_file_byte` and `max_memory_bytes` > 0 refuse a file that
// would need more memory once loaded (the message names memory_option, the config key to change).
std::vector<char> ReadVerifiedBinaryFile(const std::string& path, const BinaryFileFormat& format,
                                         std::uint64_t max_memory_bytes = 0, std::uint64_t memory_per_file_byte = 0,
                                         const char* memory_option = "");

// Little-endian writer (objscan targets little-endian hosts; the formats are defined little-endian).
class BinaryWriter {
 public:
  template <class T>
  void Pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&v);
    buf_.insert(buf_.end(), p, p + sizeof(T));
  }
  void String(const std::string& s) {
    Pod(static_cast<std::uint32_t>(s.size()));
    buf_.insert(buf_.end(), s.begin(), s.end());
  }
  template <class T>
  void Array(const T* data, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(data);
    buf_.insert(buf_.end(), p, p + count * sizeof(T));
  }
  // A u32 count, then the elements.
  template <class T>
  void Vector(const std::vector<T>& values) {
    Pod(static_cast<std::uint32_t>(values.size()));
    Array(values.data(), values.size());
  }
  void Points(const std::vector<Eigen::Vector3f>& pts) {
    Pod(static_cast<std::uint32_t>(pts.size()));
    Array(reinterpret_cast<const float*>(pts.data()), 3 * pts.size());
  }
  const std::vector<char>& buffer() const { return buf_; }

 private:
  std::vector<char> buf_;
};

// Reads what BinaryWriter wrote; every shortfall throws InputError naming the file, its kind and the
// field ("truncated or corrupt model database (at settings)").
class BinaryReader {
 public:
  BinaryReader(const char* data, std::size_t size, const std::string& path, const char* kind)
      : p_(data), end_(data + size), path_(path), kind_(kind) {}
  template <class T>
  T Pod(const char* what) {
    T v;
    Need(sizeof(T), what);
    std::memcpy(&v, p_, sizeof(T));
    p_ += sizeof(T);
    return v;
  }
  std::uint32_t Count(std::size_t element_size, const char* what) {
    const auto n = Pod<std::uint32_t>(what);
    // A count can never exceed what is left of the file.
    if (element_size > 0 && n > static_cast<std::size_t>(end_ - p_) / element_size) Truncated(what);
    return n;
  }
  std::string String(const char* what) {
    const std::uint32_t n = Count(1, what);
    std::string s(p_, n);
    p_ += n;
    return s;
  }
  template <class T>
  void Array(T* out, std::size_t count, const char* what) {
    // An empty array's out is an empty vector's data(), which may be null: no memcpy (UB on null).
    if (count == 0) return;
    Need(count * sizeof(T), what);
    std::memcpy(out, p_, count * sizeof(T));
    p_ += count * sizeof(T);
  }
  template <class T>
  std::vector<T> Vector(const char* what) {
    std::vector<T> values(Count(sizeof(T), what));
    Array(values.data(), values.size(), what);
    return values;
  }
  std::vector<Eigen::Vector3f> Points(const char* what) {
    const std::uint32_t n = Count(12, what);
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "Vector3f must be packed");
    std::vector<Eigen::Vector3f> pts(n);
    Array(reinterpret_cast<float*>(pts.data()), 3 * static_cast<std::size_t>(n), what);
    return pts;
  }
  bool AtEnd() const { return p_ == end_; }
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  void Need(std::size_t n, const char* what) {
    if (static_cast<std::size_t>(end_ - p_) < n) Truncated(what);
  }
  [[noreturn]] void Truncated(const char* what) const;
  const char* p_;
  const char* end_;
  const std::string& path_;
  const char* kind_;
};

}  // namespace objscan::io
