#pragma once
// PNG files (libpng hidden in the .cc). Writes are atomic: a failed write leaves no file behind.
#include <cstdint>
#include <string>
#include <vector>

namespace objscan::io {

// 8-bit RGB, row-major, 3 bytes per pixel. Throws InputError naming the path on failure.
void WritePngRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);
// 16-bit grey (e.g. depth in millimetres, instance ids).
void WritePng16(const std::string& path, int width, int height, const std::vector<std::uint16_t>& values);

struct Image16 {
  int width = 0, height = 0;
  std::vector<std::uint16_t> values;
};
struct ImageRgb {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};
// Throws InputError naming the path when missing, corrupt or of another format.
Image16 ReadPng16(const std::string& path);
ImageRgb ReadPngRgb(const std::string& path);

}  // namespace objscan::io
