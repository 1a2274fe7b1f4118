#pragma once
// PLY point clouds and meshes (binary little-endian by default, ASCII on request).
// Writes are atomic: a failed write leaves no file behind.
#include <array>
#include <cstdint>
#include <memory>
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

// Writes atomically (io/atomic_file.h); throws InputError naming the path for inconsistent data or a
// failed write, and leaves no file behind then.
void WritePly(const std::string& path, const PlyData& data, bool binary = true);

// What a PLY written a vertex at a time holds: the counts and fields, in the order WritePly writes
// a PlyData's (x y z, normals, colours, the int properties in this order; then the faces).
struct PlyLayout {
  std::size_t num_vertices = 0;
  bool normals = false;
  bool colors = false;
  std::vector<std::string> int_properties;
  std::size_t num_triangles = 0;
  std::vector<std::string> comments;
  bool binary = true;
};

// The layout WritePly writes `data` with.
PlyLayout LayoutOf(const PlyData& data, bool binary = true);

// Writes a PLY without holding its data: the header at construction, then every vertex, then every
// face, out to disk in 1 MB chunks (a house's map is hundreds of MB as a PlyData). The file appears
// at Commit(), complete; without it (an exception on the way) nothing is left. Throws InputError
// naming the path for a bad layout, a count other than announced, a face index out of range or a
// failed write. WritePly is this writer over a PlyData, so both give the same bytes.
class PlyStreamWriter {
 public:
  PlyStreamWriter(const std::string& path, PlyLayout layout);
  ~PlyStreamWriter();
  PlyStreamWriter(const PlyStreamWriter&) = delete;
  PlyStreamWriter& operator=(const PlyStreamWriter&) = delete;

  // `normal` and `color` are ignored when the layout has none; `ints` holds one value per int
  // property (may be null when there are none).
  void AddVertex(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, const std::array<std::uint8_t, 3>& color,
                 const std::int32_t* ints);
  void AddTriangle(const Eigen::Vector3i& triangle);
  void Commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
// Reads x y z (+ normals, colours, int properties, faces when present). Throws InputError naming the
// path on a missing or malformed file.
PlyData ReadPly(const std::string& path);

}  // namespace objscan::io
