#include "objscan/io/ply.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

PlyData MakeSample() {
  PlyData d;
  for (int i = 0; i < 5; ++i) {
    d.points.emplace_back(0.1f * i, -2.5f + i, 1e-3f * i * i);
    d.normals.emplace_back(0, i % 2, 1 - i % 2);
    d.colors.push_back({static_cast<std::uint8_t>(i), 200, static_cast<std::uint8_t>(255 - i)});
  }
  d.int_properties.push_back({"object_id", {1, 2, -3, 4, 100000}});
  d.int_properties.push_back({"category_id", {0, 21, 23, 5, 7}});
  d.triangles = {{0, 1, 2}, {2, 3, 4}};
  return d;
}

void ExpectSame(const PlyData& a, const PlyData& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i], b.points[i]) << i;  // %.9g / raw floats both round-trip exactly
    EXPECT_EQ(a.normals[i], b.normals[i]) << i;
    EXPECT_EQ(a.colors[i], b.colors[i]) << i;
  }
  ASSERT_EQ(a.int_properties.size(), b.int_properties.size());
  for (std::size_t k = 0; k < a.int_properties.size(); ++k) {
    EXPECT_EQ(a.int_properties[k], b.int_properties[k]);
  }
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) EXPECT_EQ(a.triangles[i], b.triangles[i]);
}

TEST(PlyTest, BinaryRoundTrip) {
  TempDir dir;
  const PlyData d = MakeSample();
  WritePly(dir.File("b.ply"), d, /*binary=*/true);
  ExpectSame(d, ReadPly(dir.File("b.ply")));
}

TEST(PlyTest, AsciiRoundTrip) {
  TempDir dir;
  const PlyData d = MakeSample();
  WritePly(dir.File("a.ply"), d, /*binary=*/false);
  ExpectSame(d, ReadPly(dir.File("a.ply")));
}

TEST(PlyTest, PointCloudWithoutExtras) {
  TempDir dir;
  PlyData d;
  d.points = {{1, 2, 3}, {4, 5, 6}};
  WritePly(dir.File("p.ply"), d);
  const PlyData back = ReadPly(dir.File("p.ply"));
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1], Eigen::Vector3f(4, 5, 6));
  EXPECT_TRUE(back.normals.empty());
  EXPECT_TRUE(back.colors.empty());
  EXPECT_TRUE(back.int_properties.empty());
  EXPECT_TRUE(back.triangles.empty());
}

TEST(PlyTest, ReadsForeignLayoutsQuadsAndBigEndian) {
  TempDir dir;
  // ASCII with double coordinates, an extra float property, a quad and an unrelated element.
  testing::WriteText(dir.File("q.ply"),
                     "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty double x\nproperty double y\n"
                     "property double z\nproperty float quality\nelement face 1\nproperty list uchar uint vertex_index\n"
                     "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                     "0 0 0 0.5\n1 0 0 0.5\n1 1 0 0.5\n0 1 0 0.5\n4 0 1 2 3\n0 1\n");
  const PlyData q = ReadPly(dir.File("q.ply"));
  ASSERT_EQ(q.points.size(), 4u);
  ASSERT_EQ(q.triangles.size(), 2u);  // fan split of the quad
  EXPECT_EQ(q.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_TRUE(q.int_properties.empty());  // float "quality" is not an int property

  // Big-endian: one vertex (1.5, -2, 0.25) with a short label 258.
  std::string be = "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                   "property float z\nproperty short label\nend_header\n";
  for (float f : {1.5f, -2.0f, 0.25f}) {
    unsigned char b[4];
    std::memcpy(b, &f, 4);
    for (int k = 3; k >= 0; --k) be += static_cast<char>(b[k]);
  }
  be += static_cast<char>(1);
  be += static_cast<char>(2);
  testing::WriteText(dir.File("be.ply"), be);
  const PlyData b = ReadPly(dir.File("be.ply"));
  ASSERT_EQ(b.points.size(), 1u);
  EXPECT_EQ(b.points[0], Eigen::Vector3f(1.5f, -2.0f, 0.25f));
  ASSERT_EQ(b.int_properties.size(), 1u);
  EXPECT_EQ(b.int_properties[0].first, "label");
  EXPECT_EQ(b.int_properties[0].second[0], 258);
}

// Found by fuzzing (fuzz/regressions/ply/element_without_properties_huge_count.ply): an element
// with no properties holds no bytes, so its count is not bounded by the file's size; reading it must
// not loop over 10^12 empty rows.
TEST(PlyTest, ElementWithoutPropertiesAndAHugeCountIsReadAtOnce) {
  TempDir dir;
  testing::WriteText(dir.File("e.ply"),
                     "ply\nformat ascii 1.0\nelement nothing 1000000000000\nelement vertex 1\nproperty float x\n"
                     "property float y\nproperty float z\nelement more 6242949672950\nend_header\n1 2 3\n");
  const PlyData d = ReadPly(dir.File("e.ply"));
  ASSERT_EQ(d.points.size(), 1u);
  EXPECT_EQ(d.points[0], Eigen::Vector3f(1.f, 2.f, 3.f));
}

TEST(PlyTest, CorruptFilesNameThePath) {
  TempDir dir;
  ExpectInputError([&] { ReadPly(dir.File("none.ply")); }, "none.ply");
  testing::WriteText(dir.File("magic.ply"), "plx\nformat ascii 1.0\nend_header\n");
  ExpectInputError([&] { ReadPly(dir.File("magic.ply")); }, "magic.ply");
  testing::WriteText(dir.File("noend.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  ExpectInputError([&] { ReadPly(dir.File("noend.ply")); }, "noend.ply");
  testing::WriteText(dir.File("short.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "end_header\n0 0 0\n1 1 1\n");
  ExpectInputError([&] { ReadPly(dir.File("short.ply")); }, "short.ply");
  testing::WriteText(dir.File("text.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                     "end_header\n0 zero 0\n");
  ExpectInputError([&] { ReadPly(dir.File("text.ply")); }, "text.ply");
  testing::WriteText(dir.File("index.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 0 7\n");
  ExpectInputError([&] { ReadPly(dir.File("index.ply")); }, "index.ply");
  testing::WriteText(dir.File("huge.ply"),
                     "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                     "property float y\nproperty float z\nend_header\n");
  ExpectInputError([&] { ReadPly(dir.File("huge.ply")); }, "huge.ply");
  // Values that do not fit their use (found by fuzzing: converting them was undefined behaviour):
  // a vertex index beyond int32, a NaN list length, a non-integer index, an int property beyond int32.
  const std::string xyz = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  const auto expect_error = [&](const std::string& name, const std::string& text, const std::string& what) {
    testing::WriteText(dir.File(name), text);
    try {
      ReadPly(dir.File(name));
      ADD_FAILURE() << name << " read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), dir.File(name) + ": bad PLY: " + what);
    }
  };
  expect_error("big_index.ply", xyz + face + "3 0 1 4294967295\n", "face 0 has a vertex index that is not a 32-bit integer");
  expect_error("nan_count.ply", xyz + face + "nan 0 1 2\n", "face 0 has a bad vertex count");
  expect_error("half_index.ply", xyz + face + "3 0 1 1.5\n", "face 0 has a vertex index that is not a 32-bit integer");
  expect_error("big_label.ply", xyz + "property uint label\nend_header\n0 0 0 3000000000\n1 0 0 1\n0 1 0 2\n",
               "vertex 0 property 'label' is not a 32-bit integer");
  expect_error("vertex_list.ply", xyz + "property list uchar int extra\nend_header\n0 0 0 -1\n1 0 0 0\n0 1 0 0\n",
               "vertex 0 has a bad list length for 'extra'");
  // NaN colours are black, not an undefined conversion.
  testing::WriteText(dir.File("nan_colour.ply"), xyz + "property float red\nproperty float green\nproperty float blue\n"
                                                   "end_header\n0 0 0 nan 2 0.5\n1 0 0 0 0 0\n0 1 0 1 1 1\n");
  const PlyData coloured = ReadPly(dir.File("nan_colour.ply"));
  ASSERT_EQ(coloured.colors.size(), 3u);
  EXPECT_EQ(coloured.colors[0], (std::array<std::uint8_t, 3>{0, 255, 128}));
  // Binary file cut short.
  WritePly(dir.File("full.ply"), MakeSample());
  std::filesystem::copy_file(dir.File("full.ply"), dir.File("cut.ply"));
  std::filesystem::resize_file(dir.File("cut.ply"), std::filesystem::file_size(dir.File("full.ply")) - 5);
  ExpectInputError([&] { ReadPly(dir.File("cut.ply")); }, "cut.ply");
}

// Header comments (category names, say) come back in order after the writer's own, in both formats;
// a file read and written again keeps one "written by objscan".
TEST(PlyTest, CommentsRoundTrip) {
  TempDir dir;
  PlyData d = MakeSample();
  d.comments = {"category 4 chair 148 103 189", "second  comment with  spaces"};
  for (const bool binary : {true, false}) {
    const std::string path = dir.File(binary ? "cb.ply" : "ca.ply");
    WritePly(path, d, binary);
    const PlyData back = ReadPly(path);
    EXPECT_EQ(back.comments,
              (std::vector<std::string>{"written by objscan", "category 4 chair 148 103 189", "second  comment with  spaces"}));
    ExpectSame(d, back);
    WritePly(dir.File("again.ply"), back, binary);
    EXPECT_EQ(ReadPly(dir.File("again.ply")).comments, back.comments);
  }
  d.comments = {"two\nlines"};
  ExpectInputError([&] { WritePly(dir.File("x.ply"), d); }, "spans lines");
  EXPECT_FALSE(std::filesystem::exists(dir.File("x.ply")));
}

TEST(PlyTest, InconsistentDataIsRejectedAndLeavesNoFile) {
  TempDir dir;
  PlyData d = MakeSample();
  d.int_properties[0].second.pop_back();
  ExpectInputError([&] { WritePly(dir.File("x.ply"), d); }, "object_id");
  d = MakeSample();
  d.triangles.emplace_back(0, 1, 5);
  ExpectInputError([&] { WritePly(dir.File("x.ply"), d); }, "x.ply");
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(PlyTest, FilesLargerThanAWriteChunkRoundTripWhole) {
  // 200k vertices with every property and 100k triangles: several megabytes in either encoding, so
  // the writer flushes its buffer many times, in the middle of vertices and of faces.
  PlyData d;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    d.points.emplace_back(1e-3f * static_cast<float>(i), -0.5f * static_cast<float>(i % 7), 1.0f / static_cast<float>(i + 1));
    d.normals.emplace_back(0.f, static_cast<float>(i % 2), static_cast<float>(1 - i % 2));
    d.colors.push_back({static_cast<std::uint8_t>(i % 256), 7, static_cast<std::uint8_t>((i / 256) % 256)});
  }
  std::vector<std::int32_t> ids(n);
  for (int i = 0; i < n; ++i) ids[i] = i * 13 - 5;
  d.int_properties.push_back({"object_id", ids});
  for (int i = 0; i + 2 < n; i += 2) d.triangles.emplace_back(i, i + 1, i + 2);
  TempDir dir;
  for (const bool binary : {true, false}) {
    const std::string path = dir.File(binary ? "big_b.ply" : "big_a.ply");
    WritePly(path, d, binary);
    EXPECT_GT(std::filesystem::file_size(path), std::uintmax_t{4} << 20);
    ExpectSame(d, ReadPly(path));
  }
  // Only the two files: no temporary left beside them.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 2);
}

TEST(PlyTest, AFolderThatCannotBeWrittenNamesTheFileAndLeavesNothing) {
  TempDir dir;
  const std::string blocker = dir.File("not_a_folder");
  WritePly(blocker, MakeSample());  // a file where the folder should be
  ExpectInputError([&] { WritePly(blocker + "/x.ply", MakeSample()); }, "not_a_folder/x.ply");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(PlyTest, AStreamWriterGivesTheBytesOfWritePly) {
  TempDir dir;
  PlyData d = MakeSample();
  d.comments = {"made by a test"};
  for (const bool binary : {true, false}) {
    const std::string whole = dir.File(binary ? "whole_b.ply" : "whole_a.ply");
    const std::string streamed = dir.File(binary ? "streamed_b.ply" : "streamed_a.ply");
    WritePly(whole, d, binary);
    PlyStreamWriter writer(streamed, LayoutOf(d, binary));
    for (std::size_t i = 0; i < d.points.size(); ++i) {
      const std::int32_t ints[2] = {d.int_properties[0].second[i], d.int_properties[1].second[i]};
      writer.AddVertex(d.points[i], d.normals[i], d.colors[i], ints);
    }
    EXPECT_FALSE(std::filesystem::exists(streamed)) << "the file appears at Commit()";
    for (const auto& t : d.triangles) writer.AddTriangle(t);
    writer.Commit();
    EXPECT_EQ(FileBytes(streamed), FileBytes(whole));
    ExpectSame(d, ReadPly(streamed));
  }
}

TEST(PlyTest, AStreamWriterRefusesOtherCountsThanAnnouncedAndLeavesNoFile) {
  TempDir dir;
  const PlyData d = MakeSample();
  const std::int32_t ints[2] = {1, 2};
  {
    // Too few vertices at Commit().
    PlyStreamWriter writer(dir.File("few.ply"), LayoutOf(d, true));
    writer.AddVertex(d.points[0], d.normals[0], d.colors[0], ints);
    ExpectInputError([&] { writer.Commit(); }, "few.ply");
  }
  {
    // A face before the vertices are all written, and a face index out of range.
    PlyStreamWriter writer(dir.File("early.ply"), LayoutOf(d, true));
    ExpectInputError([&] { writer.AddTriangle({0, 1, 2}); }, "early.ply");
    for (std::size_t i = 0; i < d.points.size(); ++i) writer.AddVertex(d.points[i], d.normals[i], d.colors[i], ints);
    ExpectInputError([&] { writer.AddVertex(d.points[0], d.normals[0], d.colors[0], ints); }, "early.ply");
    ExpectInputError([&] { writer.AddTriangle({0, 1, 5}); }, "triangle index 5");
  }
  {
    PlyLayout bad = LayoutOf(d, true);
    bad.int_properties[0] = "two words";
    ExpectInputError([&] { PlyStreamWriter writer(dir.File("bad.ply"), bad); }, "bad property name");
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace objscan::io
