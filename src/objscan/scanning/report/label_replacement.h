#pragma once
// Beyond the paper: when a check takes an object's label at the end of a run (no model of that
// category has its size, or a window label on something not in a wall opening), the object's own
// full-model matches may still name what it is: a monitor the graph cut called shelves, a chair it
// called bed. The replacement must be confident, of another category, and fit the object's size.
#include <optional>
#include <vector>

#include "objscan/recognition/category_extent.h"
#include "objscan/scanning/run_record.h"
#include "objscan/segmentation/post_matcher.h"
#include "objscan/world/category.h"

namespace objscan::scanning {

// The match (among `matches`, any order) whose category replaces `taken`: the highest objectness
// among those of another category with objectness >= options.relabel_min_objectness whose extent
// range admits `extent`, windows only when `in_wall_opening`, never a curtain: a curtain hangs over a
// window, and the scanner's curtain check names those (one that hangs over none is a guess). Null
// when none qualifies.
const segmentation::ModelMatch* ReplacementLabel(world::Category taken, const segmentation::MatchResult& matches,
                                                 const recognition::ObjectExtent& extent, bool in_wall_opening,
                                                 const recognition::CategoryExtents& extents,
                                                 const recognition::SizePlausibilityOptions& options);

// The label an unfinished object is reported with (report.model_label_min_objectness, report rule model_label): its best
// full model's category when that model's objectness reaches `min_objectness`, else the graph-cut
// label (nullopt: "none"). The graph cut votes with the components' matches, which include parts and
// views of models (a monitor's screen matches a shelf board); the best full model is fitted to the
// whole object. `best` may be null (no full model matched).
std::optional<world::Category> ModelLabel(const std::optional<world::Category>& graph_cut,
                                          const segmentation::ModelMatch* best, double min_objectness);


}  // namespace objscan::scanning
