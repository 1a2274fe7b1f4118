#include "objscan/scanning/report/reported_objects.h"

#include <algorithm>

#include "objscan/common/error.h"

namespace objscan::scanning {

int ReportedObjects::Add(ReportedObject object) {
  objects_.push_back(std::move(object));
  return static_cast<int>(objects_.size()) - 1;
}

void ReportedObjects::Record(std::size_t i, LabelChange change) {
  objects_[i].record.label_changes.push_back(std::move(change));
}

void ReportedObjects::Join(std::size_t from, std::size_t into, const std::string& rule) {
  if (from == into || from >= objects_.size() || into >= objects_.size() || !objects_[from].reported() ||
      !objects_[into].reported()) {
    throw std::logic_error("ReportedObjects::Join: both objects must be reported and distinct");
  }
  ReportedObject& f = objects_[from];
  ReportedObject& t = objects_[into];
  auto& labels = t.record.labels;
  labels.insert(labels.end(), f.record.labels.begin(), f.record.labels.end());
  std::sort(labels.begin(), labels.end());
  t.points_world.insert(t.points_world.end(), f.points_world.begin(), f.points_world.end());
  f.points_world.clear();
  f.points_world.shrink_to_fit();
  f.joined_into = static_cast<int>(into);
  LabelChange c;
  c.rule = rule;
  c.action = "join";
  c.from = t.record.category;
  c.to = t.record.category;
  c.joined_id = f.record.id;
  Record(into, std::move(c));
}

void ReportedObjects::Relabel(std::size_t i, const std::optional<world::Category>& to, const std::string& rule) {
  ObjectRecord& o = objects_[i].record;
  if (o.category == to) return;
  LabelChange c;
  c.rule = rule;
  c.action = "relabel";
  c.from = o.category;
  c.to = to;
  o.category = to;
  Record(i, std::move(c));
}

void ReportedObjects::Adopt(std::size_t i, const segmentation::ModelMatch& match, const std::string& model_name,
                            const std::string& rule) {
  ObjectRecord& o = objects_[i].record;
  LabelChange c;
  c.rule = rule;
  c.action = "adopt";
  c.from = o.category;
  c.to = match.category;
  c.model = model_name;
  o.category = match.category;
  o.model_index = match.model_id;
  o.model = model_name;
  o.T_world_model = match.T_world_model;
  o.objectness = match.objectness;
  objects_[i].model_entry = match.entry_id;
  Record(i, std::move(c));
}

void ReportedObjects::TakeLabel(std::size_t i, const std::string& rule) {
  ObjectRecord& o = objects_[i].record;
  if (!o.category) return;
  LabelChange c;
  c.rule = rule;
  c.action = "take";
  c.from = o.category;
  objects_[i].taken = o.category;
  o.category.reset();
  Record(i, std::move(c));
}

void ReportedObjects::Reopen(std::size_t i, segmentation::MatchResult matches,
                             std::vector<Eigen::Vector3f> seen_points_world, const std::string& best_model_name,
                             const std::string& rule) {
  ReportedObject& r = objects_[i];
  ObjectRecord& o = r.record;
  LabelChange c;
  c.rule = rule;
  c.action = "reopen";
  c.from = o.category;
  c.to = o.category;
  c.model = o.model;
  o.complete = false;
  owned_matches_.push_back(std::make_unique<segmentation::MatchResult>(std::move(matches)));
  r.full_matches = owned_matches_.back().get();
  r.model_entry = -1;  // none unless the new matches name one
  if (!r.full_matches->models.empty()) {
    const segmentation::ModelMatch& best = r.full_matches->models.front();
    o.model_index = best.model_id;
    o.model = best_model_name;
    o.T_world_model = best.T_world_model;
    o.objectness = best.objectness;
    r.model_entry = best.entry_id;
  }
  r.points_world = std::move(seen_points_world);
  r.num_elements = 0;
  Record(i, std::move(c));
}

std::vector<ObjectRecord> ReportedObjects::TakeReportedRecords() {
  std::vector<ObjectRecord> out;
  for (ReportedObject& r : objects_) {
    if (r.reported()) out.push_back(std::move(r.record));
  }
  return out;
}

}  // namespace objscan::scanning
