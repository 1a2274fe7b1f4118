#include "objscan/recognition/fpfh_descriptor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/rng.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/test_database.h"

namespace objscan::recognition {
namespace {

// Our histograms must be PCL's FPFHEstimation's (databases were built with it): equal up to float
// rounding, which can move a rare pair feature across a bin edge.
TEST(FpfhDescriptorTest, MatchesPclFpfhEstimation) {
  for (testing::ShapeFn shape : {&testing::ChairLike, &testing::SofaLike}) {
    geometry::PointCloud cloud;
    std::vector<Eigen::Vector3f> keypoints;
    testing::NoisyShapeWithKeypoints(shape, 200, &cloud, &keypoints);
    keypoints.push_back(Eigen::Vector3f(50.f, 50.f, 50.f));  // no support: an all-zero row
    const FpfhDescriptor fpfh{DescriptorOptions()};
    std::vector<float> ours, pcl;
    fpfh.Compute(cloud, keypoints, &ours);
    fpfh.ComputeWithPcl(cloud, keypoints, &pcl);
    ASSERT_EQ(ours.size(), pcl.size());
    double max_row_l1 = 0.0, sum_l1 = 0.0;
    const int d = FpfhDescriptor::kDimension;
    for (std::size_t k = 0; k < keypoints.size(); ++k) {
      double l1 = 0.0, mass = 0.0;
      for (int b = 0; b < d; ++b) {
        l1 += std::abs(ours[k * d + b] - pcl[k * d + b]);
        mass += ours[k * d + b];
      }
      if (k + 1 < keypoints.size()) {
        EXPECT_NEAR(mass, 300.0, 0.1);  // three histograms of 100 each
      } else {
        EXPECT_EQ(mass, 0.0);
      }
      max_row_l1 = std::max(max_row_l1, l1);
      sum_l1 += l1;
    }
    EXPECT_LT(sum_l1 / keypoints.size(), 0.05);  // of 300 per row
    EXPECT_LT(max_row_l1, 3.0);
  }
}

}  // namespace
}  // namespace objscan::recognition
