#include "objscan/planning/information_gain.h"

#include <cmath>
#include <string>

#include "objscan/common/error.h"

namespace objscan::planning {

std::vector<double> CandidateProbabilities(const std::vector<double>& objectness) {
  double sum = 0.0;
  for (std::size_t i = 0; i < objectness.size(); ++i) {
    if (!std::isfinite(objectness[i]) || objectness[i] < 0.0) {
      throw InputError("nbv model " + std::to_string(i) + ": objectness must be finite and >= 0");
    }
    sum += objectness[i];
  }
  std::vector<double> p(objectness.size(), objectness.empty() ? 0.0 : 1.0 / objectness.size());
  if (sum > 0.0) {
    for (std::size_t i = 0; i < objectness.size(); ++i) p[i] = objectness[i] / sum;
  }
  return p;
}

double Entropy(const double* p, int n) {
  double h = 0.0;
  for (int k = 0; k < n; ++k) {
    if (p[k] > 0.0) h -= p[k] * std::log(p[k]);
  }
  return h;
}

void OutcomeEntropies(const double* p, const float* f, int n, double prior_entropy, double* h0, double* h1) {
  double z0 = 0.0, z1 = 0.0;
  for (int k = 0; k < n; ++k) {
    z1 += p[k] * f[k];
    z0 += p[k] * (1.0 - f[k]);
  }
  double e0 = 0.0, e1 = 0.0;
  for (int k = 0; k < n; ++k) {
    if (z1 > 0.0) {
      const double q = p[k] * f[k] / z1;
      if (q > 0.0) e1 -= q * std::log(q);
    }
    if (z0 > 0.0) {
      const double q = p[k] * (1.0 - f[k]) / z0;
      if (q > 0.0) e0 -= q * std::log(q);
    }
  }
  *h0 = z0 > 0.0 ? e0 : prior_entropy;
  *h1 = z1 > 0.0 ? e1 : prior_entropy;
}

}  // namespace objscan::planning
