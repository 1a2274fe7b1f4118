#include "depth_image.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

// Whether this machine stores numbers little-endian (an image from another machine may differ).
bool HostIsBigEndian() {
  const std::uint16_t one = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

template <class T>
ImageBuffer PackImage(const std::vector<T>& values, int width, int height, const char* encoding) {
  ImageBuffer image;
  image.width = width;
  image.height = height;
  image.encoding = encoding;
  image.is_bigendian = HostIsBigEndian();
  image.step_bytes = static_cast<std::uint32_t>(width * sizeof(T));
  image.data.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(image.data.data(), values.data(), image.data.size());
  return image;
}

// Pixel (u, v) of a `Bytes`-wide channel as host-order bytes in `out`.
template <std::size_t Bytes>
void ReadPixel(const ImageBuffer& image, int u, int v, bool swap, std::uint8_t* out) {
  const std::uint8_t* p = image.data.data() + static_cast<std::size_t>(v) * image.step_bytes + u * Bytes;
  for (std::size_t b = 0; b < Bytes; ++b) out[b] = swap ? p[Bytes - 1 - b] : p[b];
}

void CheckSize(const ImageBuffer& image, std::size_t pixel_bytes, const std::string& what) {
  if (image.width <= 0 || image.height <= 0) {
    throw InputError(what + ": image of size " + std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  if (image.step_bytes < image.width * pixel_bytes ||
      image.data.size() < static_cast<std::size_t>(image.step_bytes) * image.height) {
    throw InputError(what + ": " + image.encoding + " image of " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " with step " + std::to_string(image.step_bytes) + " holds " +
                     std::to_string(image.data.size()) + " bytes, too few");
  }
}

}  // namespace

ImageBuffer DepthImageFromMetres(const std::vector<float>& depth_m, int width, int height) {
  std::vector<float> values(depth_m);
  for (float& d : values) {
    if (!(d > 0.f)) d = std::numeric_limits<float>::quiet_NaN();
  }
  return PackImage(values, width, height, "32FC1");
}

std::vector<float> DepthMetresFromImage(const ImageBuffer& image, const std::string& what) {
  const bool swap = image.is_bigendian != HostIsBigEndian();
  std::vector<float> depth_m(static_cast<std::size_t>(std::max(0, image.width)) * std::max(0, image.height), 0.f);
  if (image.encoding == "32FC1") {
    CheckSize(image, 4, what);
    for (int v = 0; v < image.height; ++v) {
      for (int u = 0; u < image.width; ++u) {
        float d = 0.f;
        ReadPixel<4>(image, u, v, swap, reinterpret_cast<std::uint8_t*>(&d));
        depth_m[static_cast<std::size_t>(v) * image.width + u] = std::isfinite(d) && d > 0.f ? d : 0.f;
      }
    }
  } else if (image.encoding == "16UC1" || image.encoding == "mono16") {
    CheckSize(image, 2, what);
    for (int v = 0; v < image.height; ++v) {
      for (int u = 0; u < image.width; ++u) {
        std::uint16_t mm = 0;
        ReadPixel<2>(image, u, v, swap, reinterpret_cast<std::uint8_t*>(&mm));
        depth_m[static_cast<std::size_t>(v) * image.width + u] = static_cast<float>(mm) * 0.001f;
      }
    }
  } else {
    throw InputError(what + ": depth image encoding '" + image.encoding + "' (expected 32FC1 metres or 16UC1 millimetres)");
  }
  return depth_m;
}

ImageBuffer InstanceImage(const std::vector<std::int32_t>& instance, int width, int height) {
  return PackImage(instance, width, height, "32SC1");
}

std::vector<std::int32_t> InstancesFromImage(const ImageBuffer& image, const std::string& what) {
  if (image.encoding != "32SC1") {
    throw InputError(what + ": instance image encoding '" + image.encoding + "' (expected 32SC1)");
  }
  CheckSize(image, 4, what);
  const bool swap = image.is_bigendian != HostIsBigEndian();
  std::vector<std::int32_t> out(static_cast<std::size_t>(image.width) * image.height, 0);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      ReadPixel<4>(image, u, v, swap, reinterpret_cast<std::uint8_t*>(&out[static_cast<std::size_t>(v) * image.width + u]));
    }
  }
  return out;
}

CameraInfoBuffer CameraInfoFromIntrinsics(const platform::CameraIntrinsics& k) {
  CameraInfoBuffer info;
  info.width = k.width_px;
  info.height = k.height_px;
  info.K = {k.fx_px, 0.0, k.cx_px, 0.0, k.fy_px, k.cy_px, 0.0, 0.0, 1.0};
  info.P = {k.fx_px, 0.0, k.cx_px, 0.0, 0.0, k.fy_px, k.cy_px, 0.0, 0.0, 0.0, 1.0, 0.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  return info;
}

platform::CameraIntrinsics IntrinsicsFromCameraInfo(const CameraInfoBuffer& info, double min_range_m,
                                                    double max_range_m, const std::string& what) {
  if (info.width <= 0 || info.height <= 0) {
    throw InputError(what + ": camera info of size " + std::to_string(info.width) + "x" + std::to_string(info.height));
  }
  if (!(info.K[0] > 0.0) || !(info.K[4] > 0.0)) throw InputError(what + ": camera info without focal lengths (K)");
  platform::CameraIntrinsics k;
  k.width_px = info.width;
  k.height_px = info.height;
  k.fx_px = info.K[0];
  k.fy_px = info.K[4];
  k.cx_px = info.K[2];
  k.cy_px = info.K[5];
  k.min_range_m = min_range_m;
  k.max_range_m = max_range_m;
  return k;
}

}  // namespace objscan::ros_bridge
