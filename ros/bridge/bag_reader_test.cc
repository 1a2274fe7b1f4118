#include "bag_reader.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

// A bag written byte by byte as format 2.0 lays it out (the fixture of these tests).
class BagBytes {
 public:
  BagBytes() { bytes_ = "#ROSBAG V2.0\n"; }
  static std::string U32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
  static std::string Field(const std::string& name, const std::string& value) {
    return U32(static_cast<std::uint32_t>(name.size() + 1 + value.size())) + name + "=" + value;
  }
  static std::string Record(const std::string& header, const std::string& data) {
    return U32(static_cast<std::uint32_t>(header.size())) + header + U32(static_cast<std::uint32_t>(data.size())) + data;
  }
  static std::string Connection(std::uint32_t conn, const std::string& topic, const std::string& type) {
    return Record(Field("op", "\x07") + Field("conn", U32(conn)) + Field("topic", topic),
                  Field("topic", topic) + Field("type", type) + Field("md5sum", "*"));
  }
  static std::string Message(std::uint32_t conn, std::uint32_t sec, const std::string& data) {
    return Record(Field("op", "\x02") + Field("conn", U32(conn)) + Field("time", U32(sec) + U32(7)), data);
  }
  void Add(const std::string& record) { bytes_ += record; }
  void AddChunk(const std::string& records, const std::string& compression = "none") {
    bytes_ += Record(Field("op", "\x05") + Field("compression", compression) +
                         Field("size", U32(static_cast<std::uint32_t>(records.size()))),
                     records);
  }
  std::string Write(const std::string& name) const {
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    std::ofstream(path, std::ios::binary) << bytes_;
    return path;
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

std::vector<BagMessage> Read(const std::string& path) {
  std::vector<BagMessage> out;
  ReadBag(path, [&](const BagMessage& m) { out.push_back(m); });
  return out;
}

TEST(BagReaderTest, MessagesComeInFileOrderWithTopicTypeTimeAndBytes) {
  BagBytes bag;
  bag.Add(BagBytes::Record(BagBytes::Field("op", "\x03") + BagBytes::Field("index_pos", std::string(8, '\0')),
                           std::string(16, ' ')));
  bag.AddChunk(BagBytes::Connection(0, "/objscan/robot_request", "std_msgs/String") + BagBytes::Message(0, 5, "abc") +
               BagBytes::Connection(1, "/camera/depth/image", "sensor_msgs/Image") + BagBytes::Message(1, 6, "xy"));
  bag.AddChunk(BagBytes::Message(0, 8, "d"));
  // The index records after the chunks: a connection again and an index entry, skipped.
  bag.Add(BagBytes::Connection(0, "/objscan/robot_request", "std_msgs/String"));
  bag.Add(BagBytes::Record(BagBytes::Field("op", "\x04") + BagBytes::Field("conn", BagBytes::U32(0)), "12345678"));
  const std::string path = bag.Write("objscan_bag_reader_ok.bag");
  const std::vector<BagMessage> m = Read(path);
  std::remove(path.c_str());
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].topic, "/objscan/robot_request");
  EXPECT_EQ(m[0].type, "std_msgs/String");
  EXPECT_EQ(std::string(m[0].data.begin(), m[0].data.end()), "abc");
  EXPECT_EQ(m[0].time_sec, 5u);
  EXPECT_EQ(m[0].time_nsec, 7u);
  EXPECT_EQ(m[1].topic, "/camera/depth/image");
  EXPECT_EQ(m[1].type, "sensor_msgs/Image");
  EXPECT_EQ(std::string(m[1].data.begin(), m[1].data.end()), "xy");
  EXPECT_EQ(m[2].time_sec, 8u);
}

TEST(BagReaderTest, DamagedOrCompressedBagsGiveOneLineNamingTheFile) {
  auto error_of = [](const std::string& path) {
    try {
      Read(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BagBytes not_a_bag;
  not_a_bag.bytes() = "#ROSBAG V1.2\n";
  std::string e = error_of(not_a_bag.Write("objscan_bag_reader_v1.bag"));
  EXPECT_NE(e.find("objscan_bag_reader_v1.bag"), std::string::npos) << e;
  EXPECT_NE(e.find("#ROSBAG V2.0"), std::string::npos) << e;

  BagBytes truncated;
  truncated.AddChunk(BagBytes::Connection(0, "/t", "std_msgs/String") + BagBytes::Message(0, 1, "abcdef"));
  truncated.bytes().resize(truncated.bytes().size() - 3);
  e = error_of(truncated.Write("objscan_bag_reader_truncated.bag"));
  EXPECT_NE(e.find("objscan_bag_reader_truncated.bag"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;

  BagBytes compressed;
  compressed.AddChunk("zzzz", "lz4");
  e = error_of(compressed.Write("objscan_bag_reader_lz4.bag"));
  EXPECT_NE(e.find("lz4"), std::string::npos) << e;
  EXPECT_NE(e.find("rosbag decompress"), std::string::npos) << e;

  BagBytes orphan;
  orphan.AddChunk(BagBytes::Message(3, 1, "abc"));
  e = error_of(orphan.Write("objscan_bag_reader_orphan.bag"));
  EXPECT_NE(e.find("connection"), std::string::npos) << e;

  EXPECT_NE(error_of("/nonexistent/objscan.bag").find("cannot open"), std::string::npos);
  for (const char* name : {"objscan_bag_reader_v1.bag", "objscan_bag_reader_truncated.bag",
                           "objscan_bag_reader_lz4.bag", "objscan_bag_reader_orphan.bag"}) {
    std::remove((std::filesystem::temp_directory_path() / name).string().c_str());
  }
}

}  // namespace
}  // namespace objscan::ros_bridge
