#pragma once
// The report rules (report_rule.h), each a small class with the options it reads. First, when
// listed (not by default: it cost recall and coverage on the OASC dev worlds):
//   reopen_outgrown        completed objects whose seen surface outgrew their model, or a door deeper
//                          than a door leaf, are reported unfinished and recognized again as a whole
// then in objscan's default order (DefaultReportRules):
//   model_label            an unfinished object takes its best full model's category when confident
//   absorb_fragments       pieces lying on a recognized neighbour's model join it
//   regroup_by_size        pieces too small for their label join a neighbour whose category fits
//   join_stacked           of two labelled pieces one under the other, the smaller joins the larger
//   door_depth             a door label on a thing deeper than a door leaf goes
//   wall_openings          things in wall openings are windows; window labels elsewhere go
//   size_check             a label no database model of the object's size has goes
//   curtain_must_hang      a curtain label on a thing that hangs on no wall goes
//   relabel                a label a rule took is replaced by a confident match that fits
//   join_window_pieces     pieces of one window in a wall opening are one window
//   curtains_over_windows  things hanging over a window are curtains; the panels over one are one
//   drop_small             a labelled object too small to trust is reported unrecognized
// and, not listed by default:
//   drop_unsure            an unfinished object recognized with low objectness is reported unrecognized
#include <memory>
#include <string>

#include "objscan/scanning/report/report_options.h"
#include "objscan/scanning/report/report_rule.h"

namespace objscan::scanning {

class ReopenOutgrownRule : public ReportRule {
 public:
  ReopenOutgrownRule(const CompletionCheckOptions& options, const WallOpeningOptions& doors)
      : options_(options), doors_(doors) {}
  const char* name() const override { return "reopen_outgrown"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  CompletionCheckOptions options_;
  WallOpeningOptions doors_;
};

class ModelLabelRule : public ReportRule {
 public:
  explicit ModelLabelRule(double min_objectness) : min_objectness_(min_objectness) {}
  const char* name() const override { return "model_label"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  double min_objectness_;
};

class AbsorbFragmentsRule : public ReportRule {
 public:
  explicit AbsorbFragmentsRule(const FragmentAbsorptionOptions& options) : options_(options) {}
  const char* name() const override { return "absorb_fragments"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  FragmentAbsorptionOptions options_;
};

class RegroupBySizeRule : public ReportRule {
 public:
  explicit RegroupBySizeRule(const recognition::SizePlausibilityOptions& options) : options_(options) {}
  const char* name() const override { return "regroup_by_size"; }
  bool needs_category_extents() const override { return true; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  recognition::SizePlausibilityOptions options_;
};

class JoinStackedRule : public ReportRule {
 public:
  explicit JoinStackedRule(const recognition::SizePlausibilityOptions& options) : options_(options) {}
  const char* name() const override { return "join_stacked"; }
  bool needs_category_extents() const override { return true; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  recognition::SizePlausibilityOptions options_;
};

class DoorDepthRule : public ReportRule {
 public:
  explicit DoorDepthRule(const WallOpeningOptions& options) : options_(options) {}
  const char* name() const override { return "door_depth"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  WallOpeningOptions options_;
};

class WallOpeningsRule : public ReportRule {
 public:
  explicit WallOpeningsRule(const WallOpeningOptions& options) : options_(options) {}
  const char* name() const override { return "wall_openings"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  WallOpeningOptions options_;
};

class SizeCheckRule : public ReportRule {
 public:
  explicit SizeCheckRule(const recognition::SizePlausibilityOptions& options) : options_(options) {}
  const char* name() const override { return "size_check"; }
  bool needs_category_extents() const override { return true; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  recognition::SizePlausibilityOptions options_;
};

class CurtainMustHangRule : public ReportRule {
 public:
  explicit CurtainMustHangRule(const WallOpeningOptions& options) : options_(options) {}
  const char* name() const override { return "curtain_must_hang"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  WallOpeningOptions options_;
};

class RelabelRule : public ReportRule {
 public:
  explicit RelabelRule(const recognition::SizePlausibilityOptions& options) : options_(options) {}
  const char* name() const override { return "relabel"; }
  bool needs_category_extents() const override { return true; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  recognition::SizePlausibilityOptions options_;
};

class JoinWindowPiecesRule : public ReportRule {
 public:
  explicit JoinWindowPiecesRule(const WallOpeningOptions& options) : options_(options) {}
  const char* name() const override { return "join_window_pieces"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  WallOpeningOptions options_;
};

class CurtainsOverWindowsRule : public ReportRule {
 public:
  explicit CurtainsOverWindowsRule(const WallOpeningOptions& options) : options_(options) {}
  const char* name() const override { return "curtains_over_windows"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  WallOpeningOptions options_;
};

class DropSmallRule : public ReportRule {
 public:
  explicit DropSmallRule(int min_elements) : min_elements_(min_elements) {}
  const char* name() const override { return "drop_small"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  int min_elements_;
};

class DropUnsureRule : public ReportRule {
 public:
  explicit DropUnsureRule(double min_objectness) : min_objectness_(min_objectness) {}
  const char* name() const override { return "drop_unsure"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  double min_objectness_;
};

// shape_agrees: a labelled object whose category the database-trained category classifier finds
// less than min_odds times as likely as its own first choice is reported unrecognized
// (recognition/category_classifier.h). Two recognizers that share no evidence but the points, the
// best-fitting model and the shape statistics of whole categories, agreeing: on the OASC dev models
// (leave one world out) their agreement held most right labels and their disagreement mostly wrong
// ones (docs/results/oasc-dev-2026-11-27-category-classifier.md).
class ShapeAgreesRule : public ReportRule {
 public:
  explicit ShapeAgreesRule(double min_odds) : min_odds_(min_odds) {}
  const char* name() const override { return "shape_agrees"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  double min_odds_;
};

// name_by_shape: a labelled object is named by both recognizers (recognition/category_naming.h):
// the category classifier's posterior for its points and its full models' categories and
// objectness (an unfinished object's M(r), a completed object's own model). A new name brings the
// best model of that category when there is one. The paper names the best model's category; with a
// few real models per category the nearest instance is often another category's.
class NameByShapeRule : public ReportRule {
 public:
  // scope and adopt_model: ReportOptions::name_scope, name_adopts_model.
  explicit NameByShapeRule(std::string scope = "all", bool adopt_model = true)
      : scope_(std::move(scope)), adopt_model_(adopt_model) {}
  const char* name() const override { return "name_by_shape"; }
  void Apply(const ReportContext& context, ReportedObjects* objects) const override;

 private:
  std::string scope_;
  bool adopt_model_;
};

// The rule named `name` with its options from `options`; null for an unknown name.
std::unique_ptr<ReportRule> MakeReportRule(const std::string& name, const ReportOptions& options);

// The size of what was seen of object i as the size rules measure it: its grouped points away from
// the walls (size_regrouping.h, PointsAwayFromWalls), trimmed (MeasureObjectExtent).
recognition::ObjectExtent MeasureReportedExtent(const ReportContext& context, const ReportedObjects& objects,
                                                std::size_t i, const recognition::SizePlausibilityOptions& options);

}  // namespace objscan::scanning
