#pragma once
// Virtual scanning of a single model (database building and evaluation): the model alone in an
// empty scene, rendered by render::DepthCamera from views around it, fused into a mapping::SurfaceMap
// and pre-segmented by the live system's segmentation::IncrementalSegmenter.
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/rng.h"
#include "objscan/geometry/mesh.h"
#include "objscan/geometry/point_cloud.h"
#include "objscan/geometry/pose.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/segmentation/component_graph.h"
#include "objscan/segmentation/incremental_segmenter.h"
#include "objscan/render/depth_camera.h"

namespace objscan::recognition {

struct VirtualScanOptions {
  // Views: rings around the model's bounding box centre at these elevations (deg above horizontal),
  // each with the matching number of evenly spaced azimuths (the first ring starts at azimuth 0).
  std::vector<double> ring_elevations_deg = {10.0, 35.0, 65.0};
  std::vector<double> ring_views = {8.0, 8.0, 4.0};
  // Camera distance: the model's bounding-box diagonal times this plus the margin, so the model fits
  // the vertical field of view; clamped into the sensor's range.
  double distance_per_diagonal = 1.15;
  double distance_margin_m = 0.4;
  render::SensorOptions sensor;  // the live sensor; `noise` is overridden per use (see below)
  mapping::SurfaceMapOptions map;
  // Clean model scans: adjacent pairs only where parts touch (2-voxel cells), so the database does not
  // change with the live system's adjacency. With its 3-voxel cells here too, 15 procedural rooms
  // gave recall 53.1% / precision 54.7% (one room stuck) against 52.3% / 54.2% (all done): no clear
  // difference.
  segmentation::IncrementalSegmenterOptions segmenter = TouchingAdjacency();

  static segmentation::IncrementalSegmenterOptions TouchingAdjacency() {
    segmentation::IncrementalSegmenterOptions options;
    options.adjacency_cell_voxels = 2;
    return options;
  }

  template <class V>
  void Visit(V& v) {
    v("ring_elevations_deg", ring_elevations_deg);
    v("ring_views", ring_views);
    v("distance_per_diagonal", distance_per_diagonal);
    v("distance_margin_m", distance_margin_m);
    v("sensor", sensor);
    v("map", map);
    v("segmenter", segmenter);
  }
  void Validate() const;
};

// Camera distance for a model with this bounding box.
double ViewDistance(const geometry::Aabb3& bounds, const VirtualScanOptions& options);
// The ring views around a bounding box (optical frame poses looking at its centre).
std::vector<geometry::Pose3> RingViews(const geometry::Aabb3& bounds, const VirtualScanOptions& options);
// One view from an azimuth and elevation (radians) at the standard distance.
geometry::Pose3 ViewFrom(const geometry::Aabb3& bounds, double azimuth_rad, double elevation_rad,
                         const VirtualScanOptions& options);

struct ModelScan {
  geometry::PointCloud surface;       // every fused element: points, normals, labels (0 = none)
  segmentation::ComponentGraph components;  // pre-segmented components and adjacency
};

// Renders the mesh (object frame = world frame) from each view, fuses and pre-segments.
// `noise` turns the sensor noise on (drawn from `rng`, which may be nullptr when off).
ModelScan ScanModel(const geometry::TriangleMesh& mesh, const std::vector<geometry::Pose3>& views,
                    const VirtualScanOptions& options, bool noise, Rng* rng);

// Renders the mesh from each view and fuses the frames (ScanModel without pre-segmentation): the
// surface a live scan of the model alone would hold. Same `rng` state, same cloud.
geometry::PointCloud ScanSurface(const geometry::TriangleMesh& mesh, const std::vector<geometry::Pose3>& views,
                                 const VirtualScanOptions& options, bool noise, Rng* rng);

// Half of a view: the points (and normals, when every point has one) on one side of a vertical
// plane through their centroid, the plane's direction drawn from `rng`. An empty cloud draws nothing.
geometry::PointCloud HalfOf(const geometry::PointCloud& cloud, Rng* rng);

// Brings a mesh into the database frame: centred on the origin in XY and standing on z = 0. A mesh
// whose size is implausible in metres (ModelNet-style arbitrary units: bounding-box diagonal above
// 20 m or below 5 cm) is scaled so its height is `typical_height_m`.
geometry::TriangleMesh NormalizeModel(const geometry::TriangleMesh& mesh, double typical_height_m);
// A typical height (m) per category, used only by NormalizeModel for unit-less meshes.
double TypicalHeight(world::Category category);

}  // namespace objscan::recognition
