#include "objscan/io/png.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

TEST(PngTest, RgbRoundTripIsExact) {
  TempDir dir;
  const int w = 37, h = 11;
  std::vector<std::uint8_t> rgb(w * h * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>((i * 7919) % 256);
  WritePngRgb(dir.File("a.png"), w, h, rgb);
  const ImageRgb back = ReadPngRgb(dir.File("a.png"));
  EXPECT_EQ(back.width, w);
  EXPECT_EQ(back.height, h);
  EXPECT_EQ(back.rgb, rgb);
  // Nothing but the target is left in the folder (the temporary file was renamed).
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(PngTest, Grey16RoundTripKeepsFullRange) {
  TempDir dir;
  const int w = 300, h = 7;
  std::vector<std::uint16_t> values(w * h);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<std::uint16_t>(i * 31);
  values[0] = 0;
  values[1] = 65535;
  values[2] = 256;  // distinguishes byte order
  WritePng16(dir.File("d.png"), w, h, values);
  const Image16 back = ReadPng16(dir.File("d.png"));
  EXPECT_EQ(back.width, w);
  EXPECT_EQ(back.height, h);
  EXPECT_EQ(back.values, values);
}

TEST(PngTest, Grey16ReadRejectsRgbFile) {
  TempDir dir;
  WritePngRgb(dir.File("c.png"), 2, 2, std::vector<std::uint8_t>(12, 5));
  ExpectInputError([&] { ReadPng16(dir.File("c.png")); }, "c.png");
  ExpectInputError([&] { ReadPng16(dir.File("c.png")); }, "16-bit grey");
}

TEST(PngTest, RgbReadConvertsGrey16) {
  TempDir dir;
  WritePng16(dir.File("g.png"), 2, 1, {0, 65535});
  const ImageRgb back = ReadPngRgb(dir.File("g.png"));
  ASSERT_EQ(back.rgb.size(), 6u);
  EXPECT_EQ(back.rgb[0], 0);
  EXPECT_EQ(back.rgb[3], 255);
  EXPECT_EQ(back.rgb[5], 255);
}

TEST(PngTest, MissingCorruptAndTruncatedFilesNameThePath) {
  TempDir dir;
  ExpectInputError([&] { ReadPngRgb(dir.File("missing.png")); }, "missing.png");
  testing::WriteText(dir.File("text.png"), "this is not a png");
  ExpectInputError([&] { ReadPngRgb(dir.File("text.png")); }, "text.png");
  // A valid file cut in half.
  std::vector<std::uint8_t> rgb(64 * 64 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>(i * 13);
  WritePngRgb(dir.File("full.png"), 64, 64, rgb);
  const auto size = std::filesystem::file_size(dir.File("full.png"));
  std::filesystem::copy_file(dir.File("full.png"), dir.File("cut.png"));
  std::filesystem::resize_file(dir.File("cut.png"), size / 2);
  ExpectInputError([&] { ReadPngRgb(dir.File("cut.png")); }, "cut.png");
}

TEST(PngTest, FailedWriteLeavesNoFile) {
  TempDir dir;
  ExpectInputError([&] { WritePngRgb(dir.File("nodir/x.png"), 2, 2, std::vector<std::uint8_t>(12)); }, "x.png");
  ExpectInputError([&] { WritePngRgb(dir.File("bad.png"), 2, 2, std::vector<std::uint8_t>(5)); }, "bad.png");
  EXPECT_FALSE(std::filesystem::exists(dir.File("bad.png")));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace objscan::io
