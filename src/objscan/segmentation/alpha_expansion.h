#pragma once
// Multi-label energy minimization by alpha-expansion (Boykov, Veksler, Zabih 2001) for energies
//
//   E(L) = sum_c D_c(l_c) + sum_(c,d) w_cd [l_c != l_d],     w_cd >= 0,
//
// the form of the paper's eq. (2)-(4). Each expansion move is a binary problem solved exactly by
// Boykov-Kolmogorov max-flow; for this Potts pairwise term the local minimum reached is within a
// factor 2 of the global minimum (for non-negative data costs).
#include <cstddef>
#include <vector>

namespace objscan::segmentation {

// The energy: dense data costs (node-major flat array) and weighted Potts edges.
class PottsEnergy {
 public:
  struct Edge {
    int a = 0;
    int b = 0;
    double weight = 0.0;
  };

  // All data costs start at 0. Throws InputError for negative sizes or zero labels.
  PottsEnergy(int num_nodes, int num_labels);

  // Throws InputError on an index out of range or a non-finite cost.
  void SetDataCost(int node, int label, double cost);
  double DataCost(int node, int label) const { return data_cost_[Index(node, label)]; }
  // Adds w [l_a != l_b]. Parallel edges add up. Throws InputError on a bad index, a self-loop or a
  // negative/non-finite weight.
  void AddEdge(int a, int b, double weight);

  int num_nodes() const { return num_nodes_; }
  int num_labels() const { return num_labels_; }
  const std::vector<Edge>& edges() const { return edges_; }

  // E(labels); labels.size() must equal num_nodes() (throws InputError otherwise).
  double Evaluate(const std::vector<int>& labels) const;

 private:
  std::size_t Index(int node, int label) const {
    return static_cast<std::size_t>(node) * static_cast<std::size_t>(num_labels_) +
           static_cast<std::size_t>(label);
  }

  int num_nodes_ = 0;
  int num_labels_ = 0;
  std::vector<double> data_cost_;
  std::vector<Edge> edges_;
};

struct AlphaExpansionOptions {
  // A sweep tries every label once as alpha; stop after this many sweeps even if still improving.
  int max_sweeps = 20;
  // A move is accepted only when it lowers the energy by more than this (guards against
  // floating-point cycling).
  double min_improvement = 1e-9;

  template <class V>
  void Visit(V& v) {
    v("max_sweeps", max_sweeps);
    v("min_improvement", min_improvement);
  }
  void Validate() const;
};

enum class AlphaExpansionStatus {
  kConverged,        // a full sweep found no improving expansion move
  kMaxSweepsReached, // still improving when max_sweeps ran out (labels are valid, energy lower)
  kEmpty,            // no nodes
};

struct AlphaExpansionResult {
  std::vector<int> labels;
  double energy = 0.0;
  int sweeps = 0;
  int accepted_moves = 0;
  AlphaExpansionStatus status = AlphaExpansionStatus::kEmpty;
};

// Minimizes `energy` by alpha-expansion. Starts from `initial_labels` when given (size must match),
// else from the per-node data-cost minimum (lowest label on ties). Labels are tried in increasing
// order in every sweep, so the result is deterministic.
AlphaExpansionResult MinimizeByAlphaExpansion(const PottsEnergy& energy,
                                              const AlphaExpansionOptions& options = {},
                                              const std::vector<int>* initial_labels = nullptr);

}  // namespace objscan::segmentation
