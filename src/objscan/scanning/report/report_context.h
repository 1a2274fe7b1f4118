#pragma once
// What the report rules may read besides the objects: the room's structure, the database's category
// sizes, and, through ReportSources, recognition and the map. Read-only for the rules, except that
// recognition may cache its answers.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "objscan/recognition/category_extent.h"
#include "objscan/recognition/category_naming.h"
#include "objscan/scanning/report/reported_objects.h"
#include "objscan/segmentation/post_matcher.h"
#include "objscan/world/category.h"

namespace objscan::mapping {
struct StructureResult;
}  // namespace objscan::mapping

namespace objscan::scanning {

// The seam between the report rules and the rest of the method (the scanner implements it; tests
// implement it on hand-made objects).
class ReportSources {
 public:
  virtual ~ReportSources() = default;
  // M(X) over full models for the union of these pre-segment components (ascending labels).
  virtual segmentation::MatchResult MatchFullModels(const std::vector<std::int32_t>& labels) = 0;
  // The best full model of `category` for the union; nullopt when there is none.
  virtual std::optional<segmentation::ModelMatch> BestOfCategory(const std::vector<std::int32_t>& labels,
                                                                 world::Category category) = 0;
  // The map points of these components: what the robot saw of them.
  virtual std::vector<Eigen::Vector3f> ComponentPoints(const std::vector<std::int32_t>& labels) const = 0;
  // The number of map elements carrying these labels outside the floor and walls.
  virtual std::size_t ElementCount(const std::vector<std::int32_t>& labels) const = 0;
  // The database model's name ("" for model_id < 0).
  virtual std::string ModelName(int model_id) const = 0;
  // A database entry's points in its model frame (empty for none).
  virtual std::vector<Eigen::Vector3f> EntryPoints(int entry_id) const = 0;
  // The category classifier's odds for the union, P(k) / max_j P(j) per world::CategoryId k
  // (recognition::Recognizer::CategoryOdds); empty when there is no classifier or no description.
  virtual std::vector<float> CategoryOdds(const std::vector<std::int32_t>& /*labels*/) { return {}; }
  // The category recognition names the union by from the category classifier and `votes` (the
  // categories and scores of its models; recognition/category_naming.h); nullopt when it cannot
  // (no classifier, no description).
  virtual std::optional<world::Category> NameCategory(const std::vector<std::int32_t>& /*labels*/,
                                                      const std::vector<recognition::RetrievedCategory>& /*votes*/) {
    return std::nullopt;
  }
};

struct ReportContext {
  ReportSources* sources = nullptr;
  const mapping::StructureResult* structure = nullptr;
  // Per-category model sizes of the database (empty when no listed rule needs them).
  const recognition::CategoryExtents* category_extents = nullptr;

  // What the robot saw of object i: a completed object stands for its model, so its components'
  // points; an unfinished one, the points grouped into it.
  std::vector<Eigen::Vector3f> SeenPoints(const ReportedObjects& objects, std::size_t i) const {
    const ReportedObject& o = objects[i];
    return o.record.complete ? sources->ComponentPoints(o.record.labels) : o.points_world;
  }
};

}  // namespace objscan::scanning
