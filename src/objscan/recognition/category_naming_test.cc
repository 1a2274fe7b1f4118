#include "objscan/recognition/category_naming.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"

namespace objscan::recognition {
namespace {

using world::Category;

CategoryClassifier::Probabilities Posterior(std::initializer_list<std::pair<Category, double>> p) {
  CategoryClassifier::Probabilities out{};
  for (const auto& [c, v] : p) out[static_cast<std::size_t>(world::CategoryId(c))] = v;
  return out;
}

TEST(CategoryNamingTest, WeightZeroIsThePapersChoiceOfTheBestModel) {
  CategoryNamingOptions options;
  options.classifier_weight = 0.0;
  const auto name = NameCategory(Posterior({{Category::kChair, 0.9}, {Category::kSofa, 0.1}}),
                                 {{Category::kChair, 0.5}, {Category::kSofa, 0.7}}, options);
  ASSERT_TRUE(name.named);
  EXPECT_EQ(name.category, Category::kSofa);
  EXPECT_DOUBLE_EQ(name.posterior, 0.1);
}

TEST(CategoryNamingTest, BothVoteAndACategoryMCLacksCountsAtItsShareOfTheWeakest) {
  const CategoryNamingOptions options;  // weight 1, absent share 0.5
  // chair 0.9 x 0.5 = 0.45 against sofa 0.1 x 0.7 = 0.07.
  EXPECT_EQ(NameCategory(Posterior({{Category::kChair, 0.9}, {Category::kSofa, 0.1}}),
                         {{Category::kChair, 0.5}, {Category::kSofa, 0.7}}, options)
                .category,
            Category::kChair);
  // Bed is not in M(c): 0.6 x 0.5 x 0.4 = 0.12 against chair 0.3 x 0.6 = 0.18 and sofa 0.1 x 0.4.
  EXPECT_EQ(NameCategory(Posterior({{Category::kBed, 0.6}, {Category::kChair, 0.3}, {Category::kSofa, 0.1}}),
                         {{Category::kChair, 0.6}, {Category::kSofa, 0.4}}, options)
                .category,
            Category::kChair);
  // ... unless the classifier is sure enough: 0.95 x 0.2 = 0.19 against 0.04 x 0.6.
  EXPECT_EQ(NameCategory(Posterior({{Category::kBed, 0.95}, {Category::kChair, 0.04}, {Category::kSofa, 0.01}}),
                         {{Category::kChair, 0.6}, {Category::kSofa, 0.4}}, options)
                .category,
            Category::kBed);
}

TEST(CategoryNamingTest, OtherCountsAtItsWeight) {
  CategoryNamingOptions options;
  options.other_weight = 0.5;
  // other 0.5 x 0.5 x 0.6 = 0.15 against table 0.4 x 0.6: table.
  const auto posterior = Posterior({{Category::kOther, 0.5}, {Category::kTable, 0.4}, {Category::kDesk, 0.1}});
  const std::vector<RetrievedCategory> votes = {{Category::kOther, 0.6}, {Category::kTable, 0.6}};
  const auto name = NameCategory(posterior, votes, options);
  EXPECT_EQ(name.category, Category::kTable);
  EXPECT_DOUBLE_EQ(name.posterior, 0.4);
  options.other_weight = 1.0;
  EXPECT_EQ(NameCategory(posterior, votes, options).category, Category::kOther);
  // A weight above 1 favours `other`: 1.5 x 0.2 x 0.6 = 0.18 against table 0.3 x 0.5 = 0.15.
  const auto unsure = Posterior({{Category::kOther, 0.2}, {Category::kTable, 0.3}, {Category::kDesk, 0.5}});
  const std::vector<RetrievedCategory> table_votes = {{Category::kOther, 0.6}, {Category::kTable, 0.5}};
  options.other_weight = 1.0;
  EXPECT_EQ(NameCategory(unsure, table_votes, options).category, Category::kTable);
  options.other_weight = 1.5;
  EXPECT_EQ(NameCategory(unsure, table_votes, options).category, Category::kOther);
}

TEST(CategoryNamingTest, OneRecognizerAloneNamesAndNeitherNamesNothing) {
  const CategoryNamingOptions options;
  EXPECT_EQ(NameCategory(CategoryClassifier::Probabilities{}, {{Category::kLamp, 0.2}, {Category::kDesk, 0.3}}, options)
                .category,
            Category::kDesk);
  EXPECT_EQ(NameCategory(Posterior({{Category::kToilet, 0.7}, {Category::kSink, 0.3}}), {}, options).category,
            Category::kToilet);
  EXPECT_FALSE(NameCategory(CategoryClassifier::Probabilities{}, {}, options).named);
}

TEST(CategoryNamingTest, OptionsOutOfRangeNameTheirField) {
  CategoryNamingOptions options;
  options.absent_share = 1.5;
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.naming.absent_share"), std::string::npos) << e.what();
  }
  options = CategoryNamingOptions();
  options.other_weight = -0.5;
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.naming.other_weight"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace objscan::recognition
