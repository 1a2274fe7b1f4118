#include "objscan/segmentation/component_graph.h"

#include <algorithm>

namespace objscan::segmentation {

int ComponentGraph::IndexOf(std::int32_t label) const {
  auto it = std::lower_bound(components_.begin(), components_.end(), label,
                             [](const Component& c, std::int32_t l) { return c.label < l; });
  if (it == components_.end() || it->label != label) return -1;
  return static_cast<int>(it - components_.begin());
}

const Component* ComponentGraph::Find(std::int32_t label) const {
  const int i = IndexOf(label);
  return i < 0 ? nullptr : &components_[i];
}

const std::vector<std::int32_t>& ComponentGraph::Neighbors(std::int32_t label) const {
  static const std::vector<std::int32_t> kNone;
  const int i = IndexOf(label);
  return i < 0 ? kNone : neighbors_[i];
}

bool ComponentGraph::Adjacent(std::int32_t a, std::int32_t b) const {
  const std::vector<std::int32_t>& n = Neighbors(a);
  return std::binary_search(n.begin(), n.end(), b);
}

std::vector<std::pair<std::int32_t, std::int32_t>> ComponentGraph::Edges() const {
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  for (std::size_t i = 0; i < components_.size(); ++i) {
    for (std::int32_t b : neighbors_[i]) {
      if (components_[i].label < b) edges.emplace_back(components_[i].label, b);
    }
  }
  return edges;
}

void ComponentGraph::Assign(std::vector<Component> components, std::vector<std::vector<std::int32_t>> neighbors) {
  components_ = std::move(components);
  neighbors_ = std::move(neighbors);
  neighbors_.resize(components_.size());
  for (auto& n : neighbors_) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
}

}  // namespace objscan::segmentation
