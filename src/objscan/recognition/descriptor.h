#pragma once
// Local shape descriptors at keypoints, behind an interface: the paper uses 3DMatch (learned weights
// we cannot obtain); objscan ships FPFH (PCL), and a learned descriptor can be added as another
// implementation selected by DescriptorOptions::type.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/point_cloud.h"

namespace objscan::recognition {

struct DescriptorOptions {
  std::string type = "fpfh";
  // Metric support radius: the sensor gives true scale, so a fixed radius describes the same local
  // geometry on a partial view and on the full model (a radius tied to each point set's own bounding
  // box would not, since a partial view has a smaller box).
  double support_radius_m = 0.10;
  double normal_radius_m = 0.05;    // PCA normals over this radius (given normals only orient them)
  double surface_voxel_m = 0.025;   // the surface is thinned to this spacing before describing

  template <class V>
  void Visit(V& v) {
    v("type", type);
    v("support_radius_m", support_radius_m);
    v("normal_radius_m", normal_radius_m);
    v("surface_voxel_m", surface_voxel_m);
  }
  void Validate() const;
};

class DescriptorExtractor {
 public:
  virtual ~DescriptorExtractor() = default;
  virtual std::string Name() const = 0;
  virtual int Dimension() const = 0;
  // Describes the surface around each keypoint. `surface` may carry normals (used for orientation)
  // or not (oriented away from the surface's centroid). Output: keypoints.size() x Dimension(),
  // row-major; a keypoint with too little support gets an all-zero row.
  virtual void Compute(const geometry::PointCloud& surface, const std::vector<Eigen::Vector3f>& keypoints,
                       std::vector<float>* descriptors) const = 0;
};

// Throws ConfigError naming recognition.descriptor.type for an unknown type.
std::unique_ptr<DescriptorExtractor> MakeDescriptorExtractor(const DescriptorOptions& options);

}  // namespace objscan::recognition
