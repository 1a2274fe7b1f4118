#pragma once
// The objects a run reports, as the report stage (report_pipeline.h) reads and changes them after the
// loop: each object's record (label, model, pose, objectness), the surface points grouped into it, its
// full-model matches and the measurements the rules share. Rules change objects only through Join,
// Relabel, Adopt, Reopen and TakeLabel, and each change is written to the object's label_changes
// (run.json), so one list tells which rule did what.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "objscan/recognition/category_extent.h"
#include "objscan/scanning/run_record.h"
#include "objscan/segmentation/post_matcher.h"

namespace objscan::scanning {

struct ReportedObject {
  ObjectRecord record;
  // The map points grouped into this object: an unfinished object's own points; a completed object
  // starts with none (its model stands for it) and gains those of the pieces that join it.
  std::vector<Eigen::Vector3f> points_world;
  // Its size for the fragment rule when points_world is empty (a completed object's map elements).
  std::size_t num_elements = 0;
  // Its full-model matches at the end of the run, best first (null for a completed object).
  const segmentation::MatchResult* full_matches = nullptr;
  // The database entry of its model (record.model), -1 for none.
  int model_entry = -1;
  // The label a check took (TakeLabel), which the relabel rule may replace.
  std::optional<world::Category> taken;
  // Whether the wall-opening rule found it in a wall opening.
  bool in_wall_opening = false;
  // The object it joined (its index), or -1 while it is reported in its own right.
  int joined_into = -1;

  bool reported() const { return joined_into < 0; }
};

class ReportedObjects {
 public:
  ReportedObjects() = default;
  ReportedObjects(const ReportedObjects&) = delete;
  ReportedObjects& operator=(const ReportedObjects&) = delete;

  // Adds an object; returns its index.
  int Add(ReportedObject object);

  std::size_t size() const { return objects_.size(); }
  const ReportedObject& operator[](std::size_t i) const { return objects_[i]; }
  // Fields that are measurements, not provenance (wall_opening_share, height) may be written directly.
  ReportedObject& mutable_object(std::size_t i) { return objects_[i]; }

  // `from` is reported as part of `into` (both reported): its labels and points join into's, and it
  // leaves the report.
  void Join(std::size_t from, std::size_t into, const std::string& rule);
  // Only the label changes (nullopt: unrecognized).
  void Relabel(std::size_t i, const std::optional<world::Category>& to, const std::string& rule);
  // The object is reported as `match`: its category, model, pose and objectness.
  void Adopt(std::size_t i, const segmentation::ModelMatch& match, const std::string& model_name,
             const std::string& rule);
  // The label goes (the object is reported unrecognized) and is kept in `taken` for the relabel rule.
  void TakeLabel(std::size_t i, const std::string& rule);
  // A completed object is reported unfinished, recognized again from `matches` (owned from now on):
  // its best full model gives model, pose and objectness; the label stays until a rule changes it.
  void Reopen(std::size_t i, segmentation::MatchResult matches, std::vector<Eigen::Vector3f> seen_points_world,
              const std::string& best_model_name, const std::string& rule);

  // The records of the objects still reported, in order.
  std::vector<ObjectRecord> TakeReportedRecords();

 private:
  void Record(std::size_t i, LabelChange change);

  std::vector<ReportedObject> objects_;
  std::vector<std::unique_ptr<segmentation::MatchResult>> owned_matches_;
};

}  // namespace objscan::scanning
