#pragma once
// Fast Point Feature Histograms (Rusu et al. 2009) computed by PCL (hidden in the .cc): 33 bins.
#include "objscan/recognition/descriptor.h"

namespace objscan::recognition {

class FpfhDescriptor : public DescriptorExtractor {
 public:
  static constexpr int kDimension = 33;
  explicit FpfhDescriptor(const DescriptorOptions& options) : options_(options) {}
  std::string Name() const override { return "fpfh"; }
  int Dimension() const override { return kDimension; }
  void Compute(const geometry::PointCloud& surface, const std::vector<Eigen::Vector3f>& keypoints,
               std::vector<float>* descriptors) const override;

 private:
  DescriptorOptions options_;
};

}  // namespace objscan::recognition
