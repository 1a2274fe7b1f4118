#pragma once
// Beyond the paper: pieces too small for their label join a neighbour. At the end of a run an object
// may still be in pieces (a night stand's drawer fronts, a lamp's shade apart from its stem), each
// recognized on its own as something it is too small to be. When joining a piece to an adjacent
// object gives an object whose size a model of that object's category has, the piece is part of it;
// two pieces that are both too small for their labels may together make one of them.
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "objscan/recognition/category_extent.h"
#include "objscan/world/category.h"

namespace objscan::mapping {
struct StructureResult;
}  // namespace objscan::mapping

namespace objscan::scanning {

struct RegroupCandidate {
  std::vector<Eigen::Vector3f> points_world;
  std::optional<world::Category> category;  // nullopt: unrecognized (never a host, never moves)
  bool fixed = false;                       // replaced by its model: never moves, never a host
};

struct RegroupResult {
  std::vector<int> host;                                // per object: the object it joined (itself if none)
  std::vector<std::optional<world::Category>> category; // per object: its category after regrouping
  // Per object: its points with those of the pieces that joined it (empty for an object that joined).
  std::vector<std::vector<Eigen::Vector3f>> points_world;
  int merges = 0;
};

// Greedy and deterministic: repeatedly, the smallest object implausible for its category joins the
// adjacent object (`adjacency`: index pairs) with the most points among those whose union is
// plausible for the host's category, or, when the host is implausible too, for the first category
// of `recognize(members)` (the union's recognized categories, best first; members are indices into
// `objects`) that it fits. Without `recognize`, the piece's own label is the only other choice. A
// plausible host with fewer points than the piece is instead a part of it (a table's legs apart from
// its top) when the union fits the piece's label: the host then joins the piece, unless another
// neighbour takes the piece by the rules before. When the union fits both the host's label and the
// piece's and the host is plausible and smaller, the piece's label names it (the host joins the piece).
using RecognizeUnion = std::function<std::vector<world::Category>(const std::vector<int>& members)>;
RegroupResult RegroupImplausibleFragments(const std::vector<RegroupCandidate>& objects,
                                          const std::vector<std::pair<int, int>>& adjacency,
                                          const recognition::CategoryExtents& extents,
                                          const recognition::SizePlausibilityOptions& options,
                                          const RecognizeUnion& recognize = nullptr);

// Beyond the regrouping, for pieces plausible on their own: of two labelled pieces of which one stands
// under the other (ObjectsStandingUnder), the one with fewer points joins the other when the union
// fits the larger one's label, which then names it: a lamp's shade recognized as a radio over its
// stem and base, a chair's legs recognized as a night stand under its seat. Unlabelled and fixed
// pieces never join, nor do windows, doors and curtains (they hang in or on walls, and furniture
// stands in front of them). One pass over the pairs, in order; a piece joins at most once.
RegroupResult JoinStackedPieces(const std::vector<RegroupCandidate>& objects, double max_gap_m, double margin_m,
                                const recognition::CategoryExtents& extents,
                                const recognition::SizePlausibilityOptions& options);

// Index pairs (i < j) of objects with points within about `distance_m` of each other (points in the
// same or neighbouring cells of a grid of that size).
std::vector<std::pair<int, int>> ObjectsWithinDistance(const std::vector<std::vector<Eigen::Vector3f>>& points_world,
                                                       double distance_m);

// Index pairs (i < j) of objects of which one stands under the other: the lower one's footprint
// (axis-aligned, grown by `margin_m`) lies within the upper one's and its top is at most `max_gap_m`
// below the upper one's bottom (and not above the upper one's middle). A table top seen from above
// and its legs or pedestal are apart by the underside no camera saw (5-15 cm); they are adjacent for
// the regrouping all the same.
std::vector<std::pair<int, int>> ObjectsStandingUnder(const std::vector<std::vector<Eigen::Vector3f>>& points_world,
                                                      double max_gap_m, double margin_m);

// The points an object's size is measured on (size_check.wall_margin_m): those farther than
// wall_margin_m from every detected wall plane (within its span), or all of them when that leaves
// fewer than half (a door, a window or a curtain lies along its wall) or when wall_margin_m <= 0.
std::vector<Eigen::Vector3f> PointsAwayFromWalls(const std::vector<Eigen::Vector3f>& points,
                                                 const mapping::StructureResult& structure, double wall_margin_m);

}  // namespace objscan::scanning
