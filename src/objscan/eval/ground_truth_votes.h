#pragma once
// Evaluation only: the ground-truth instance of each surface-map element, as the majority of the
// simulator's per-pixel instance ids of the pixels fused into it. Fed from the scanner's frame
// observer (the frame and where the map fused each pixel), so the method itself never reads ground
// truth. Map elements are only ever appended during a run, so element indices stay valid.
#include <cstdint>
#include <vector>

namespace objscan::sim {
struct DepthFrame;
}  // namespace objscan::sim
namespace objscan::mapping {
struct FrameAssociation;
}  // namespace objscan::mapping

namespace objscan::eval {

class GroundTruthVotes {
 public:
  // Votes every fused pixel's instance for its element, in pixel order (row-major). A frame without
  // a ground-truth channel votes nothing.
  void Observe(const sim::DepthFrame& frame, const mapping::FrameAssociation& association);
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

}  // namespace objscan::eval
