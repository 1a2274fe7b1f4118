#pragma once
// Beyond the paper: which category a segment is named, from the two recognizers objscan has. The
// paper names the category of the best-fitting model in M(c); the category classifier
// (category_classifier.h) names the category whose models the segment's shape resembles as a
// whole. Both vote: with P(k) the classifier's posterior and F(k) the best rank score among M(c)'s
// models of category k (F_absent = absent_share x the weakest retrieved score for a category M(c)
// lacks), the name is argmax_k P(k)^classifier_weight x F(k). classifier_weight = 0 is the paper's
// choice (the category of the best model); a large weight is the classifier's choice. P(other) is
// first multiplied by other_weight, a prior for "not recognized": the classifier learns `other` from
// every prop and plant of the database, a class that spans all shapes. Where the forest's trees are
// deep, `other` holds leaves of its own and takes furniture queries (weights below 1 served it:
// docs/results/oasc-dev-2026-11-28-category-recognizer.md); with the shallower trees held-out
// validation chooses for real scenes, its share is spread over many leaves and a weight above 1
// names props `other` again (docs/results/recognizer-2026-11-29-held-out-depth.md).
#include <vector>

#include "objscan/common/config.h"
#include "objscan/recognition/category_classifier.h"
#include "objscan/world/category.h"

namespace objscan::recognition {

struct CategoryNamingOptions {
  double classifier_weight = 1.0;
  double absent_share = 0.5;
  double other_weight = 1.5;

  template <class V>
  void Visit(V& v) {
    v("classifier_weight", classifier_weight);
    v("absent_share", absent_share);
    v("other_weight", other_weight);
  }
  void Validate() const;
};

// One retrieved model's category and rank score (M(c), any order).
struct RetrievedCategory {
  world::Category category = world::Category::kOther;
  double score = 0.0;
};

struct CategoryName {
  bool named = false;  // false: nothing retrieved and no classifier
  world::Category category = world::Category::kOther;
  double posterior = 0.0;  // P(category) of the classifier (0 when it has none)
};

// The name; without a trained classifier (all-zero posterior) the category of the best retrieved
// model, without retrieved models the classifier's first choice.
CategoryName NameCategory(const CategoryClassifier::Probabilities& posterior,
                          const std::vector<RetrievedCategory>& retrieved, const CategoryNamingOptions& options);

}  // namespace objscan::recognition
