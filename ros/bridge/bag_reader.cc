#include "bag_reader.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::uint8_t kOpMessageData = 0x02;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpConnection = 0x07;

struct Connection {
  std::string topic, type;
};

class Reader {
 public:
  Reader(const std::string& path, const std::function<void(const BagMessage&)>& visit) : path_(path), visit_(visit) {}

  // Records in [begin, end); chunks hold records themselves.
  void Records(const std::uint8_t* begin, const std::uint8_t* end, bool in_chunk) {
    const std::uint8_t* p = begin;
    while (p < end) {
      const std::uint32_t header_len = U32(p, end, "record header length");
      p += 4;
      Need(p, end, header_len, "record header");
      const std::map<std::string, std::string> header = Fields(p, p + header_len);
      p += header_len;
      const std::uint32_t data_len = U32(p, end, "record data length");
      p += 4;
      Need(p, end, data_len, "record data");
      const std::uint8_t* data = p;
      p += data_len;
      const auto op = header.find("op");
      if (op == header.end() || op->second.size() != 1) Fail("a record without its op field");
      const auto kind = static_cast<std::uint8_t>(op->second[0]);
      if (kind == kOpChunk) {
        if (in_chunk) Fail("a chunk inside a chunk");
        const auto compression = header.find("compression");
        if (compression == header.end() || compression->second != "none") {
          Fail("compressed chunks (" + (compression == header.end() ? std::string("?") : compression->second) +
               ") are not read: run `rosbag decompress` on it first");
        }
        Records(data, data + data_len, true);
      } else if (kind == kOpConnection) {
        Connection c;
        c.topic = Field(header, "topic");
        const std::map<std::string, std::string> info = Fields(data, data + data_len);
        const auto type = info.find("type");
        c.type = type == info.end() ? std::string() : type->second;
        connections_[U32Field(header, "conn")] = c;
      } else if (kind == kOpMessageData) {
        const auto c = connections_.find(U32Field(header, "conn"));
        if (c == connections_.end()) Fail("a message of a connection not defined before it");
        const std::string& time = Field(header, "time");
        if (time.size() != 8) Fail("a message time of " + std::to_string(time.size()) + " bytes");
        BagMessage m;
        m.topic = c->second.topic;
        m.type = c->second.type;
        std::memcpy(&m.time_sec, time.data(), 4);
        std::memcpy(&m.time_nsec, time.data() + 4, 4);
        m.data.assign(data, data + data_len);
        visit_(m);
      }
      // Bag header, index and chunk info records say where things are; reading in order needs none.
    }
  }

  [[noreturn]] void Fail(const std::string& why) const { throw InputError(path_ + ": not a readable ROS bag: " + why); }

 private:
  std::uint32_t U32(const std::uint8_t* p, const std::uint8_t* end, const char* what) const {
    Need(p, end, 4, what);
    std::uint32_t v;
    std::memcpy(&v, p, 4);  // little-endian, as bags are written on every ROS platform
    return v;
  }
  void Need(const std::uint8_t* p, const std::uint8_t* end, std::uint64_t n, const char* what) const {
    if (static_cast<std::uint64_t>(end - p) < n) Fail(std::string("truncated in a ") + what);
  }
  // Header fields: (length, name=value) pairs.
  std::map<std::string, std::string> Fields(const std::uint8_t* p, const std::uint8_t* end) const {
    std::map<std::string, std::string> fields;
    while (p < end) {
      const std::uint32_t len = U32(p, end, "header field length");
      p += 4;
      Need(p, end, len, "header field");
      const std::string field(reinterpret_cast<const char*>(p), len);
      p += len;
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) Fail("a header field without '='");
      fields[field.substr(0, eq)] = field.substr(eq + 1);
    }
    return fields;
  }
  const std::string& Field(const std::map<std::string, std::string>& fields, const std::string& name) const {
    const auto it = fields.find(name);
    if (it == fields.end()) Fail("a record without its " + name + " field");
    return it->second;
  }
  std::uint32_t U32Field(const std::map<std::string, std::string>& fields, const std::string& name) const {
    const std::string& v = Field(fields, name);
    if (v.size() != 4) Fail("a " + name + " field of " + std::to_string(v.size()) + " bytes");
    std::uint32_t x;
    std::memcpy(&x, v.data(), 4);
    return x;
  }

  std::string path_;
  const std::function<void(const BagMessage&)>& visit_;
  std::map<std::uint32_t, Connection> connections_;
};

}  // namespace

void ReadBag(const std::string& path, const std::function<void(const BagMessage&)>& visit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the bag");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader reader(path, visit);
  const std::size_t magic = std::strlen(kMagic);
  if (bytes.size() < magic || std::memcmp(bytes.data(), kMagic, magic) != 0) {
    reader.Fail("it does not start with \"#ROSBAG V2.0\"");
  }
  reader.Records(bytes.data() + magic, bytes.data() + bytes.size(), false);
}

}  // namespace objscan::ros_bridge
