#pragma once
// Where the reported objects of a run go wrong: every reported labelled object (an output of the
// recognition metrics) falls in exactly one error class, and a confusion matrix counts ground-truth
// category against reported category. The classes are decided with MatchRecognitions (metrics.h),
// so `correct` is precision's numerator and the classes sum to its denominator.
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "objscan/eval/metrics.h"

namespace objscan::eval {

// The error class of one reported labelled object. Checked in this order, the first that holds:
enum class OutputOutcome : int {
  kCorrect = 0,           // a true positive of MatchRecognitions
  kBackgroundOrStructure, // its majority instance is no ground-truth object (background, floor, wall)
  kDuplicatePiece,        // its object is matched by another output: a second piece of a found object,
                          // whatever its label, whether it was reported before or after the match
  kOtherObject,           // it lies on an object of category `other` (plant, towel, box, vase...)
  kWrongCategory,         // it lies on an unmatched object of another category
};
constexpr int kNumOutputOutcomes = 5;
// Snake-case names used in JSON and CSV: correct, background_or_structure, duplicate_piece,
// other_object, wrong_category.
const char* OutputOutcomeName(OutputOutcome outcome);
// All classes in report order: correct first, then the errors from the one the issue counts most.
const std::array<OutputOutcome, kNumOutputOutcomes>& OutputOutcomesInReportOrder();

// An output holding less than this share of its ground-truth object's reconstructed surface lies on a
// piece of it (OutputObject::instance_share).
constexpr double kPieceMaxInstanceShare = 0.5;

// Counts of reported labelled objects per error class.
struct ErrorBreakdown {
  std::array<int, kNumOutputOutcomes> counts{};
  // Of each class, the outputs on a piece of their object (instance_share known and below
  // kPieceMaxInstanceShare), and how many outputs have their share known at all.
  std::array<int, kNumOutputOutcomes> on_piece{};
  int share_known = 0;

  int Count(OutputOutcome outcome) const { return counts[static_cast<std::size_t>(outcome)]; }
  int OnPiece(OutputOutcome outcome) const { return on_piece[static_cast<std::size_t>(outcome)]; }
  int Total() const;
  // Count / Total; 0 when nothing was reported.
  double Share(OutputOutcome outcome) const;
  void Add(const ErrorBreakdown& other);
};

// Ground-truth category (rows) against reported category (columns), in counts. Category names are
// world::CategoryName spellings. A reported object adds one to (its majority instance's category, its
// label), or to (kBackgroundRow, its label) when that instance is no ground-truth object; a
// non-structural ground-truth object no reported object lies on adds one to (its category, kMissedColumn).
class ConfusionMatrix {
 public:
  static constexpr const char* kBackgroundRow = "background/structure";
  static constexpr const char* kMissedColumn = "missed";

  void Add(const std::string& row, const std::string& column, int count = 1);
  void Add(const ConfusionMatrix& other);
  int Count(const std::string& row, const std::string& column) const;
  bool Empty() const { return cells_.empty(); }
  // Rows and columns holding a non-zero count: categories in world::Category order (unknown names
  // after them, sorted), then kBackgroundRow / kMissedColumn.
  std::vector<std::string> Rows() const;
  std::vector<std::string> Columns() const;
  // Sum of a row or column.
  int RowTotal(const std::string& row) const;
  int ColumnTotal(const std::string& column) const;

 private:
  std::map<std::pair<std::string, std::string>, int> cells_;
};

struct ErrorAnalysis {
  std::vector<OutputOutcome> output_outcomes;  // parallel to the outputs
  ErrorBreakdown breakdown;
  ConfusionMatrix confusion;
  RecognitionResult recognition;  // the matching the classes come from
};

// Classifies `outputs` (in reporting order, as MatchRecognitions takes them) against `ground_truth`
// (structural instances may be listed: outputs on them count as structure and they are never missed).
// Throws InputError on duplicate instance ids.
ErrorAnalysis AnalyseErrors(const std::vector<GroundTruthInstance>& ground_truth,
                            const std::vector<OutputObject>& outputs,
                            const std::vector<world::Category>& database_categories);

}  // namespace objscan::eval
