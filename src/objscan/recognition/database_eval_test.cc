#include "objscan/recognition/database_eval.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "objscan/common/error.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::recognition {
namespace {

// Fewer views and a small vocabulary keep the build to seconds.
DatabaseBuildOptions FastBuildOptions() {
  DatabaseBuildOptions options;
  options.scan.ring_elevations_deg = {20.0, 55.0};
  options.scan.ring_views = {6.0, 3.0};
  options.vocabulary.num_words = 32;
  options.vocabulary.max_training_descriptors = 5000;
  return options;
}

std::vector<ModelSource> SourcesOf(std::initializer_list<world::Category> categories) {
  std::vector<ModelSource> out;
  for (const ModelSource& s : ProceduralModelSources(1)) {
    if (std::find(categories.begin(), categories.end(), s.category) != categories.end()) out.push_back(s);
  }
  return out;
}

DatabaseEvalOptions FastEvalOptions() {
  DatabaseEvalOptions options;
  options.scan = FastBuildOptions().scan;
  options.objectness_models_per_category = 0;
  options.threads = 2;
  options.recognition.classifier.extra_training_databases = {};  // the database's own models only
  return options;
}

// The user's own models as queries: a database recognizes fresh scans of the very models it holds
// (a chair and a bed, as different as furniture gets), and a query of a category it lacks is skipped
// by name rather than counted as a miss.
TEST(DatabaseEvalTest, OwnModelsAreRecognizedAndUnknownCategoriesSkipped) {
  const ModelDatabase db = BuildDatabase(SourcesOf({world::Category::kChair, world::Category::kBed}), FastBuildOptions());
  const std::vector<ModelSource> queries =
      SourcesOf({world::Category::kChair, world::Category::kBed, world::Category::kSofa});
  ASSERT_EQ(queries.size(), 3u);

  const DatabaseEvalResult r = EvaluateDatabase(db, queries, FastEvalOptions());
  EXPECT_EQ(r.query_models, 2);
  ASSERT_EQ(r.skipped_queries.size(), 1u);
  EXPECT_EQ(r.skipped_queries[0], SourcesOf({world::Category::kSofa})[0].name);
  // Whole from 1 and from 3 views, and pieces (half of one view).
  ASSERT_EQ(r.by_views.size(), 3u);
  EXPECT_EQ(r.by_views[0].queries, 2);
  EXPECT_EQ(r.by_views[1].queries, 2);
  EXPECT_TRUE(r.by_views[2].piece);
  EXPECT_EQ(r.by_views[2].queries, 2);
  EXPECT_DOUBLE_EQ(r.by_views[1].top1_category_accuracy, 1.0) << "three views of a model the database holds";
  EXPECT_DOUBLE_EQ(r.by_views[1].retrieval_top1_accuracy, 1.0);
  ASSERT_EQ(r.queries.size(), 6u);
  for (const auto& q : r.queries) {
    EXPECT_TRUE(q.model == queries[0].name || q.model == queries[1].name) << q.model;
    EXPECT_TRUE(q.top5) << q.model << ": both categories are among the retrieved";
    // M(c) is listed best first, the first names the paper's prediction and its scores are eq. (1)'s
    // terms; the classifier trained on the two models gives a posterior over their categories.
    ASSERT_FALSE(q.retrieved.empty()) << q.model;
    EXPECT_EQ(q.retrieved.front().category, q.retrieved_category);
    EXPECT_TRUE(q.classified);
    EXPECT_NEAR(q.posterior[world::CategoryId(world::Category::kChair)] + q.posterior[world::CategoryId(world::Category::kBed)],
                1.0, 1e-6);  // leaves hold floats
    for (std::size_t k = 0; k < q.retrieved.size(); ++k) {
      const auto& m = q.retrieved[k];
      if (k > 0) {
        EXPECT_LE(m.rank_score, q.retrieved[k - 1].rank_score) << q.model;
      }
      EXPECT_GT(m.fit, 0.0);
      EXPECT_LE(m.fit, 1.0);
      EXPECT_LE(m.objectness, m.fit) << "eq. (1) adds completeness to the fit's distance";
      EXPECT_FALSE(m.model.empty());
    }
  }

  // Same seed, same answers, whatever the thread count.
  DatabaseEvalOptions one_thread = FastEvalOptions();
  one_thread.threads = 1;
  const DatabaseEvalResult again = EvaluateDatabase(db, queries, one_thread);
  ASSERT_EQ(again.queries.size(), r.queries.size());
  for (std::size_t i = 0; i < r.queries.size(); ++i) {
    EXPECT_EQ(again.queries[i].predicted, r.queries[i].predicted);
    EXPECT_EQ(again.queries[i].model, r.queries[i].model);
  }

  // Two draws: every query twice, the second from new views; the first draw is the same queries as
  // one draw gives (same posteriors), and each draw holds every kind of query of every model.
  DatabaseEvalOptions two_draws = FastEvalOptions();
  two_draws.draws_per_model = 2;
  const DatabaseEvalResult drawn = EvaluateDatabase(db, queries, two_draws);
  ASSERT_EQ(drawn.queries.size(), 2 * r.queries.size());
  EXPECT_EQ(drawn.query_models, r.query_models);
  ASSERT_EQ(drawn.by_views.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(drawn.by_views[k].queries, 2 * r.by_views[k].queries);
  // Queries are listed by kind (1 view, 3 views, piece), each kind's draws in order.
  std::vector<const DatabaseEvalResult::Query*> first_draw;
  int second = 0;
  bool any_new_posterior = false;
  for (const auto& q : drawn.queries) {
    if (q.draw == 0) {
      first_draw.push_back(&q);
    } else {
      EXPECT_EQ(q.draw, 1);
      ++second;
    }
  }
  ASSERT_EQ(first_draw.size(), r.queries.size());
  EXPECT_EQ(second, static_cast<int>(r.queries.size()));
  for (std::size_t i = 0; i < r.queries.size(); ++i) {
    EXPECT_EQ(first_draw[i]->model, r.queries[i].model);
    EXPECT_EQ(first_draw[i]->posterior, r.queries[i].posterior) << i;
  }
  for (const auto& q : drawn.queries) {
    if (q.draw != 1) continue;
    for (const auto& p : r.queries) {
      if (p.model == q.model && p.views == q.views && p.piece == q.piece && p.posterior != q.posterior) any_new_posterior = true;
    }
  }
  EXPECT_TRUE(any_new_posterior) << "the second draw scans the models from other views";
  two_draws.draws_per_model = 0;
  EXPECT_THROW(two_draws.Validate(), InputError);

  // At most queries_per_category per category: the first one of each.
  DatabaseEvalOptions capped = FastEvalOptions();
  std::vector<ModelSource> doubled = queries;
  doubled.insert(doubled.end(), queries.begin(), queries.end());
  capped.queries_per_category = 1;
  EXPECT_EQ(EvaluateDatabase(db, doubled, capped).query_models, 2);
  capped.queries_per_category = 0;
  EXPECT_EQ(EvaluateDatabase(db, doubled, capped).query_models, 4);

  // Nothing the database can answer: one error, not an empty success.
  EXPECT_THROW(EvaluateDatabase(db, SourcesOf({world::Category::kSofa}), FastEvalOptions()), InputError);
}

}  // namespace
}  // namespace objscan::recognition
