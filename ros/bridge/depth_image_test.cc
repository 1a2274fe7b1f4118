#include "depth_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

TEST(DepthImageTest, MetresTravelExactlyAndInvalidBecomesNan) {
  const std::vector<float> depth = {0.f, 1.25f, 3.999999f, 0.5f, 0.f, 2.f};
  const ImageBuffer image = DepthImageFromMetres(depth, 3, 2);
  EXPECT_EQ(image.encoding, "32FC1");
  EXPECT_EQ(image.step_bytes, 12u);
  ASSERT_EQ(image.data.size(), 24u);
  float first = 0.f;
  std::memcpy(&first, image.data.data(), 4);
  EXPECT_TRUE(std::isnan(first)) << "REP 118: no return is NaN, not 0";
  EXPECT_EQ(DepthMetresFromImage(image, "depth"), depth);
}

TEST(DepthImageTest, ReadsMillimetresBigEndianAndPaddedRows) {
  // 2x2 16UC1, big-endian, rows padded to 6 bytes: 1000 mm, 0 (invalid), 2500 mm, 65535 mm.
  ImageBuffer image;
  image.width = 2;
  image.height = 2;
  image.encoding = "16UC1";
  image.is_bigendian = true;
  image.step_bytes = 6;
  image.data = {0x03, 0xE8, 0x00, 0x00, 0xAA, 0xAA, 0x09, 0xC4, 0xFF, 0xFF, 0xAA, 0xAA};
  const std::vector<float> depth = DepthMetresFromImage(image, "depth");
  ASSERT_EQ(depth.size(), 4u);
  EXPECT_FLOAT_EQ(depth[0], 1.0f);
  EXPECT_EQ(depth[1], 0.f);
  EXPECT_FLOAT_EQ(depth[2], 2.5f);
  EXPECT_FLOAT_EQ(depth[3], 65.535f);
}

TEST(DepthImageTest, FloatInfinitiesAndNegativesAreInvalid) {
  const std::vector<float> raw = {INFINITY, -INFINITY, -1.f, 2.f};
  ImageBuffer image = DepthImageFromMetres({1.f, 1.f, 1.f, 1.f}, 2, 2);
  std::memcpy(image.data.data(), raw.data(), 16);
  EXPECT_EQ(DepthMetresFromImage(image, "depth"), (std::vector<float>{0.f, 0.f, 0.f, 2.f}));
}

TEST(DepthImageTest, RejectsOtherEncodingsAndShortBuffersNamingTheTopic) {
  ImageBuffer image = DepthImageFromMetres({1.f, 2.f}, 2, 1);
  image.encoding = "rgb8";
  try {
    DepthMetresFromImage(image, "/camera/depth/image");
    FAIL() << "rgb8 is no depth";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/camera/depth/image"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rgb8"), std::string::npos) << e.what();
  }
  image.encoding = "32FC1";
  image.data.resize(7);
  EXPECT_THROW(DepthMetresFromImage(image, "depth"), InputError);
  image.height = 0;
  EXPECT_THROW(DepthMetresFromImage(image, "depth"), InputError);
}

TEST(DepthImageTest, InstancesRoundTrip) {
  const std::vector<std::int32_t> ids = {0, 7, -1, 123456};
  const ImageBuffer image = InstanceImage(ids, 2, 2);
  EXPECT_EQ(image.encoding, "32SC1");
  EXPECT_EQ(InstancesFromImage(image, "gt"), ids);
  ImageBuffer wrong = image;
  wrong.encoding = "32FC1";
  EXPECT_THROW(InstancesFromImage(wrong, "gt"), InputError);
}

TEST(DepthImageTest, CameraInfoCarriesThePinholeModel) {
  platform::CameraIntrinsics k;
  k.width_px = 160;
  k.height_px = 120;
  k.fx_px = 131.25;
  k.fy_px = 130.5;
  k.cx_px = 79.5;
  k.cy_px = 59.25;
  const CameraInfoBuffer info = CameraInfoFromIntrinsics(k);
  EXPECT_EQ(info.K[0], 131.25);
  EXPECT_EQ(info.K[2], 79.5);
  EXPECT_EQ(info.P[5], 130.5);
  EXPECT_EQ(info.K[8], 1.0);
  const platform::CameraIntrinsics back = IntrinsicsFromCameraInfo(info, 0.4, 5.0, "info");
  EXPECT_EQ(back.width_px, 160);
  EXPECT_EQ(back.height_px, 120);
  EXPECT_EQ(back.fx_px, k.fx_px);
  EXPECT_EQ(back.fy_px, k.fy_px);
  EXPECT_EQ(back.cx_px, k.cx_px);
  EXPECT_EQ(back.cy_px, k.cy_px);
  EXPECT_EQ(back.min_range_m, 0.4);
  EXPECT_EQ(back.max_range_m, 5.0);
  CameraInfoBuffer uncalibrated = info;
  uncalibrated.K = {};
  EXPECT_THROW(IntrinsicsFromCameraInfo(uncalibrated, 0.4, 5.0, "info"), InputError);
}

}  // namespace
}  // namespace objscan::ros_bridge
