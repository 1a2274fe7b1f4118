#pragma once
// Category sizes and size-check options for the size rule tests (hand-made, not from a database).
#include "objscan/recognition/category_extent.h"

namespace objscan::scanning::testing {

// Tight bounds (0.8 x the smallest to 1.2 x the largest model) on whole point sets: a sparse piece
// (eight corner points) would be trimmed away in a union.
inline recognition::SizePlausibilityOptions TightSizeOptions() {
  recognition::SizePlausibilityOptions options;
  options.min_ratio = 0.8;
  options.max_ratio = 1.2;
  options.extent_trim_fraction = 0.0;
  return options;
}

// Night stands 0.5 m tall with a 0.6-0.7 m footprint diagonal; beds 0.6 m tall, 2.2-2.6 m.
inline recognition::CategoryExtents NightStandAndBedSizes() {
  recognition::CategoryExtents extents;
  extents.Add(world::Category::kNightStand, {0.5, 0.6});
  extents.Add(world::Category::kNightStand, {0.5, 0.7});
  extents.Add(world::Category::kBed, {0.6, 2.2});
  extents.Add(world::Category::kBed, {0.6, 2.6});
  return extents;
}

}  // namespace objscan::scanning::testing
