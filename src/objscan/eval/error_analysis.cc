#include "objscan/eval/error_analysis.h"

#include <algorithm>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "objscan/world/category.h"

namespace objscan::eval {

const char* OutputOutcomeName(OutputOutcome outcome) {
  switch (outcome) {
    case OutputOutcome::kCorrect: return "correct";
    case OutputOutcome::kBackgroundOrStructure: return "background_or_structure";
    case OutputOutcome::kDuplicatePiece: return "duplicate_piece";
    case OutputOutcome::kOtherObject: return "other_object";
    case OutputOutcome::kWrongCategory: return "wrong_category";
  }
  return "unknown";
}

const std::array<OutputOutcome, kNumOutputOutcomes>& OutputOutcomesInReportOrder() {
  static const std::array<OutputOutcome, kNumOutputOutcomes> kOrder = {
      OutputOutcome::kCorrect, OutputOutcome::kWrongCategory, OutputOutcome::kDuplicatePiece,
      OutputOutcome::kOtherObject, OutputOutcome::kBackgroundOrStructure};
  return kOrder;
}

int ErrorBreakdown::Total() const {
  int total = 0;
  for (int c : counts) total += c;
  return total;
}

double ErrorBreakdown::Share(OutputOutcome outcome) const {
  const int total = Total();
  return total > 0 ? static_cast<double>(Count(outcome)) / total : 0.0;
}

void ErrorBreakdown::Add(const ErrorBreakdown& other) {
  for (std::size_t i = 0; i < counts.size(); ++i) {
    counts[i] += other.counts[i];
    on_piece[i] += other.on_piece[i];
  }
  share_known += other.share_known;
}

void ConfusionMatrix::Add(const std::string& row, const std::string& column, int count) {
  if (count == 0) return;
  cells_[{row, column}] += count;
}

void ConfusionMatrix::Add(const ConfusionMatrix& other) {
  for (const auto& [cell, count] : other.cells_) Add(cell.first, cell.second, count);
}

int ConfusionMatrix::Count(const std::string& row, const std::string& column) const {
  auto it = cells_.find({row, column});
  return it == cells_.end() ? 0 : it->second;
}

namespace {

// Category names in world::Category order, unknown names after them (sorted, as the set holds them),
// `last` at the end: a fixed order so that merged shards give the same table as one bench.
std::vector<std::string> InCategoryOrder(const std::set<std::string>& names, const std::string& last) {
  std::vector<std::string> out;
  for (int c = 0; c < world::kNumCategories; ++c) {
    const std::string name = world::CategoryName(static_cast<world::Category>(c));
    if (names.count(name)) out.push_back(name);
  }
  for (const auto& name : names) {
    if (name != last && !world::ParseCategory(name)) out.push_back(name);
  }
  if (names.count(last)) out.push_back(last);
  return out;
}

}  // namespace

std::vector<std::string> ConfusionMatrix::Rows() const {
  std::set<std::string> rows;
  for (const auto& [cell, count] : cells_) rows.insert(cell.first);
  return InCategoryOrder(rows, kBackgroundRow);
}

std::vector<std::string> ConfusionMatrix::Columns() const {
  std::set<std::string> columns;
  for (const auto& [cell, count] : cells_) columns.insert(cell.second);
  return InCategoryOrder(columns, kMissedColumn);
}

int ConfusionMatrix::RowTotal(const std::string& row) const {
  int total = 0;
  for (const auto& [cell, count] : cells_) {
    if (cell.first == row) total += count;
  }
  return total;
}

int ConfusionMatrix::ColumnTotal(const std::string& column) const {
  int total = 0;
  for (const auto& [cell, count] : cells_) {
    if (cell.second == column) total += count;
  }
  return total;
}

ErrorAnalysis AnalyseErrors(const std::vector<GroundTruthInstance>& ground_truth,
                            const std::vector<OutputObject>& outputs,
                            const std::vector<world::Category>& database_categories) {
  ErrorAnalysis analysis;
  // The matching of the recall/precision metrics itself (it also rejects duplicate instance ids).
  analysis.recognition = MatchRecognitions(ground_truth, outputs, database_categories);
  const RecognitionResult& rec = analysis.recognition;
  std::unordered_map<int, const GroundTruthInstance*> instance_by_id;
  for (const GroundTruthInstance& g : ground_truth) instance_by_id.emplace(g.instance_id, &g);
  const std::unordered_set<int> matched(rec.matched_instances.begin(), rec.matched_instances.end());

  std::unordered_set<int> reported_instances;
  analysis.output_outcomes.reserve(outputs.size());
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const OutputObject& out = outputs[o];
    auto it = instance_by_id.find(out.majority_instance);
    const GroundTruthInstance* g = it == instance_by_id.end() ? nullptr : it->second;
    const bool on_object = g != nullptr && !world::IsStructural(g->category);
    OutputOutcome outcome;
    if (rec.output_is_true_positive[o]) {
      outcome = OutputOutcome::kCorrect;
    } else if (!on_object) {
      outcome = OutputOutcome::kBackgroundOrStructure;
    } else if (matched.count(g->instance_id)) {
      // Not the true positive itself, so another output matched this object.
      outcome = OutputOutcome::kDuplicatePiece;
    } else if (g->category == world::Category::kOther) {
      outcome = OutputOutcome::kOtherObject;
    } else {
      outcome = OutputOutcome::kWrongCategory;
    }
    analysis.output_outcomes.push_back(outcome);
    ++analysis.breakdown.counts[static_cast<std::size_t>(outcome)];
    if (out.instance_share >= 0.0) {
      ++analysis.breakdown.share_known;
      if (on_object && out.instance_share < kPieceMaxInstanceShare) {
        ++analysis.breakdown.on_piece[static_cast<std::size_t>(outcome)];
      }
    }
    const std::string row = on_object ? world::CategoryName(g->category) : ConfusionMatrix::kBackgroundRow;
    analysis.confusion.Add(row, world::CategoryName(out.category));
    if (on_object) reported_instances.insert(g->instance_id);
  }
  for (const GroundTruthInstance& g : ground_truth) {
    if (world::IsStructural(g.category) || reported_instances.count(g.instance_id)) continue;
    analysis.confusion.Add(world::CategoryName(g.category), ConfusionMatrix::kMissedColumn);
  }
  return analysis;
}

}  // namespace objscan::eval
