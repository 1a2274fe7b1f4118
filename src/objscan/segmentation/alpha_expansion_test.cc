#include "objscan/segmentation/alpha_expansion.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"

namespace objscan::segmentation {
namespace {

// Global minimum by enumerating every labeling.
double BruteForceMinimum(const PottsEnergy& energy, std::vector<int>* best_labels) {
  const int n = energy.num_nodes();
  const int k = energy.num_labels();
  std::vector<int> labels(static_cast<std::size_t>(n), 0);
  double best = std::numeric_limits<double>::infinity();
  while (true) {
    const double e = energy.Evaluate(labels);
    if (e < best) {
      best = e;
      if (best_labels != nullptr) *best_labels = labels;
    }
    int i = 0;
    while (i < n && ++labels[static_cast<std::size_t>(i)] == k) labels[static_cast<std::size_t>(i++)] = 0;
    if (i == n) break;
  }
  return best;
}

// Lowest energy reachable from `labels` by one expansion move, by enumerating every subset of nodes
// that switches to each alpha.
double BestExpansionMove(const PottsEnergy& energy, const std::vector<int>& labels) {
  const int n = energy.num_nodes();
  double best = energy.Evaluate(labels);
  std::vector<int> moved(labels.size());
  for (int alpha = 0; alpha < energy.num_labels(); ++alpha) {
    for (unsigned mask = 0; mask < (1u << n); ++mask) {
      for (int p = 0; p < n; ++p) {
        moved[static_cast<std::size_t>(p)] = (mask >> p) & 1u ? alpha : labels[static_cast<std::size_t>(p)];
      }
      best = std::min(best, energy.Evaluate(moved));
    }
  }
  return best;
}

PottsEnergy RandomEnergy(Rng& rng, int num_nodes, int num_labels, double edge_probability) {
  PottsEnergy energy(num_nodes, num_labels);
  for (int p = 0; p < num_nodes; ++p) {
    for (int l = 0; l < num_labels; ++l) energy.SetDataCost(p, l, rng.Uniform01());
  }
  for (int a = 0; a < num_nodes; ++a) {
    for (int b = a + 1; b < num_nodes; ++b) {
      if (rng.Uniform01() < edge_probability) {
        // Some exact zeros, otherwise weights comparable to the data costs so that moves matter.
        const double w = rng.Uniform01() < 0.1 ? 0.0 : rng.Uniform(0.0, 1.2);
        energy.AddEdge(a, b, w);
      }
    }
  }
  return energy;
}

TEST(AlphaExpansionTest, MatchesBruteForceOnRandomGraphsAndNeverExceedsTwiceTheMinimum) {
  Rng rng(20180601);
  int trials = 0;
  int optimal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = rng.UniformInt(1, 8);
    const int k = rng.UniformInt(2, 4);
    const PottsEnergy energy = RandomEnergy(rng, n, k, rng.Uniform(0.2, 0.9));
    const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
    ASSERT_EQ(result.status, AlphaExpansionStatus::kConverged);
    ASSERT_EQ(result.labels.size(), static_cast<std::size_t>(n));
    // The reported energy is the energy of the returned labels.
    EXPECT_NEAR(result.energy, energy.Evaluate(result.labels), 1e-12);
    const double minimum = BruteForceMinimum(energy, nullptr);
    // The expansion bound for Potts terms with non-negative data costs.
    EXPECT_LE(result.energy, 2.0 * minimum + 1e-9) << "trial " << trial;
    EXPECT_GE(result.energy, minimum - 1e-12);
    // Converged means no expansion move improves: this checks every max-flow cut was optimal.
    EXPECT_GE(BestExpansionMove(energy, result.labels), result.energy - 1e-9) << "trial " << trial;
    ++trials;
    if (result.energy <= minimum + 1e-9) ++optimal;
  }
  const double fraction = static_cast<double>(optimal) / trials;
  RecordProperty("optimal_fraction", std::to_string(fraction));
  std::printf("alpha-expansion reached the brute-force minimum in %d of %d random graphs\n", optimal, trials);
  EXPECT_GE(fraction, 0.9) << optimal << " of " << trials << " reached the global minimum";
}

TEST(AlphaExpansionTest, LargerRandomGraphsReachLocalMinimumOfExpansionMoves) {
  Rng rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    const PottsEnergy energy = RandomEnergy(rng, 12, 5, 0.3);
    const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
    ASSERT_EQ(result.status, AlphaExpansionStatus::kConverged);
    EXPECT_GE(BestExpansionMove(energy, result.labels), result.energy - 1e-9);
  }
}

TEST(AlphaExpansionTest, EmptyGraph) {
  const PottsEnergy energy(0, 3);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.status, AlphaExpansionStatus::kEmpty);
  EXPECT_TRUE(result.labels.empty());
  EXPECT_EQ(result.energy, 0.0);
}

TEST(AlphaExpansionTest, SingleNodeTakesCheapestLabel) {
  PottsEnergy energy(1, 3);
  energy.SetDataCost(0, 0, 0.7);
  energy.SetDataCost(0, 1, 0.2);
  energy.SetDataCost(0, 2, 0.5);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.status, AlphaExpansionStatus::kConverged);
  ASSERT_EQ(result.labels.size(), 1u);
  EXPECT_EQ(result.labels[0], 1);
  EXPECT_DOUBLE_EQ(result.energy, 0.2);
}

TEST(AlphaExpansionTest, SingleLabel) {
  PottsEnergy energy(3, 1);
  energy.SetDataCost(1, 0, 0.4);
  energy.AddEdge(0, 1, 1.0);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.labels, (std::vector<int>{0, 0, 0}));
  EXPECT_DOUBLE_EQ(result.energy, 0.4);
}

TEST(AlphaExpansionTest, ZeroWeightsGivePerNodeMinimum) {
  PottsEnergy energy(3, 2);
  energy.SetDataCost(0, 0, 0.0);
  energy.SetDataCost(0, 1, 1.0);
  energy.SetDataCost(1, 0, 1.0);
  energy.SetDataCost(1, 1, 0.0);
  energy.SetDataCost(2, 0, 0.0);
  energy.SetDataCost(2, 1, 1.0);
  energy.AddEdge(0, 1, 0.0);
  energy.AddEdge(1, 2, 0.0);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.labels, (std::vector<int>{0, 1, 0}));
  EXPECT_DOUBLE_EQ(result.energy, 0.0);
}

TEST(AlphaExpansionTest, StrongEdgesPullAWeakNodeOver) {
  // A chain a-b-c: a and c prefer label 0 strongly, b prefers label 1 weakly; cutting both edges
  // costs 2 * 0.5 = 1.0 > the 0.3 data penalty of relabeling b.
  PottsEnergy energy(3, 2);
  energy.SetDataCost(0, 1, 2.0);
  energy.SetDataCost(1, 0, 0.3);
  energy.SetDataCost(2, 1, 2.0);
  energy.AddEdge(0, 1, 0.5);
  energy.AddEdge(1, 2, 0.5);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.labels, (std::vector<int>{0, 0, 0}));
  EXPECT_DOUBLE_EQ(result.energy, 0.3);
}

TEST(AlphaExpansionTest, DisconnectedComponentsAreSolvedIndependently) {
  // Two separate pairs; in each, the node with the weak preference follows its partner.
  PottsEnergy energy(4, 3);
  for (int p = 0; p < 4; ++p) {
    for (int l = 0; l < 3; ++l) energy.SetDataCost(p, l, 1.0);
  }
  energy.SetDataCost(0, 2, 0.0);  // strong: 2
  energy.SetDataCost(1, 1, 0.8);  // weak: 1
  energy.SetDataCost(2, 0, 0.0);  // strong: 0
  energy.SetDataCost(3, 1, 0.9);  // weak: 1
  energy.AddEdge(0, 1, 0.5);
  energy.AddEdge(2, 3, 0.5);
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(result.labels, (std::vector<int>{2, 2, 0, 0}));
  EXPECT_DOUBLE_EQ(result.energy, 2.0);
  std::vector<int> brute;
  EXPECT_DOUBLE_EQ(BruteForceMinimum(energy, &brute), 2.0);
}

TEST(AlphaExpansionTest, DeterministicAndRespectsInitialLabels) {
  Rng rng(3);
  const PottsEnergy energy = RandomEnergy(rng, 8, 4, 0.5);
  const AlphaExpansionResult a = MinimizeByAlphaExpansion(energy);
  const AlphaExpansionResult b = MinimizeByAlphaExpansion(energy);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.energy, b.energy);
  // Starting from the optimum stays there.
  std::vector<int> optimum;
  const double minimum = BruteForceMinimum(energy, &optimum);
  const AlphaExpansionResult c = MinimizeByAlphaExpansion(energy, {}, &optimum);
  EXPECT_NEAR(c.energy, minimum, 1e-12);
  EXPECT_EQ(c.accepted_moves, 0);
}

TEST(AlphaExpansionTest, MaxSweepsStopsEarly) {
  Rng rng(11);
  const PottsEnergy energy = RandomEnergy(rng, 8, 4, 0.8);
  std::vector<int> start(8, 0);
  for (int p = 0; p < 8; ++p) start[static_cast<std::size_t>(p)] = p % 4;  // far from optimal
  AlphaExpansionOptions options;
  options.max_sweeps = 1;
  const AlphaExpansionResult result = MinimizeByAlphaExpansion(energy, options, &start);
  EXPECT_EQ(result.sweeps, 1);
  EXPECT_LE(result.energy, energy.Evaluate(start));
}

TEST(AlphaExpansionTest, RejectsBadInput) {
  EXPECT_THROW(PottsEnergy(2, 0), InputError);
  PottsEnergy energy(2, 2);
  EXPECT_THROW(energy.AddEdge(0, 0, 1.0), InputError);
  EXPECT_THROW(energy.AddEdge(0, 2, 1.0), InputError);
  EXPECT_THROW(energy.AddEdge(0, 1, -0.1), InputError);
  EXPECT_THROW(energy.SetDataCost(0, 2, 1.0), InputError);
  EXPECT_THROW(energy.SetDataCost(0, 1, std::numeric_limits<double>::infinity()), InputError);
  const std::vector<int> wrong_size{0};
  EXPECT_THROW(MinimizeByAlphaExpansion(energy, {}, &wrong_size), InputError);
  AlphaExpansionOptions options;
  options.max_sweeps = 0;
  EXPECT_THROW(options.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::segmentation
