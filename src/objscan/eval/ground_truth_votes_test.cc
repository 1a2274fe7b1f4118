#include "objscan/eval/ground_truth_votes.h"

#include <gtest/gtest.h>

#include "objscan/mapping/surface_map.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::eval {
namespace {

TEST(GroundTruthVotesTest, MajorityOfVotesNamesTheInstance) {
  GroundTruthVotes votes;
  for (int k = 0; k < 5; ++k) votes.Vote(3, 7);
  for (int k = 0; k < 2; ++k) votes.Vote(3, 9);
  votes.Vote(3, 11);  // a third instance cancels one vote of each slot
  EXPECT_EQ(votes.Instance(3), 7);
  EXPECT_EQ(votes.Instance(0), 0);   // never voted
  EXPECT_EQ(votes.Instance(99), 0);  // beyond what was voted
  const std::vector<std::int32_t> all = votes.Instances(4);
  EXPECT_EQ(all, (std::vector<std::int32_t>{0, 0, 0, 7}));
}

TEST(GroundTruthVotesTest, ObservesFusedPixelsOnly) {
  platform::DepthFrame frame;
  frame.depth_m = {1.f, 1.f, 1.f, 1.f};
  frame.gt_instance = {4, 4, 5, 6};
  mapping::FrameAssociation association;
  association.pixel_element = {0, 0, 1, -1};  // the last pixel was not fused
  GroundTruthVotes votes;
  votes.Observe(frame, association);
  EXPECT_EQ(votes.Instance(0), 4);
  EXPECT_EQ(votes.Instance(1), 5);
  EXPECT_EQ(votes.Instance(2), 0);
  // A frame without ground truth votes nothing.
  frame.gt_instance.clear();
  votes.Observe(frame, association);
  EXPECT_EQ(votes.Instance(1), 5);
}

}  // namespace
}  // namespace objscan::eval
