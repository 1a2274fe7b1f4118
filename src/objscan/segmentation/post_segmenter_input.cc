// PostSegmenterInput::FromGraph lives apart from post_segmenter.cc so that the post-segmenter links
// without the component graph's implementation (unit tests feed PostSegmenterInput directly).
#include "objscan/segmentation/component_graph.h"
#include "objscan/segmentation/post_segmenter.h"

namespace objscan::segmentation {

PostSegmenterInput PostSegmenterInput::FromGraph(const ComponentGraph& graph) {
  PostSegmenterInput input;
  input.components.reserve(graph.size());
  for (const segmentation::Component& c : graph.components()) {
    input.components.push_back({c.label, c.revision, c.points.size()});
  }
  input.edges = graph.Edges();
  return input;
}

}  // namespace objscan::segmentation
