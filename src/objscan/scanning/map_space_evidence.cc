#include "objscan/scanning/map_space_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace objscan::scanning {

MapSpaceEvidence::MapSpaceEvidence(const mapping::OccupancySnapshot& snapshot,
                                   const mapping::StructureResult& structure, const MapSpaceEvidenceOptions& options)
    : snapshot_(snapshot), structure_(structure), options_(options) {
  options_.Validate();
  const auto& s = snapshot_;
  impossible_.assign(s.cells.size(), 0);
  auto free_at = [&s](int x, int y, int z) {
    // Outside the snapshot nothing is known.
    return s.Contains(x, y, z) && s.cells[s.Index(x, y, z)] == mapping::Occupancy::kFree;
  };
  for (int z = 0; z < s.nz; ++z) {
    for (int y = 0; y < s.ny; ++y) {
      for (int x = 0; x < s.nx; ++x) {
        if (!free_at(x, y, z)) continue;
        if (options_.erode_free &&
            !(free_at(x - 1, y, z) && free_at(x + 1, y, z) && free_at(x, y - 1, z) && free_at(x, y + 1, z) &&
              free_at(x, y, z - 1) && free_at(x, y, z + 1))) {
          continue;
        }
        impossible_[s.Index(x, y, z)] = 1;
      }
    }
  }
}

bool MapSpaceEvidence::Impossible(const Eigen::Vector3f& p, const Eigen::Vector3f& query_center) const {
  std::size_t index = 0;
  if (snapshot_.IndexOf(p, &index) && impossible_[index]) return true;
  if (structure_.has_floor && p.z() < structure_.floor_height_m - options_.below_floor_m) return true;
  const Eigen::Vector3d pd = p.cast<double>(), cd = query_center.cast<double>();
  for (const mapping::WallPlane& w : structure_.walls) {
    if (w.SignedDistance(pd) >= -options_.behind_wall_m) continue;
    // The query itself beyond this wall (seen through a door): the wall says nothing about it.
    if (w.SignedDistance(cd) < -options_.behind_wall_m) continue;
    if (w.Spans(pd)) return true;
  }
  return false;
}

double MapSpaceEvidence::ImpossibleFraction(const std::vector<Eigen::Vector3f>& model_points_world,
                                            const Eigen::Vector3f& query_center_world) const {
  if (model_points_world.empty()) return 0.0;
  std::size_t n = 0;
  for (const auto& p : model_points_world) n += Impossible(p, query_center_world) ? 1 : 0;
  return static_cast<double>(n) / static_cast<double>(model_points_world.size());
}

double MapSpaceEvidence::SquaredDistanceToStructure(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d pd = p.cast<double>(), nd = n.cast<double>();
  const double c = options_.facing_min_cos;
  // Any face this near the floor lies in the band the floor's tags take (presegmentation.floor_prior),
  // where no object surface is kept. A wall's normal points into the room: a face resting against it
  // points the opposite way (faces turned to the room, as a window's in the wall plane, are seen).
  if (structure_.has_floor && options_.floor_is_structure) {
    best = std::pow(pd.z() - structure_.floor_height_m, 2);
  }
  for (const mapping::WallPlane& w : structure_.walls) {
    if (c > -1.0 && -nd.dot(w.normal) < c) continue;  // -1: any face
    if (w.Spans(pd)) best = std::min(best, std::pow(w.SignedDistance(pd), 2));
  }
  return best;
}

}  // namespace objscan::scanning
