#include "objscan/recognition/category_naming.h"

#include <algorithm>
#include <cmath>

namespace objscan::recognition {

void CategoryNamingOptions::Validate() const {
  config::RequireNonNegative("recognition.naming.classifier_weight", classifier_weight);
  config::RequireInRange("recognition.naming.absent_share", absent_share, 0.0, 1.0);
  config::RequireNonNegative("recognition.naming.other_weight", other_weight);
}

CategoryName NameCategory(const CategoryClassifier::Probabilities& posterior_in,
                          const std::vector<RetrievedCategory>& retrieved, const CategoryNamingOptions& options) {
  CategoryName out;
  CategoryClassifier::Probabilities posterior = posterior_in;
  posterior[static_cast<std::size_t>(world::CategoryId(world::Category::kOther))] *= options.other_weight;
  const bool classified = std::any_of(posterior.begin(), posterior.end(), [](double p) { return p > 0.0; });
  std::array<double, world::kNumCategories> fit{};
  fit.fill(-1.0);
  double weakest = 0.0;
  bool any = false;
  for (const RetrievedCategory& r : retrieved) {
    const auto k = static_cast<std::size_t>(world::CategoryId(r.category));
    const double s = std::max(0.0, r.score);
    fit[k] = std::max(fit[k], s);
    weakest = any ? std::min(weakest, s) : s;
    any = true;
  }
  if (!classified && !any) return out;
  const double absent = options.absent_share * weakest;
  double best = -1.0;
  for (int k = 0; k < world::kNumObjectCategories; ++k) {
    const double f = !any ? 1.0 : (fit[static_cast<std::size_t>(k)] >= 0.0 ? fit[static_cast<std::size_t>(k)] : absent);
    const double p = classified ? std::pow(posterior[static_cast<std::size_t>(k)], options.classifier_weight) : 1.0;
    // A category neither recognizer supports is never named.
    if (classified && posterior[static_cast<std::size_t>(k)] <= 0.0 && fit[static_cast<std::size_t>(k)] < 0.0) continue;
    if (!classified && fit[static_cast<std::size_t>(k)] < 0.0) continue;
    const double score = p * f;
    if (score > best) {
      best = score;
      out.named = true;
      out.category = static_cast<world::Category>(k);
      out.posterior = classified ? posterior_in[static_cast<std::size_t>(k)] : 0.0;
    }
  }
  return out;
}

}  // namespace objscan::recognition
