#pragma once
// A reader of ROS bag files (format 2.0, as `rosbag record` writes them), without ROS: the messages
// in the order they were recorded, each with its topic, type and serialized bytes. Chunks must be
// uncompressed (rosbag record's default; `rosbag decompress` undoes --bz2 and --lz4). Debian's C++
// rosbag library cannot be built against here (its headers pull ROS 2 packages), and objscan only
// needs to play its own recordings back.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace objscan::ros_bridge {

struct BagMessage {
  std::string topic;
  std::string type;  // e.g. sensor_msgs/Image
  std::uint32_t time_sec = 0, time_nsec = 0;  // when the recorder received it
  std::vector<std::uint8_t> data;             // the message, ROS-serialized
};

// Calls `visit` for every message of `path` in file order. Throws InputError naming the file on
// anything it cannot read (not a bag, truncated, compressed chunks, a message of an unknown connection).
void ReadBag(const std::string& path, const std::function<void(const BagMessage&)>& visit);

}  // namespace objscan::ros_bridge
