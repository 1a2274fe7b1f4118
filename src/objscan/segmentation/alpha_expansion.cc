#include "objscan/segmentation/alpha_expansion.h"

// Boost.Graph's edge iterator trips GCC's -Wmaybe-uninitialized inside the library headers (a known
// false positive of boost::optional); silence it for those headers only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/property_map/property_map.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cmath>
#include <string>

#include "objscan/common/config.h"
#include "objscan/common/error.h"

namespace objscan::segmentation {

PottsEnergy::PottsEnergy(int num_nodes, int num_labels) : num_nodes_(num_nodes), num_labels_(num_labels) {
  if (num_nodes < 0) throw InputError("PottsEnergy: num_nodes must be >= 0 (got " + std::to_string(num_nodes) + ")");
  if (num_labels < 1) {
    throw InputError("PottsEnergy: num_labels must be >= 1 (got " + std::to_string(num_labels) + ")");
  }
  data_cost_.assign(static_cast<std::size_t>(num_nodes) * static_cast<std::size_t>(num_labels), 0.0);
}

void PottsEnergy::SetDataCost(int node, int label, double cost) {
  if (node < 0 || node >= num_nodes_ || label < 0 || label >= num_labels_) {
    throw InputError("PottsEnergy: data cost index (" + std::to_string(node) + ", " + std::to_string(label) +
                     ") out of range");
  }
  if (!std::isfinite(cost)) throw InputError("PottsEnergy: data cost must be finite");
  data_cost_[Index(node, label)] = cost;
}

void PottsEnergy::AddEdge(int a, int b, double weight) {
  if (a < 0 || a >= num_nodes_ || b < 0 || b >= num_nodes_) {
    throw InputError("PottsEnergy: edge (" + std::to_string(a) + ", " + std::to_string(b) + ") out of range");
  }
  if (a == b) throw InputError("PottsEnergy: self-loop edge at node " + std::to_string(a));
  if (!std::isfinite(weight) || weight < 0.0) {
    throw InputError("PottsEnergy: edge weight must be finite and >= 0 (got " + std::to_string(weight) + ")");
  }
  edges_.push_back({a, b, weight});
}

double PottsEnergy::Evaluate(const std::vector<int>& labels) const {
  if (labels.size() != static_cast<std::size_t>(num_nodes_)) {
    throw InputError("PottsEnergy: labeling has " + std::to_string(labels.size()) + " entries, expected " +
                     std::to_string(num_nodes_));
  }
  double e = 0.0;
  for (int n = 0; n < num_nodes_; ++n) {
    const int l = labels[static_cast<std::size_t>(n)];
    if (l < 0 || l >= num_labels_) throw InputError("PottsEnergy: label out of range at node " + std::to_string(n));
    e += data_cost_[Index(n, l)];
  }
  for (const Edge& edge : edges_) {
    if (labels[static_cast<std::size_t>(edge.a)] != labels[static_cast<std::size_t>(edge.b)]) e += edge.weight;
  }
  return e;
}

void AlphaExpansionOptions::Validate() const {
  config::Require(max_sweeps >= 1, "max_sweeps", "must be >= 1");
  config::RequireNonNegative("min_improvement", min_improvement);
}

namespace {

using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS, boost::no_property,
                                    boost::property<boost::edge_index_t, std::size_t>>;
using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
using EdgeDesc = boost::graph_traits<Graph>::edge_descriptor;

// The s-t graph of an expansion move. Its topology depends only on the energy's graph, so it is built
// once and only capacities change between moves. Binary variable x_p: 0 (source side) keeps the
// current label, 1 (sink side) switches to alpha. Cutting s->p costs E_p(1), p->t costs E_p(0);
// a pairwise term with table A=E(0,0), B=E(0,1), C=E(1,0), D=E(1,1) becomes
// A + (C-A) x_p + (D-C) x_q + (B+C-A-D) (1-x_p) x_q, the last part an arc p->q (Kolmogorov-Zabih).
class ExpansionGraph {
 public:
  explicit ExpansionGraph(const PottsEnergy& energy)
      : energy_(energy), graph_(static_cast<std::size_t>(energy.num_nodes()) + 2) {
    const int n = energy.num_nodes();
    source_ = static_cast<Vertex>(n);
    sink_ = static_cast<Vertex>(n + 1);
    terminal_.resize(static_cast<std::size_t>(n));
    for (int p = 0; p < n; ++p) {
      terminal_[static_cast<std::size_t>(p)].from_source = AddArcPair(source_, static_cast<Vertex>(p));
      terminal_[static_cast<std::size_t>(p)].to_sink = AddArcPair(static_cast<Vertex>(p), sink_);
    }
    for (const PottsEnergy::Edge& e : energy.edges()) {
      pair_arcs_.push_back(AddArcPair(static_cast<Vertex>(e.a), static_cast<Vertex>(e.b)));
    }
    residual_.resize(capacity_.size());
    color_.resize(boost::num_vertices(graph_));
  }

  // Solves the expansion move of `alpha` from `labels`; writes the moved labeling to *out.
  void Solve(const std::vector<int>& labels, int alpha, std::vector<int>* out) {
    const int n = energy_.num_nodes();
    // Unary cost of x_p = 1 minus cost of x_p = 0, accumulated from data and pairwise terms.
    delta_.assign(static_cast<std::size_t>(n), 0.0);
    std::fill(capacity_.begin(), capacity_.end(), 0.0);
    for (int p = 0; p < n; ++p) {
      delta_[static_cast<std::size_t>(p)] =
          energy_.DataCost(p, alpha) - energy_.DataCost(p, labels[static_cast<std::size_t>(p)]);
    }
    const auto& edges = energy_.edges();
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const PottsEnergy::Edge& e = edges[i];
      const int lp = labels[static_cast<std::size_t>(e.a)];
      const int lq = labels[static_cast<std::size_t>(e.b)];
      const double a = lp != lq ? e.weight : 0.0;
      const double b = lp != alpha ? e.weight : 0.0;
      const double c = alpha != lq ? e.weight : 0.0;
      // d = 0: both take alpha.
      delta_[static_cast<std::size_t>(e.a)] += c - a;
      delta_[static_cast<std::size_t>(e.b)] += -c;
      // b + c - a >= 0 holds because the Potts term is a metric (triangle inequality).
      capacity_[pair_arcs_[i]] = std::max(0.0, b + c - a);
    }
    for (int p = 0; p < n; ++p) {
      const double d = delta_[static_cast<std::size_t>(p)];
      const Terminal& t = terminal_[static_cast<std::size_t>(p)];
      if (d > 0.0) {
        capacity_[t.from_source] = d;
      } else {
        capacity_[t.to_sink] = -d;
      }
    }
    residual_ = capacity_;
    const auto edge_index = boost::get(boost::edge_index, graph_);
    const auto vertex_index = boost::get(boost::vertex_index, graph_);
    boost::boykov_kolmogorov_max_flow(
        graph_, boost::make_iterator_property_map(capacity_.begin(), edge_index),
        boost::make_iterator_property_map(residual_.begin(), edge_index),
        boost::make_iterator_property_map(reverse_.begin(), edge_index),
        boost::make_iterator_property_map(color_.begin(), vertex_index), vertex_index, source_, sink_);
    // Black = source tree = the nodes reachable from s in the residual graph: x_p = 0 (keep).
    out->resize(static_cast<std::size_t>(n));
    const auto black = boost::color_traits<boost::default_color_type>::black();
    for (int p = 0; p < n; ++p) {
      (*out)[static_cast<std::size_t>(p)] =
          color_[static_cast<std::size_t>(p)] == black ? labels[static_cast<std::size_t>(p)] : alpha;
    }
  }

 private:
  struct Terminal {
    std::size_t from_source = 0;
    std::size_t to_sink = 0;
  };

  // Adds u->v and its reverse v->u; returns the index of u->v.
  std::size_t AddArcPair(Vertex u, Vertex v) {
    const std::size_t forward = capacity_.size();
    const EdgeDesc e1 = boost::add_edge(u, v, forward, graph_).first;
    const EdgeDesc e2 = boost::add_edge(v, u, forward + 1, graph_).first;
    capacity_.push_back(0.0);
    capacity_.push_back(0.0);
    reverse_.push_back(e2);
    reverse_.push_back(e1);
    return forward;
  }

  const PottsEnergy& energy_;
  Graph graph_;
  Vertex source_ = 0;
  Vertex sink_ = 0;
  std::vector<Terminal> terminal_;
  std::vector<std::size_t> pair_arcs_;
  std::vector<double> capacity_;
  std::vector<double> residual_;
  std::vector<EdgeDesc> reverse_;
  std::vector<boost::default_color_type> color_;
  std::vector<double> delta_;
};

}  // namespace

AlphaExpansionResult MinimizeByAlphaExpansion(const PottsEnergy& energy, const AlphaExpansionOptions& options,
                                              const std::vector<int>* initial_labels) {
  options.Validate();
  AlphaExpansionResult result;
  const int n = energy.num_nodes();
  if (n == 0) {
    result.status = AlphaExpansionStatus::kEmpty;
    return result;
  }
  if (initial_labels != nullptr) {
    result.labels = *initial_labels;
  } else {
    result.labels.resize(static_cast<std::size_t>(n));
    for (int p = 0; p < n; ++p) {
      int best = 0;
      for (int l = 1; l < energy.num_labels(); ++l) {
        if (energy.DataCost(p, l) < energy.DataCost(p, best)) best = l;
      }
      result.labels[static_cast<std::size_t>(p)] = best;
    }
  }
  result.energy = energy.Evaluate(result.labels);  // also validates initial labels
  result.status = AlphaExpansionStatus::kMaxSweepsReached;
  if (energy.num_labels() == 1) {
    result.status = AlphaExpansionStatus::kConverged;
    return result;
  }

  ExpansionGraph graph(energy);
  std::vector<int> candidate;
  for (int sweep = 0; sweep < options.max_sweeps; ++sweep) {
    ++result.sweeps;
    bool improved = false;
    for (int alpha = 0; alpha < energy.num_labels(); ++alpha) {
      graph.Solve(result.labels, alpha, &candidate);
      // The cut value equals E(candidate) up to a constant; evaluating exactly keeps the accepted
      // energy sequence strictly decreasing whatever the max-flow's floating-point rounding.
      const double e = energy.Evaluate(candidate);
      if (e < result.energy - options.min_improvement) {
        result.labels.swap(candidate);
        result.energy = e;
        ++result.accepted_moves;
        improved = true;
      }
    }
    if (!improved) {
      result.status = AlphaExpansionStatus::kConverged;
      break;
    }
  }
  return result;
}

}  // namespace objscan::segmentation
