#pragma once
// PLY point clouds and meshes (binary little-endian by default, ASCII on request).
// Writes are atomic: a failed write leaves no file behind.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "objscan/geometry/mesh.h"
#include "objscan/geometry/point_cloud.h"

namespace objscan::io {

struct PlyData {
  std::vector<Eigen::Vector3f> points;                  // "x y z"
  std::vector<Eigen::Vector3f> normals;                 // empty or per point: "nx ny nz"
  std::vector<std::array<std::uint8_t, 3>> colors;      // empty or per point: "red green blue"
  std::vector<std::pair<std::string, std::vector<std::int32_t>>> int_properties;  // per point, e.g. "object_id"
  std::vector<Eigen::Vector3i> triangles;               // empty for a point cloud: "vertex_indices"
  // Header "comment" lines (without the keyword), e.g. the names of label ids; one line each. The
  // writer puts "written by objscan" first; the reader returns every comment of the file.
  std::vector<std::string> comments;
};

void WritePly(const std::string& path, const PlyData& data, bool binary = true);
// Reads x y z (+ normals, colours, int properties, faces when present). Throws InputError naming the
// path on a missing or malformed file.
PlyData ReadPly(const std::string& path);

}  // namespace objscan::io
