#include "objscan/io/zip_archive.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"
#include "objscan/io/test_zip_writer.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::ZipWriter;

// A text long and repetitive enough that deflate really compresses it.
std::string LongText() {
  std::string text;
  for (int i = 0; i < 500; ++i) text += "v " + std::to_string(i) + " 0.5 1.25\n";
  return text;
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(Crc32Test, KnownValue) {
  EXPECT_EQ(Crc32("123456789"), 0xCBF43926u);  // the CRC-32 check value
  EXPECT_EQ(Crc32(""), 0u);
}

TEST(ZipArchiveTest, ListsAndReadsStoredAndDeflatedEntries) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("README.txt", "hello zip\n");
  zip.Add("models/", "");
  zip.Add("models/box.obj", LongText(), /*deflate=*/true);
  zip.Add("empty.txt", "");
  const std::string path = dir.File("a.zip");
  zip.Write(path);

  const ZipArchive archive = ZipArchive::Open(path);
  ASSERT_EQ(archive.entries().size(), 4u);
  EXPECT_EQ(archive.entries()[0].name, "README.txt");
  EXPECT_EQ(archive.entries()[0].method, 0);
  EXPECT_TRUE(archive.entries()[1].IsDirectory());
  const ZipEntry* obj = archive.Find("models/box.obj");
  ASSERT_NE(obj, nullptr);
  EXPECT_EQ(obj->method, 8);
  EXPECT_LT(obj->compressed_size, obj->uncompressed_size / 2);  // really deflated
  EXPECT_EQ(archive.Read("README.txt"), "hello zip\n");
  EXPECT_EQ(archive.Read("models/box.obj"), LongText());
  EXPECT_EQ(archive.Read("empty.txt"), "");
  EXPECT_FALSE(archive.Contains("models/missing.obj"));
}

TEST(ZipArchiveTest, MissingEntryNamesArchiveAndEntry) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("a.txt", "a");
  const std::string path = dir.File("a.zip");
  zip.Write(path);
  const ZipArchive archive = ZipArchive::Open(path);
  ExpectInputError([&] { archive.Read("b.txt"); }, path + ": no entry 'b.txt'");
}

TEST(ZipArchiveTest, MissingAndForeignFiles) {
  TempDir dir;
  ExpectInputError([&] { ZipArchive::Open(dir.File("none.zip")); }, dir.File("none.zip") + ": cannot open");
  WriteBytes(dir.File("text.zip"), std::string(100, 'x'));
  ExpectInputError([&] { ZipArchive::Open(dir.File("text.zip")); }, dir.File("text.zip") + ": not a zip archive");
  WriteBytes(dir.File("short.zip"), "PK");
  ExpectInputError([&] { ZipArchive::Open(dir.File("short.zip")); }, "not a zip archive");
}

TEST(ZipArchiveTest, TruncatedArchiveIsAnInputErrorNamingIt) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("a.txt", "some text");
  zip.Add("b.obj", LongText(), true);
  const std::string bytes = zip.Bytes();
  const std::string path = dir.File("t.zip");
  // Cut anywhere: the end record is gone (or, cut inside it, it no longer ends the file).
  for (std::size_t keep : {bytes.size() - 1, bytes.size() - 10, bytes.size() / 2, std::size_t{40}, std::size_t{0}}) {
    WriteBytes(path, bytes.substr(0, keep));
    ExpectInputError([&] { ZipArchive::Open(path); }, path + ": ");
  }
}

TEST(ZipArchiveTest, FlippedDataByteIsACrcError) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("a.txt", "some stored text");
  const std::string path = dir.File("c.zip");
  std::string bytes = zip.Bytes();
  const std::size_t data_at = 30 + std::string("a.txt").size();
  bytes[data_at + 3] ^= 0x20;
  WriteBytes(path, bytes);
  const ZipArchive archive = ZipArchive::Open(path);  // the directory is intact
  ExpectInputError([&] { archive.Read("a.txt"); }, path + ": a.txt: CRC-32 mismatch");
}

TEST(ZipArchiveTest, DamagedDeflateDataIsAnInputError) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("b.obj", LongText(), true);
  const std::string path = dir.File("d.zip");
  std::string bytes = zip.Bytes();
  const std::size_t data_at = 30 + std::string("b.obj").size();
  for (std::size_t k = 0; k < 16; ++k) bytes[data_at + 5 + k] = static_cast<char>(0xff);
  WriteBytes(path, bytes);
  const ZipArchive archive = ZipArchive::Open(path);
  ExpectInputError([&] { archive.Read("b.obj"); }, path + ": b.obj: ");
}

TEST(ZipArchiveTest, UnsupportedMethodAndBadLocalHeader) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("a.txt", "text");
  std::string bytes = zip.Bytes();
  const std::string path = dir.File("m.zip");
  // Method 12 (bzip2) in the central directory: it starts after the local header and the data.
  const std::size_t cd_at = 30 + 5 + 4;
  bytes[cd_at + 10] = 12;
  WriteBytes(path, bytes);
  ExpectInputError([&] { ZipArchive::Open(path).Read("a.txt"); }, path + ": a.txt: unsupported zip compression method 12");

  bytes = zip.Bytes();
  bytes[0] = 'X';  // local header signature
  WriteBytes(path, bytes);
  ExpectInputError([&] { ZipArchive::Open(path).Read("a.txt"); }, path + ": a.txt: bad local header signature");
}

TEST(ZipArchiveTest, ReadsArchivesWithAComment) {
  TempDir dir;
  ZipWriter zip;
  zip.Add("a.txt", "text");
  std::string bytes = zip.Bytes();
  const std::string comment = "a comment PK\x05\x06 with a fake signature";
  bytes[bytes.size() - 2] = static_cast<char>(comment.size());
  bytes += comment;
  const std::string path = dir.File("comment.zip");
  WriteBytes(path, bytes);
  EXPECT_EQ(ZipArchive::Open(path).Read("a.txt"), "text");
}

}  // namespace
}  // namespace objscan::io
