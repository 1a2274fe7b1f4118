#pragma once
// Evaluation only: the ground-truth instance of each surface-map element, as the majority of the
// simulator's per-pixel instance ids of the pixels fused into it. Fed from the scanner's frame
// observer (the frame and where the map fused each pixel), so the method itself never reads ground
// truth. Map elements are only ever appended during a run, so element indices stay valid.
// Header-only: the mapping and segmentation tests use it without linking evaluation (and with it
// recognition's PCL).
#include <cstdint>
#include <vector>

#include "objscan/mapping/surface_map.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::eval {

class GroundTruthVotes {
 public:
  // Votes every fused pixel's instance for its element, in pixel order (row-major). A frame without
  // a ground-truth channel votes nothing.
  void Observe(const platform::DepthFrame& frame, const mapping::FrameAssociation& association);
  // One vote (for tests and other feeders).
  void Vote(std::size_t element, std::int32_t instance);

  // The majority instance of element i (0 = none or never voted).
  std::int32_t Instance(std::size_t element) const;
  // Instance() of elements 0 .. num_elements-1.
  std::vector<std::int32_t> Instances(std::size_t num_elements) const;

 private:
  // Two-slot majority vote (Misra-Gries): enough to name the majority.
  std::vector<std::int32_t> id_;      // 2 per element
  std::vector<std::uint16_t> count_;  // 2 per element
};

inline void GroundTruthVotes::Observe(const platform::DepthFrame& frame, const mapping::FrameAssociation& association) {
  if (frame.gt_instance.size() != frame.depth_m.size() ||
      association.pixel_element.size() != frame.gt_instance.size()) {
    return;
  }
  for (std::size_t i = 0; i < association.pixel_element.size(); ++i) {
    const std::int32_t e = association.pixel_element[i];
    if (e >= 0) Vote(static_cast<std::size_t>(e), frame.gt_instance[i]);
  }
}

inline void GroundTruthVotes::Vote(std::size_t element, std::int32_t instance) {
  if (2 * element + 1 >= id_.size()) {
    id_.resize(2 * element + 2, 0);
    count_.resize(2 * element + 2, 0);
  }
  std::int32_t* id = &id_[2 * element];
  std::uint16_t* count = &count_[2 * element];
  for (int k = 0; k < 2; ++k) {
    if (id[k] == instance && count[k] > 0) {
      if (count[k] < 65535) ++count[k];
      return;
    }
  }
  for (int k = 0; k < 2; ++k) {
    if (count[k] == 0) {
      id[k] = instance;
      count[k] = 1;
      return;
    }
  }
  --count[0];
  --count[1];
}

inline std::int32_t GroundTruthVotes::Instance(std::size_t element) const {
  if (2 * element + 1 >= id_.size()) return 0;
  const std::uint16_t c0 = count_[2 * element], c1 = count_[2 * element + 1];
  if (c0 == 0 && c1 == 0) return 0;
  return c0 >= c1 ? id_[2 * element] : id_[2 * element + 1];
}

inline std::vector<std::int32_t> GroundTruthVotes::Instances(std::size_t num_elements) const {
  std::vector<std::int32_t> out(num_elements);
  for (std::size_t i = 0; i < num_elements; ++i) out[i] = Instance(i);
  return out;
}

}  // namespace objscan::eval
