#pragma once
// ScanNet scans (http://www.scan-net.org, v2 layout) as objscan scenes.
//
// A scan folder scene<space>_<scan>/ holds (ID = the folder name):
//   ID_vh_clean_2.ply                      the mesh the robot scans (binary PLY, per-vertex colours)
//   ID.aggregation.json                    {"segGroups": [{"objectId", "label", "segments": [...]}, ...]}
//   ID_vh_clean_2.0.010000.segs.json       {"segIndices": [segment id per mesh vertex]}
//   ID_vh_clean_2.labels.ply               the same mesh with a per-vertex NYU40 `label` (0 = none)
//   ID.txt                                 "axisAlignment = m00 m01 ... m33" (row-major 4x4)
// Ground truth comes from the aggregation + segments when both are present (instances are the
// segment groups, labelled with their raw category), else from labels.ply: the instances are then
// inferred, the pieces of one label grouped by proximity (scannet_instances.h), labelled with the
// NYU40 class name, and Scene::instances_inferred() says so. Categories come from the
// category map's `label` rules (config/categories/scannet.yaml). Each triangle belongs to the
// instance most of its vertices belong to; triangles of no instance form one `other` object named
// "unannotated" (still scanned, as the sensor sees them).
//
// Levelling: the mesh is moved by axisAlignment when the .txt has it, else rotated so that the plane
// fitted to the floor-labelled vertices is horizontal; then shifted so that the floor is at z = 0
// (the lowest vertex when nothing is labelled floor). The scan's own floor is the floor object (its
// holes stay holes: the robot only drives where the scan has floor).
#include <string>

#include "objscan/io/category_map.h"
#include "objscan/io/scene_spec.h"
#include "objscan/world/scene.h"

namespace objscan::io {

// True when `spec` is a folder holding a *_vh_clean_2.ply or is such a file.
bool IsScanNetSpec(const std::string& spec);

// Throws InputError with one line naming the file on a missing, malformed or inconsistent file.
world::Scene LoadScanNetScan(const std::string& spec, const SceneLoadOptions& options, const CategoryMap& categories);

// NYU40 class name of a label id (1..40), "" for 0 or an unknown id.
std::string Nyu40ClassName(int label);

}  // namespace objscan::io
