#pragma once
// The conditional information gain of the paper's NBV (eqs. (7)-(12), labels equ:info-gain ..
// equ:certainty-3), per voxel. Natural logarithms (nats); 0 log 0 = 0.
//
//   p(m_i)       = O(gamma, m_i) / sum_k O(gamma, m_k)                        (prior over candidates)
//   H(x)         = -sum_k p_x(m_k) log p_x(m_k),  p_x(m_k) = p(m_k)            (eq. intial-uncertainty)
//   p_x(1 | m_k) = f(x, m_k),  p_x(0 | m_k) = 1 - f(x, m_k)
//   p_x(m_i | d) = p(m_i) p_x(d | m_i) / sum_k p(m_k) p_x(d | m_k)             (eq. certainty-3)
//   H_x(d)       = -sum_k p_x(m_k | d) log p_x(m_k | d)                        (eq. certainty-2)
//   H(x | m_i)   = p_x(0 | m_i) H_x(0) + p_x(1 | m_i) H_x(1)                   (eq. certainty)
//   G^j(m_i)     = sum over x in Delta of H(x) - H(x | m_i)                    (eq. info-gain-pixels)
//   G^j          = sum_i p(m_i) G^j(m_i)                                       (eq. info-gain)
#include <vector>

namespace objscan::planning {

// p(m_i) from the objectness scores O(gamma, m_i) (each >= 0). All zero: uniform (no preference).
// Throws InputError on a negative or non-finite score.
std::vector<double> CandidateProbabilities(const std::vector<double>& objectness);

// -sum p log p over `n` probabilities.
double Entropy(const double* p, int n);

// H_x(0) and H_x(1) of one voxel from the priors p (n of them, summing to 1) and f(x, m_k) (n values in
// [0, 1]). When no candidate can produce outcome d (sum_k p_k p_x(d|m_k) = 0) its posterior is
// undefined; H_x(d) is then the prior entropy (that outcome carries no weight in H(x|m_i) anyway).
void OutcomeEntropies(const double* p, const float* f, int n, double prior_entropy, double* h0, double* h1);

// H(x | m_i) from f(x, m_i) and the outcome entropies.
inline double ConditionalEntropy(double f_i, double h0, double h1) { return (1.0 - f_i) * h0 + f_i * h1; }

}  // namespace objscan::planning
