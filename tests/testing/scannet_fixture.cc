#include "scannet_fixture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace objscan::testing {
namespace {

namespace fs = std::filesystem;
using Vec3 = std::array<double, 3>;

struct Object {
  std::string raw_label;  // "" = unannotated
  int nyu40 = 0;
};

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<int> vertex_segment, vertex_object;
  std::vector<std::array<int, 3>> faces;
  std::vector<Object> objects;
  int next_segment = 1000;  // ScanNet segment ids are arbitrary integers, not 0..n-1
};

Vec3 Add(const Vec3& a, const Vec3& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }

// A rectangle o + [0,1]u + [0,1]w as a grid of about `spacing_m`, vertices welded within one object.
void AddRectangle(Mesh* mesh, int object, const Vec3& o, const Vec3& u, const Vec3& w, double spacing_m,
                  std::map<std::array<long, 3>, int>* welded) {
  const auto length = [](const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
  const int nu = std::max(2, static_cast<int>(std::ceil(length(u) / spacing_m)));
  const int nw = std::max(2, static_cast<int>(std::ceil(length(w) / spacing_m)));
  const int segment = mesh->next_segment++;
  std::vector<int> index((nu + 1) * (nw + 1));
  for (int j = 0; j <= nw; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const Vec3 p = Add(Add(o, u, static_cast<double>(i) / nu), w, static_cast<double>(j) / nw);
      const std::array<long, 3> key = {std::lround(p[0] * 1e6), std::lround(p[1] * 1e6), std::lround(p[2] * 1e6)};
      auto it = welded->find(key);
      if (it == welded->end()) {
        it = welded->emplace(key, static_cast<int>(mesh->vertices.size())).first;
        mesh->vertices.push_back(p);
        mesh->vertex_segment.push_back(segment);
        mesh->vertex_object.push_back(object);
      }
      index[j * (nu + 1) + i] = it->second;
    }
  }
  for (int j = 0; j < nw; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = index[j * (nu + 1) + i], b = index[j * (nu + 1) + i + 1];
      const int c = index[(j + 1) * (nu + 1) + i + 1], d = index[(j + 1) * (nu + 1) + i];
      mesh->faces.push_back({a, b, c});
      mesh->faces.push_back({a, c, d});
    }
  }
}

int AddObject(Mesh* mesh, const std::string& raw_label, int nyu40) {
  mesh->objects.push_back({raw_label, nyu40});
  return static_cast<int>(mesh->objects.size()) - 1;
}

// Four sides and the top of an axis-aligned box, a piece of `object` not joined to its others.
void AddBoxTo(Mesh* mesh, int object, const double* b) {
  std::map<std::array<long, 3>, int> welded;
  const double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
  AddRectangle(mesh, object, {b[0], b[1], b[2]}, {dx, 0, 0}, {0, 0, dz}, 0.1, &welded);
  AddRectangle(mesh, object, {b[0], b[4], b[2]}, {dx, 0, 0}, {0, 0, dz}, 0.1, &welded);
  AddRectangle(mesh, object, {b[0], b[1], b[2]}, {0, dy, 0}, {0, 0, dz}, 0.1, &welded);
  AddRectangle(mesh, object, {b[3], b[1], b[2]}, {0, dy, 0}, {0, 0, dz}, 0.1, &welded);
  AddRectangle(mesh, object, {b[0], b[1], b[5]}, {dx, 0, 0}, {0, dy, 0}, 0.1, &welded);
}

void AddBox(Mesh* mesh, const std::string& raw_label, int nyu40, const double* b) {
  AddBoxTo(mesh, AddObject(mesh, raw_label, nyu40), b);
}

// A chair of box `b`: one box, or its base and its seat 20 cm above it.
void AddChair(Mesh* mesh, const double* b, bool split) {
  if (!split) return AddBox(mesh, "office chair", 5, b);
  const int chair = AddObject(mesh, "office chair", 5);
  const double base[6] = {b[0], b[1], b[2], b[3], b[4], b[2] + 0.25};
  const double seat[6] = {b[0], b[1], b[2] + 0.45, b[3], b[4], b[5]};
  AddBoxTo(mesh, chair, base);
  AddBoxTo(mesh, chair, seat);
}

Mesh MakeRoom(const ScanNetFixtureOptions& options) {
  Mesh mesh;
  {
    const int floor = AddObject(&mesh, "floor", 2);
    std::map<std::array<long, 3>, int> welded;
    const double half = kFixtureRoomX / 2;
    AddRectangle(&mesh, floor, {0, 0, 0}, {half, 0, 0}, {0, kFixtureRoomY, 0}, 0.2, &welded);
    AddRectangle(&mesh, floor, {half, 0, 0}, {half, 0, 0}, {0, kFixtureRoomY, 0}, 0.2, &welded);
  }
  {
    const int wall = AddObject(&mesh, "wall", 1);
    std::map<std::array<long, 3>, int> welded;
    const Vec3 up = {0, 0, kFixtureWallHeight};
    AddRectangle(&mesh, wall, {0, 0, 0}, {kFixtureRoomX, 0, 0}, up, 0.2, &welded);
    AddRectangle(&mesh, wall, {0, kFixtureRoomY, 0}, {kFixtureRoomX, 0, 0}, up, 0.2, &welded);
    AddRectangle(&mesh, wall, {0, 0, 0}, {0, kFixtureRoomY, 0}, up, 0.2, &welded);
    AddRectangle(&mesh, wall, {kFixtureRoomX, 0, 0}, {0, kFixtureRoomY, 0}, up, 0.2, &welded);
  }
  AddChair(&mesh, kFixtureChair, options.split_chairs);
  AddBox(&mesh, "coffee table", 7, kFixtureTable);
  AddBox(&mesh, "trash can", 39, kFixtureTrashCan);
  AddBox(&mesh, "", 0, kFixtureUnannotated);
  // Last, so that the default fixture's objects keep their order and names.
  if (options.second_chair) AddChair(&mesh, kFixtureSecondChair, options.split_chairs);
  return mesh;
}

template <class T>
void Put(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the test machines are little-endian, as the format
  out->append(bytes, sizeof(T));
}

void WritePly(const std::string& path, const Mesh& mesh, const std::vector<Vec3>& points, bool with_label) {
  std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(points.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
                    "property uchar blue\nproperty uchar alpha\n" +
                    (with_label ? "property ushort label\n" : "") + "element face " + std::to_string(mesh.faces.size()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (double c : points[v]) Put(&out, static_cast<float>(c));
    for (std::uint8_t c : {std::uint8_t{150}, std::uint8_t{140}, std::uint8_t{120}, std::uint8_t{255}}) Put(&out, c);
    if (with_label) Put(&out, static_cast<std::uint16_t>(mesh.objects[mesh.vertex_object[v]].nyu40));
  }
  for (const auto& f : mesh.faces) {
    Put(&out, std::uint8_t{3});
    for (int i : f) Put(&out, static_cast<std::int32_t>(i));
  }
  std::ofstream(path, std::ios::binary) << out;
}

}  // namespace

std::string WriteScanNetFixture(const std::string& parent_dir, const std::string& scan_id,
                                const ScanNetFixtureOptions& options) {
  const fs::path dir = fs::path(parent_dir) / scan_id;
  fs::create_directories(dir);
  const Mesh mesh = MakeRoom(options);
  // The file's frame: the levelled room turned about x by the tilt, then shifted and lifted.
  const double a = options.tilt_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  const Vec3 t = {0.3, -0.2, options.lift_m};
  std::vector<Vec3> points;
  for (const Vec3& p : mesh.vertices) points.push_back({p[0] + t[0], c * p[1] - s * p[2] + t[1], s * p[1] + c * p[2] + t[2]});

  const std::string base = (dir / scan_id).string();
  WritePly(base + "_vh_clean_2.ply", mesh, points, false);
  if (options.labels_ply) WritePly(base + "_vh_clean_2.labels.ply", mesh, points, true);
  if (options.aggregation) {
    std::ostringstream segs;
    segs << "{\"params\": {\"kThresh\": \"0.0001\", \"segMinVerts\": \"20\"}, \"sceneId\": \"" << scan_id
         << "\", \"segIndices\": [";
    for (std::size_t v = 0; v < mesh.vertex_segment.size(); ++v) segs << (v ? ", " : "") << mesh.vertex_segment[v];
    segs << "]}";
    std::ofstream(base + "_vh_clean_2.0.010000.segs.json") << segs.str();
    std::map<int, std::vector<int>> segments_of_object;
    for (std::size_t v = 0; v < mesh.vertex_segment.size(); ++v) {
      auto& segments = segments_of_object[mesh.vertex_object[v]];
      if (std::find(segments.begin(), segments.end(), mesh.vertex_segment[v]) == segments.end()) {
        segments.push_back(mesh.vertex_segment[v]);
      }
    }
    std::ostringstream agg;
    agg << "{\"sceneId\": \"scannet." << scan_id << "\", \"appId\": \"Aggregator.v2\", \"segGroups\": [";
    int id = 0;
    for (std::size_t o = 0; o < mesh.objects.size(); ++o) {
      if (mesh.objects[o].raw_label.empty()) continue;
      agg << (id ? ", " : "") << "{\"id\": " << id << ", \"objectId\": " << id << ", \"segments\": [";
      const auto& segments = segments_of_object[static_cast<int>(o)];
      for (std::size_t k = 0; k < segments.size(); ++k) agg << (k ? ", " : "") << segments[k];
      agg << "], \"label\": \"" << mesh.objects[o].raw_label << "\"}";
      ++id;
    }
    agg << "], \"segmentsFile\": \"scannet." << scan_id << "_vh_clean_2.0.010000.segs.json\"}";
    std::ofstream(base + ".aggregation.json") << agg.str();
  }
  if (options.axis_alignment) {
    // axisAlignment maps the file's frame to the aligned one: the inverse of the transform above.
    const double R[3][3] = {{1, 0, 0}, {0, c, -s}, {0, s, c}};
    double M[4][4] = {{0}};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) M[r][k] = R[k][r];
      M[r][3] = -(R[0][r] * t[0] + R[1][r] * t[1] + R[2][r] * t[2]);
    }
    M[3][3] = 1;
    std::ostringstream txt;
    txt.precision(17);
    txt << "axisAlignment =";
    for (auto& row : M)
      for (double m : row) txt << " " << m;
    txt << "\ncolorHeight = 968\ncolorWidth = 1296\ndepthHeight = 480\ndepthWidth = 640\nnumColorFrames = 0\n"
           "numDepthFrames = 0\nnumIMUmeasurements = 0\nsceneType = Living room / Lounge\n";
    std::ofstream(base + ".txt") << txt.str();
  }
  return dir.string();
}

}  // namespace objscan::testing
