// Writes the seeds of the bag fuzz target (fuzz/corpus/bag/): tiny ROS bags (format 2.0) laid out as
// `rosbag record` writes them (bag header record; uncompressed chunks of connection and message
// records, each followed by its index data records; then the connection and chunk info records),
// each read back with ros_bridge::ReadBag. The bag header's padding is 16 bytes, not rosbag's 4096,
// to keep the seeds small.
// Usage: fuzz_make_bag_seeds OUT_DIR (built with -DOBJSCAN_FUZZ=ON).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bag_reader.h"

namespace {

std::string U32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
std::string U64(std::uint64_t v) { return std::string(reinterpret_cast<const char*>(&v), 8); }
std::string Time(std::uint32_t sec, std::uint32_t nsec) { return U32(sec) + U32(nsec); }
// A header field: its length, then name=value.
std::string Field(const std::string& name, const std::string& value) {
  return U32(static_cast<std::uint32_t>(name.size() + 1 + value.size())) + name + "=" + value;
}
std::string Record(const std::string& header, const std::string& data) {
  return U32(static_cast<std::uint32_t>(header.size())) + header + U32(static_cast<std::uint32_t>(data.size())) + data;
}
// A ROS-serialized string.
std::string RosString(const std::string& s) { return U32(static_cast<std::uint32_t>(s.size())) + s; }

struct Topic {
  std::uint32_t conn;
  std::string topic, type, md5sum, definition;
  bool latched;
};

struct Message {
  std::uint32_t conn;
  std::uint32_t sec, nsec;
  std::string data;
};

std::string ConnectionRecord(const Topic& t) {
  std::string data = Field("topic", t.topic) + Field("type", t.type) + Field("md5sum", t.md5sum) +
                     Field("message_definition", t.definition);
  if (t.latched) data += Field("callerid", "/objscan_sim_ros") + Field("latching", "1");
  return Record(Field("op", "\x07") + Field("conn", U32(t.conn)) + Field("topic", t.topic), data);
}

// A bag of `chunks` (each the messages recorded in it, every connection defined in the chunk that
// first uses it, as rosbag does), with the index section after them.
std::string Bag(const std::vector<Topic>& topics, const std::vector<std::vector<Message>>& chunks) {
  std::string body;  // everything after the bag header record
  std::string chunk_infos;
  const std::string magic = "#ROSBAG V2.0\n";
  auto header_record = [&](std::uint64_t index_pos) {
    return Record(Field("op", "\x03") + Field("index_pos", U64(index_pos)) +
                      Field("conn_count", U32(static_cast<std::uint32_t>(topics.size()))) +
                      Field("chunk_count", U32(static_cast<std::uint32_t>(chunks.size()))),
                  std::string(16, ' '));
  };
  const std::size_t start = magic.size() + header_record(0).size();
  std::vector<bool> defined(topics.size(), false);
  for (const std::vector<Message>& chunk : chunks) {
    std::string records;
    std::vector<std::string> entries(topics.size());  // per connection: (time, offset in the chunk)
    std::vector<std::uint32_t> counts(topics.size(), 0);
    std::uint32_t first = ~0u, last = 0;
    for (const Message& m : chunk) {
      if (!defined[m.conn]) {
        records += ConnectionRecord(topics[m.conn]);
        defined[m.conn] = true;
      }
      entries[m.conn] += Time(m.sec, m.nsec) + U32(static_cast<std::uint32_t>(records.size()));
      records += Record(Field("op", "\x02") + Field("conn", U32(m.conn)) + Field("time", Time(m.sec, m.nsec)), m.data);
      ++counts[m.conn];
      first = std::min(first, m.sec);
      last = std::max(last, m.sec);
    }
    const std::uint64_t chunk_pos = start + body.size();
    body += Record(Field("op", "\x05") + Field("compression", "none") +
                       Field("size", U32(static_cast<std::uint32_t>(records.size()))),
                   records);
    std::string per_conn;
    std::uint32_t conns = 0;
    for (std::size_t c = 0; c < topics.size(); ++c) {
      if (counts[c] == 0) continue;
      body += Record(Field("op", "\x04") + Field("ver", U32(1)) + Field("conn", U32(static_cast<std::uint32_t>(c))) +
                         Field("count", U32(counts[c])),
                     entries[c]);
      per_conn += U32(static_cast<std::uint32_t>(c)) + U32(counts[c]);
      ++conns;
    }
    chunk_infos += Record(Field("op", "\x06") + Field("ver", U32(1)) + Field("chunk_pos", U64(chunk_pos)) +
                              Field("start_time", Time(first, 0)) + Field("end_time", Time(last, 0)) +
                              Field("count", U32(conns)),
                          per_conn);
  }
  const std::uint64_t index_pos = start + body.size();
  for (const Topic& t : topics) body += ConnectionRecord(t);
  body += chunk_infos;
  return magic + header_record(index_pos) + body;
}

const Topic kRequest{0, "/objscan/robot_request", "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1",
                     "string data\n", false};
const Topic kDepth{1, "/camera/depth/image", "sensor_msgs/Image", "060021388200f6f0f447d0fcd9c64743",
                   "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\n"
                   "uint32 step\nuint8[] data\n",
                   false};
const Topic kInfo{2, "/objscan/info", "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data\n", true};

// A 2 x 2 depth image in millimetres (16UC1), as the simulator publishes them.
std::string DepthImage(std::uint32_t seq, std::uint16_t mm) {
  std::string pixels;
  for (int i = 0; i < 4; ++i) {
    const std::uint16_t v = static_cast<std::uint16_t>(mm + 10 * i);
    pixels += std::string(reinterpret_cast<const char*>(&v), 2);
  }
  return U32(seq) + Time(100 + seq, 0) + RosString("camera_depth_optical_frame") + U32(2) + U32(2) +
         RosString("16UC1") + std::string(1, '\0') + U32(4) + RosString(pixels);
}

void Write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  std::size_t messages = 0;
  objscan::ros_bridge::ReadBag(path.string(), [&](const objscan::ros_bridge::BagMessage&) { ++messages; });
  std::printf("%s: %zu bytes, %zu messages\n", path.filename().string().c_str(), bytes.size(), messages);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  try {
    Write(out / "empty.bag", Bag({kRequest}, {}));
    Write(out / "one_chunk_strings.bag",
          Bag({kRequest}, {{{0, 100, 5, RosString("{\"hello\":1}")}, {0, 101, 0, RosString("{\"move\":[1,0]}")}}}));
    Write(out / "two_chunks_depth_and_latched.bag",
          Bag({kRequest, kDepth, kInfo}, {{{2, 100, 0, RosString("objscan 1")},
                                           {1, 100, 500, DepthImage(0, 1200)},
                                           {0, 101, 0, RosString("{\"scan\":true}")}},
                                          {{1, 102, 0, DepthImage(1, 1500)}, {0, 102, 7, RosString("")}}}));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
