#pragma once
// A small database of analytic shapes for the recognition tests (no scanning): chair, table (with
// components: top and legs), shelves, sofa, cabinet.
#include <string>
#include <vector>

#include "objscan/common/rng.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition::testing {

using ShapeFn = void (*)(double, std::vector<Eigen::Vector3f>*, std::vector<Eigen::Vector3f>*);

// A shape's surface at 1 cm spacing with 2 mm Gaussian noise, and num_keypoints Lloyd keypoints on
// it (fixed seeds): the input the FPFH test and the FPFH benchmark share.
inline void NoisyShapeWithKeypoints(ShapeFn shape, int num_keypoints, geometry::PointCloud* cloud,
                                    std::vector<Eigen::Vector3f>* keypoints) {
  shape(0.01, &cloud->points, &cloud->normals);
  Rng noise(4);
  for (auto& p : cloud->points) p += Eigen::Vector3f(noise.Normal(0, 0.002), noise.Normal(0, 0.002), noise.Normal(0, 0.002));
  Rng rng(2);
  KeypointOptions options;
  options.num_keypoints = num_keypoints;
  for (int i : SampleKeypointsLloyd(cloud->points, options, &rng)) keypoints->push_back(cloud->points[i]);
}

inline ModelScan ShapeScan(ShapeFn shape, double spacing_m) {
  ModelScan scan;
  shape(spacing_m, &scan.surface.points, &scan.surface.normals);
  scan.surface.labels.assign(scan.surface.size(), 0);
  return scan;
}

// The table with its top (label 1) and legs (labels 2..5) as components, each leg touching the top.
inline ModelScan TableScanWithComponents(double spacing_m) {
  ModelScan scan;
  std::vector<segmentation::Component> comps(5);
  for (int c = 0; c < 5; ++c) comps[c].label = c + 1;
  auto add = [&](int label, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const std::size_t before = scan.surface.points.size();
    BoxSurface(lo, hi, spacing_m, &scan.surface.points, &scan.surface.normals);
    for (std::size_t i = before; i < scan.surface.points.size(); ++i) {
      scan.surface.labels.push_back(label);
      comps[label - 1].points.push_back(scan.surface.points[i]);
      comps[label - 1].normals.push_back(scan.surface.normals[i]);
      comps[label - 1].bounds.Extend(scan.surface.points[i].cast<double>());
    }
  };
  add(1, {-0.6, -0.4, 0.70}, {0.6, 0.4, 0.75});
  int label = 2;
  for (double x : {-0.55, 0.5}) {
    for (double y : {-0.35, 0.3}) add(label++, {x, y, 0.0}, {x + 0.05, y + 0.05, 0.70});
  }
  std::vector<std::vector<std::int32_t>> neighbors = {{2, 3, 4, 5}, {1}, {1}, {1}, {1}};
  scan.components.Assign(std::move(comps), std::move(neighbors));
  return scan;
}

inline DatabaseBuildOptions SmallDatabaseOptions() {
  DatabaseBuildOptions options;
  options.vocabulary.num_words = 48;
  options.vocabulary.max_training_descriptors = 3000;
  options.threads = 1;
  options.min_entry_points = 20;
  return options;
}

inline std::vector<ScannedModel> ShapeModels(double spacing_m) {
  std::vector<ScannedModel> models;
  auto add = [&](world::Category c, const std::string& name, ModelScan scan) {
    ScannedModel m;
    m.category = c;
    m.name = name;
    m.source = "test/" + name;
    m.scan = std::move(scan);
    models.push_back(std::move(m));
  };
  add(world::Category::kChair, "chair/a", ShapeScan(&ChairLike, spacing_m));
  add(world::Category::kTable, "table/a", TableScanWithComponents(spacing_m));
  add(world::Category::kShelves, "shelves/a", ShapeScan(&ShelfLike, spacing_m));
  add(world::Category::kSofa, "sofa/a", ShapeScan(&SofaLike, spacing_m));
  add(world::Category::kCabinet, "cabinet/a", ShapeScan(&CabinetLike, spacing_m));
  return models;
}

}  // namespace objscan::recognition::testing
