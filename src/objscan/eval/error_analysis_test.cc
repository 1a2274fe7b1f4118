#include "objscan/eval/error_analysis.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "objscan/common/error.h"

namespace objscan::eval {
namespace {

using world::Category;

// A hand-made room where every error class occurs. Ground truth: chairs 1 and 2, bed 3, a plant 4
// (`other`), lamp 5, table 6, a wall 9, a box 10 (`other`). The database knows chair, bed, lamp,
// table and radio (not `other`). Reported, in this order:
//   a chair on 1        correct
//   b chair on 1        duplicate piece (1 already matched by a)
//   c radio on 2        wrong category
//   d chair on 4        `other` object
//   e table on 0        background (no instance)
//   f bed on 9          structure (a wall)
//   g lamp on 3         duplicate piece (3 is matched by h, reported later)
//   h bed on 3          correct
//   i table on 42       background (an id not in the ground truth)
//   j table on 6        correct
// Lamp 5 and box 10 carry no reported object: missed.
struct HandMadeRoom {
  std::vector<GroundTruthInstance> truth = {
      {1, Category::kChair, true}, {2, Category::kChair, true}, {3, Category::kBed, true},
      {4, Category::kOther, true}, {5, Category::kLamp, false}, {6, Category::kTable, true},
      {9, Category::kWall, false}, {10, Category::kOther, true}};
  std::vector<OutputObject> outputs = {{Category::kChair, 1}, {Category::kChair, 1}, {Category::kRadio, 2},
                                       {Category::kChair, 4}, {Category::kTable, 0}, {Category::kBed, 9},
                                       {Category::kLamp, 3},  {Category::kBed, 3},   {Category::kTable, 42},
                                       {Category::kTable, 6}};
  std::vector<Category> database = {Category::kChair, Category::kBed, Category::kLamp, Category::kTable,
                                    Category::kRadio};
};

TEST(ErrorAnalysisTest, EveryReportedObjectFallsInExactlyOneClass) {
  const HandMadeRoom room;
  const ErrorAnalysis a = AnalyseErrors(room.truth, room.outputs, room.database);
  using O = OutputOutcome;
  EXPECT_EQ(a.output_outcomes,
            (std::vector<O>{O::kCorrect, O::kDuplicatePiece, O::kWrongCategory, O::kOtherObject,
                            O::kBackgroundOrStructure, O::kBackgroundOrStructure, O::kDuplicatePiece, O::kCorrect,
                            O::kBackgroundOrStructure, O::kCorrect}));
  EXPECT_EQ(a.breakdown.Count(O::kCorrect), 3);
  EXPECT_EQ(a.breakdown.Count(O::kWrongCategory), 1);
  EXPECT_EQ(a.breakdown.Count(O::kDuplicatePiece), 2);
  EXPECT_EQ(a.breakdown.Count(O::kOtherObject), 1);
  EXPECT_EQ(a.breakdown.Count(O::kBackgroundOrStructure), 3);
  EXPECT_EQ(a.breakdown.Total(), 10);
  EXPECT_DOUBLE_EQ(a.breakdown.Share(O::kDuplicatePiece), 0.2);
  EXPECT_DOUBLE_EQ(ErrorBreakdown{}.Share(O::kCorrect), 0.0);
}

// `correct` is precision's numerator and the classes sum to its denominator, on the hand-made room
// and on every prefix of its outputs (the order decides which piece is the match).
TEST(ErrorAnalysisTest, CorrectAgreesWithTheRecallPrecisionMatching) {
  const HandMadeRoom room;
  for (std::size_t n = 0; n <= room.outputs.size(); ++n) {
    SCOPED_TRACE(n);
    const std::vector<OutputObject> outputs(room.outputs.begin(), room.outputs.begin() + n);
    const RecognitionResult metrics = MatchRecognitions(room.truth, outputs, room.database);
    const ErrorAnalysis a = AnalyseErrors(room.truth, outputs, room.database);
    EXPECT_EQ(a.breakdown.Count(OutputOutcome::kCorrect), metrics.all.true_positives);
    EXPECT_EQ(a.breakdown.Total(), metrics.all.outputs);
    for (std::size_t o = 0; o < n; ++o) {
      EXPECT_EQ(a.output_outcomes[o] == OutputOutcome::kCorrect, metrics.output_is_true_positive[o]) << o;
    }
  }
  EXPECT_DOUBLE_EQ(AnalyseErrors(room.truth, room.outputs, room.database).breakdown.Share(OutputOutcome::kCorrect),
                   MatchRecognitions(room.truth, room.outputs, room.database).all.Precision());
}

TEST(ErrorAnalysisTest, ConfusionMatrixCountsCellByCell) {
  const HandMadeRoom room;
  const ConfusionMatrix& m = AnalyseErrors(room.truth, room.outputs, room.database).confusion;
  const std::string bg = ConfusionMatrix::kBackgroundRow, missed = ConfusionMatrix::kMissedColumn;
  // Categories in world::Category order, background last; missed last.
  EXPECT_EQ(m.Rows(), (std::vector<std::string>{"bed", "chair", "lamp", "table", "other", bg}));
  EXPECT_EQ(m.Columns(), (std::vector<std::string>{"bed", "chair", "lamp", "radio", "table", missed}));
  // Every cell: {row, {column, count}...}; the cells not listed are 0.
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, int>>>> expected = {
      {"bed", {{"lamp", 1}, {"bed", 1}}},
      {"chair", {{"chair", 2}, {"radio", 1}}},
      {"lamp", {{missed, 1}}},
      {"table", {{"table", 1}}},
      {"other", {{"chair", 1}, {missed, 1}}},
      {bg, {{"table", 2}, {"bed", 1}}}};
  int sum = 0;
  for (const auto& row : m.Rows()) {
    for (const auto& column : m.Columns()) {
      int want = 0;
      for (const auto& [r, cells] : expected) {
        if (r != row) continue;
        for (const auto& [c, n] : cells) want += c == column ? n : 0;
      }
      EXPECT_EQ(m.Count(row, column), want) << row << " x " << column;
      sum += m.Count(row, column);
    }
  }
  // Ten reported objects and two missed ground-truth objects; the wall is never missed.
  EXPECT_EQ(sum, 12);
  EXPECT_EQ(m.ColumnTotal(missed), 2);
  EXPECT_EQ(m.RowTotal(bg), 3);
  EXPECT_EQ(m.Count("wall", missed), 0);
  EXPECT_EQ(m.Count("no such row", "chair"), 0);

  ConfusionMatrix twice = m;
  twice.Add(m);
  EXPECT_EQ(twice.Count("chair", "chair"), 4);
  EXPECT_EQ(twice.Count(bg, "table"), 4);
}

TEST(ErrorAnalysisTest, OtherObjectsAreNeverGroundTruthEvenWhenTheDatabaseHasThem) {
  // With `other` models in the database, objects recognised as `other` are no outputs (the caller
  // leaves them out) and plants are in no ground-truth set: a chair on a plant stays an `other`
  // object error, and the plants are not missed objects of the recall.
  const std::vector<GroundTruthInstance> truth = {{4, Category::kOther, true}, {5, Category::kOther, true}};
  const std::vector<OutputObject> outputs = {{Category::kChair, 5}};
  const ErrorAnalysis a = AnalyseErrors(truth, outputs, {Category::kChair, Category::kOther});
  EXPECT_EQ(a.output_outcomes, (std::vector<OutputOutcome>{OutputOutcome::kOtherObject}));
  EXPECT_EQ(a.recognition.all.ground_truth, 0);
  EXPECT_EQ(a.confusion.Count("other", "chair"), 1);
  EXPECT_EQ(a.confusion.Count("other", ConfusionMatrix::kMissedColumn), 1);
  EXPECT_THROW(AnalyseErrors(truth, {{Category::kOther, 4}}, {Category::kChair, Category::kOther}),
               std::invalid_argument);
}

TEST(ErrorAnalysisTest, NothingReportedMissesEveryObjectAndDuplicateIdsThrow) {
  const HandMadeRoom room;
  const ErrorAnalysis a = AnalyseErrors(room.truth, {}, room.database);
  EXPECT_EQ(a.breakdown.Total(), 0);
  EXPECT_EQ(a.confusion.Columns(), (std::vector<std::string>{ConfusionMatrix::kMissedColumn}));
  EXPECT_EQ(a.confusion.ColumnTotal(ConfusionMatrix::kMissedColumn), 7);  // all but the wall
  EXPECT_EQ(a.confusion.Count("other", ConfusionMatrix::kMissedColumn), 2);
  std::vector<GroundTruthInstance> twice = room.truth;
  twice.push_back(room.truth.front());
  EXPECT_THROW(AnalyseErrors(twice, room.outputs, room.database), InputError);
}

// Each output's share of its object (metrics.h: OutputObject::instance_share) sorts it as on a piece
// (below half) or not, per class; outputs without a share (negative) are not counted as known.
TEST(ErrorAnalysisTest, OutputsOnAPieceOfTheirObjectAreCountedPerClass) {
  HandMadeRoom room;
  const std::vector<double> shares = {0.9,   // a: correct, whole
                                      0.1,   // b: duplicate piece, on a piece
                                      0.3,   // c: wrong category, on a piece
                                      0.5,   // d: `other` object, half is no piece
                                      0.2,   // e: background: never on a piece
                                      -1.0,  // f: unknown
                                      0.49,  // g: duplicate piece, on a piece
                                      0.51,  // h: correct, whole
                                      -1.0,  // i: unknown
                                      0.0};  // j: correct with no share of its object: on a piece
  for (std::size_t o = 0; o < shares.size(); ++o) room.outputs[o].instance_share = shares[o];
  const ErrorAnalysis a = AnalyseErrors(room.truth, room.outputs, room.database);
  using O = OutputOutcome;
  EXPECT_EQ(a.breakdown.share_known, 8);
  EXPECT_EQ(a.breakdown.OnPiece(O::kCorrect), 1);
  EXPECT_EQ(a.breakdown.OnPiece(O::kDuplicatePiece), 2);
  EXPECT_EQ(a.breakdown.OnPiece(O::kWrongCategory), 1);
  EXPECT_EQ(a.breakdown.OnPiece(O::kOtherObject), 0);
  EXPECT_EQ(a.breakdown.OnPiece(O::kBackgroundOrStructure), 0);
  ErrorBreakdown sum = a.breakdown;
  sum.Add(a.breakdown);
  EXPECT_EQ(sum.share_known, 16);
  EXPECT_EQ(sum.OnPiece(O::kDuplicatePiece), 4);
  // Without shares (the default), nothing is known and nothing is on a piece.
  const ErrorAnalysis none = AnalyseErrors(room.truth, HandMadeRoom().outputs, room.database);
  EXPECT_EQ(none.breakdown.share_known, 0);
  EXPECT_EQ(none.breakdown.on_piece, (std::array<int, kNumOutputOutcomes>{}));
}

TEST(ErrorAnalysisTest, OutcomeNames) {
  EXPECT_STREQ(OutputOutcomeName(OutputOutcome::kCorrect), "correct");
  EXPECT_STREQ(OutputOutcomeName(OutputOutcome::kWrongCategory), "wrong_category");
  EXPECT_STREQ(OutputOutcomeName(OutputOutcome::kDuplicatePiece), "duplicate_piece");
  EXPECT_STREQ(OutputOutcomeName(OutputOutcome::kOtherObject), "other_object");
  EXPECT_STREQ(OutputOutcomeName(OutputOutcome::kBackgroundOrStructure), "background_or_structure");
  EXPECT_EQ(OutputOutcomesInReportOrder().front(), OutputOutcome::kCorrect);
}

}  // namespace
}  // namespace objscan::eval
