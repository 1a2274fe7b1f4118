#include "objscan/recognition/fpfh_descriptor.h"

#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>

#include "objscan/recognition/keypoints.h"

namespace objscan::recognition {

void DescriptorOptions::Validate() const {
  config::Require(type == "fpfh", "recognition.descriptor.type", "must be fpfh (got '" + type + "')");
  config::RequirePositive("recognition.descriptor.support_radius_m", support_radius_m);
  config::RequirePositive("recognition.descriptor.normal_radius_m", normal_radius_m);
  config::RequireNonNegative("recognition.descriptor.surface_voxel_m", surface_voxel_m);
}

std::unique_ptr<DescriptorExtractor> MakeDescriptorExtractor(const DescriptorOptions& options) {
  options.Validate();
  return std::make_unique<FpfhDescriptor>(options);
}

void FpfhDescriptor::Compute(const geometry::PointCloud& surface, const std::vector<Eigen::Vector3f>& keypoints,
                             std::vector<float>* descriptors) const {
  descriptors->assign(keypoints.size() * kDimension, 0.f);
  if (keypoints.empty() || surface.empty()) return;

  const std::vector<int> kept = VoxelThin(surface.points, options_.surface_voxel_m);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(kept.size());
  for (int i : kept) {
    const auto& p = surface.points[i];
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);

  // Normals are always re-estimated by PCA over normal_radius_m of the thinned surface: a single noisy
  // view and a fused clean scan then get equally smooth normals (per-pixel map normals of one noisy
  // frame would make the same shape look different). Given normals only decide the orientation.
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(tree);
  estimation.setRadiusSearch(options_.normal_radius_m);
  estimation.compute(*normals);
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : *cloud) centroid += p.getVector3fMap();
  centroid /= static_cast<float>(cloud->size());
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    Eigen::Map<Eigen::Vector3f> n = (*normals)[i].getNormalVector3fMap();
    // Orientation: towards the sensor side when the surface has normals, else away from the centroid.
    const Eigen::Vector3f reference = surface.HasNormals() ? surface.normals[kept[i]]
                                                           : Eigen::Vector3f((*cloud)[i].getVector3fMap() - centroid);
    if (n.dot(reference) < 0.f) n = -n;
  }
  // Drop surface points without a usable normal (isolated points).
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr c2(new pcl::PointCloud<pcl::PointXYZ>);
    pcl::PointCloud<pcl::Normal>::Ptr n2(new pcl::PointCloud<pcl::Normal>);
    for (std::size_t i = 0; i < cloud->size(); ++i) {
      const auto n = (*normals)[i].getNormalVector3fMap();
      if (!n.allFinite() || n.squaredNorm() < 0.25f) continue;
      c2->push_back((*cloud)[i]);
      n2->push_back((*normals)[i]);
    }
    cloud = c2;
    normals = n2;
  }
  if (cloud->size() < 3) return;

  pcl::PointCloud<pcl::PointXYZ>::Ptr keypoint_cloud(new pcl::PointCloud<pcl::PointXYZ>);
  keypoint_cloud->reserve(keypoints.size());
  for (const auto& k : keypoints) keypoint_cloud->push_back(pcl::PointXYZ(k.x(), k.y(), k.z()));

  pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
  fpfh.setInputCloud(keypoint_cloud);
  fpfh.setSearchSurface(cloud);
  fpfh.setInputNormals(normals);
  fpfh.setSearchMethod(tree);
  fpfh.setRadiusSearch(options_.support_radius_m);
  pcl::PointCloud<pcl::FPFHSignature33> features;
  fpfh.compute(features);
  for (std::size_t i = 0; i < features.size() && i < keypoints.size(); ++i) {
    const float* h = features[i].histogram;
    bool finite = true;
    for (int b = 0; b < kDimension; ++b) finite = finite && std::isfinite(h[b]);
    if (!finite) continue;
    std::copy(h, h + kDimension, descriptors->begin() + i * kDimension);
  }
}

}  // namespace objscan::recognition
