#pragma once
// Beyond the paper: when a check takes an object's label at the end of a run (no model of that
// category has its size, or a window label on something not in a wall opening), the object's own
// full-model matches may still name what it is: a monitor the graph cut called shelves, a chair it
// called bed. The replacement must be confident, of another category, and fit the object's size.
#include <optional>

#include "objscan/recognition/category_extent.h"
#include "objscan/segmentation/post_matcher.h"
#include "objscan/world/category.h"

namespace objscan::scanning {

// The match (among `matches`, any order) whose category replaces `taken`: the highest objectness
// among those of another category with objectness >= options.relabel_min_objectness whose extent
// range admits `extent`, windows only when `in_wall_opening`. Null when none qualifies or when
// options.relabel (or options.enabled) is off.
const segmentation::ModelMatch* ReplacementLabel(world::Category taken, const segmentation::MatchResult& matches,
                                                 const recognition::ObjectExtent& extent, bool in_wall_opening,
                                                 const recognition::CategoryExtents& extents,
                                                 const recognition::SizePlausibilityOptions& options);

}  // namespace objscan::scanning
