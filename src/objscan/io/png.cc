#include "objscan/io/png.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <fstream>
#include <iterator>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"

namespace objscan::io {
namespace {

// libpng reports errors through a callback that must not return; we record the message and
// longjmp back to the setjmp point of the (POD-only) function that drives libpng.
struct ErrorState {
  char message[256] = {0};
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  if (state != nullptr) {
    std::strncpy(state->message, message != nullptr ? message : "unknown libpng error",
                 sizeof(state->message) - 1);
  }
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

void AppendToString(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void FlushNothing(png_structp) {}

// Encodes an image in memory. `rows` point at big-endian sample rows. Returns false and fills
// state->message on failure.
bool EncodePng(int width, int height, int bit_depth, int color_type, png_bytep* rows, std::string* out,
               ErrorState* state) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, state, OnPngError, OnPngWarning);
  if (png == nullptr) {
    std::strncpy(state->message, "cannot create libpng writer", sizeof(state->message) - 1);
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, AppendToString, FlushNothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth,
               color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

void CheckSize(const std::string& path, int width, int height, std::size_t values, int per_pixel) {
  if (width <= 0 || height <= 0) {
    throw InputError(path + ": cannot write a PNG of size " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (values != static_cast<std::size_t>(width) * height * per_pixel) {
    throw InputError(path + ": image buffer holds " + std::to_string(values) + " values, expected " +
                     std::to_string(static_cast<std::size_t>(width) * height * per_pixel));
  }
}

struct MemoryReader {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  std::size_t offset = 0;
};

void ReadFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* reader = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (reader->offset + length > reader->size) png_error(png, "file is truncated");
  std::memcpy(out, reader->data + reader->offset, length);
  reader->offset += length;
}

enum class Want { kRgb8, kGrey16 };

struct Decoded {
  int width = 0, height = 0;
  std::vector<unsigned char> bytes;  // rows as delivered by libpng after the transforms
  std::vector<unsigned char*> rows;  // pointers into `bytes` for libpng
};

// Decodes `file` (already in memory). Returns false and fills state->message on failure; a
// wrong format gives the message "not a 16-bit grey PNG" etc.
bool DecodePng(const std::string& file, Want want, Decoded* out, ErrorState* state) {
  if (file.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(file.data()), 0, 8) != 0) {
    std::strncpy(state->message, "not a PNG file", sizeof(state->message) - 1);
    return false;
  }
  MemoryReader reader{reinterpret_cast<const unsigned char*>(file.data()), file.size(), 0};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, state, OnPngError, OnPngWarning);
  if (png == nullptr) {
    std::strncpy(state->message, "cannot create libpng reader", sizeof(state->message) - 1);
    return false;
  }
  png_infop info = png_create_info_struct(png);
  // Row pointers live in `out` (owned by the caller) so a longjmp skips no destructors here.
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, &reader, ReadFromMemory);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  const int color_type = png_get_color_type(png, info);
  if (width == 0 || height == 0 || width > 1u << 15 || height > 1u << 15) png_error(png, "unsupported image size");
  if (want == Want::kGrey16) {
    if (bit_depth != 16 || color_type != PNG_COLOR_TYPE_GRAY) png_error(png, "not a 16-bit grey PNG");
    png_set_swap(png);  // PNG samples are big-endian; we hand out host-order uint16
  } else {
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (bit_depth == 16) png_set_strip_16(png);
    if (color_type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) {
      png_set_tRNS_to_alpha(png);
      png_set_strip_alpha(png);
    }
    if (color_type == PNG_COLOR_TYPE_GRAY || color_type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const png_size_t row_bytes = png_get_rowbytes(png, info);
  const png_size_t expected = want == Want::kGrey16 ? width * 2 : width * 3;
  if (row_bytes != expected) png_error(png, "unexpected row layout after conversion");
  out->width = static_cast<int>(width);
  out->height = static_cast<int>(height);
  out->bytes.resize(row_bytes * height);
  out->rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) out->rows[y] = out->bytes.data() + y * row_bytes;
  png_read_image(png, out->rows.data());  // handles every interlace pass
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open PNG file");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

Decoded Decode(const std::string& path, Want want) {
  const std::string file = ReadWholeFile(path);
  Decoded decoded;
  ErrorState state;
  if (!DecodePng(file, want, &decoded, &state)) throw InputError(path + ": bad PNG: " + state.message);
  return decoded;
}

void Encode(const std::string& path, int width, int height, int bit_depth, int color_type,
            std::vector<unsigned char>* row_data, std::size_t row_bytes) {
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) rows[y] = row_data->data() + y * row_bytes;
  std::string encoded;
  ErrorState state;
  if (!EncodePng(width, height, bit_depth, color_type, rows.data(), &encoded, &state)) {
    throw InputError(path + ": cannot encode PNG: " + state.message);
  }
  WriteFileAtomically(path, encoded);
}

}  // namespace

void WritePngRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  CheckSize(path, width, height, rgb.size(), 3);
  std::vector<unsigned char> data(rgb.begin(), rgb.end());
  Encode(path, width, height, 8, PNG_COLOR_TYPE_RGB, &data, static_cast<std::size_t>(width) * 3);
}

void WritePng16(const std::string& path, int width, int height, const std::vector<std::uint16_t>& values) {
  CheckSize(path, width, height, values.size(), 1);
  std::vector<unsigned char> data(values.size() * 2);
  for (std::size_t i = 0; i < values.size(); ++i) {
    data[2 * i] = static_cast<unsigned char>(values[i] >> 8);  // PNG is big-endian
    data[2 * i + 1] = static_cast<unsigned char>(values[i] & 0xff);
  }
  Encode(path, width, height, 16, PNG_COLOR_TYPE_GRAY, &data, static_cast<std::size_t>(width) * 2);
}

Image16 ReadPng16(const std::string& path) {
  Decoded decoded = Decode(path, Want::kGrey16);
  Image16 image;
  image.width = decoded.width;
  image.height = decoded.height;
  image.values.resize(static_cast<std::size_t>(decoded.width) * decoded.height);
  std::memcpy(image.values.data(), decoded.bytes.data(), image.values.size() * 2);
  return image;
}

ImageRgb ReadPngRgb(const std::string& path) {
  Decoded decoded = Decode(path, Want::kRgb8);
  ImageRgb image;
  image.width = decoded.width;
  image.height = decoded.height;
  image.rgb = std::move(decoded.bytes);
  return image;
}

}  // namespace objscan::io
