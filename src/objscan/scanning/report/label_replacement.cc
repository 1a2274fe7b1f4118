#include "objscan/scanning/report/label_replacement.h"

namespace objscan::scanning {

const segmentation::ModelMatch* ReplacementLabel(world::Category taken, const segmentation::MatchResult& matches,
                                                 const recognition::ObjectExtent& extent, bool in_wall_opening,
                                                 const recognition::CategoryExtents& extents,
                                                 const recognition::SizePlausibilityOptions& options) {
  const segmentation::ModelMatch* best = nullptr;
  for (const auto& m : matches.models) {
    if (m.category == taken || m.objectness < options.relabel_min_objectness) continue;
    if (m.category == world::Category::kCurtain) continue;  // the curtain check names those
    if (m.category == world::Category::kWindow && !in_wall_opening) continue;
    if (!recognition::IsPlausibleExtent(extent, extents.Find(m.category), options)) continue;
    if (best == nullptr || m.objectness > best->objectness) best = &m;
  }
  return best;
}

std::optional<world::Category> ModelLabel(const std::optional<world::Category>& graph_cut,
                                          const segmentation::ModelMatch* best, double min_objectness) {
  if (best != nullptr && best->objectness >= min_objectness) return best->category;
  return graph_cut;
}

}  // namespace objscan::scanning
