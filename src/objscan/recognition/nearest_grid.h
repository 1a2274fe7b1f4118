#pragma once
// Exact nearest-neighbour lookups near a point set by a regular grid of cells, each listing the
// points that can be the nearest one anywhere in the cell (a superset of the Voronoi cells it
// touches). A lookup is a cell index and a scan of a handful of points, no tree descent: the ICP
// correspondences of alignment, where the same few hundred item points are searched thousands of
// times by query points lying close to them. Cells farther than `band_m` from every point have no
// list (Find returns -1 there; callers fall back to a kd-tree).
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace objscan::recognition {

class NearestGrid {
 public:
  NearestGrid() = default;
  // Cells cover the points' bounds grown by band_m; at most max_cells cells (the cell size grows to
  // fit), cell size at least min_cell_m. A cell gets a list when some point is within band_m of all
  // of it. Empty for no points, band_m <= 0, max_cells < 1 or more than 65535 points.
  NearestGrid(const std::vector<Eigen::Vector3f>& points, float band_m, int max_cells, float min_cell_m);

  bool empty() const { return cell_begin_.empty(); }
  float cell_m() const { return cell_m_; }
  std::size_t num_cells() const { return cell_begin_.empty() ? 0 : cell_begin_.size() - 1; }
  std::size_t num_candidates() const { return candidates_.size(); }
  std::size_t memory_bytes() const {
    return cell_begin_.size() * sizeof(std::uint32_t) + candidates_.size() * sizeof(std::uint16_t) +
           points_.size() * sizeof(Eigen::Vector3f);
  }

  // Index (into the constructor's points) of the point nearest to q and its squared distance, exact
  // up to float rounding (ties go to the lower index); -1 when q's cell has no list.
  int Find(const Eigen::Vector3f& q, float* squared_distance) const {
    std::uint32_t begin = 0, end = 0;
    CellRange(q, &begin, &end);
    return Scan(q, begin, end, squared_distance);
  }

  // Find in two steps, so a caller with many queries can look up all their cells before scanning
  // any (independent memory reads the processor overlaps): the candidate range of q's cell (empty
  // when it has no list), then the scan of that range.
  void CellRange(const Eigen::Vector3f& q, std::uint32_t* begin, std::uint32_t* end) const {
    const Eigen::Vector3f g = (q - origin_) * inv_cell_m_;
    if (!(g.x() >= 0.f && g.y() >= 0.f && g.z() >= 0.f && g.x() < static_cast<float>(nx_) &&
          g.y() < static_cast<float>(ny_) && g.z() < static_cast<float>(nz_))) {
      *begin = *end = 0;
      return;
    }
    const std::size_t c = (static_cast<std::size_t>(g.z()) * ny_ + static_cast<std::size_t>(g.y())) * nx_ +
                          static_cast<std::size_t>(g.x());
    *begin = cell_begin_[c];
    *end = cell_begin_[c + 1];
  }
  int Scan(const Eigen::Vector3f& q, std::uint32_t begin, std::uint32_t end, float* squared_distance) const {
    int best = -1;
    float best_d2 = std::numeric_limits<float>::infinity();
    for (std::uint32_t k = begin; k < end; ++k) {
      const int i = candidates_[k];
      const Eigen::Vector3f& p = points_[i];
      const float dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
      const float d2 = dx * dx + dy * dy + dz * dz;
      // Selects rather than branches: which candidate wins is unpredictable.
      const bool closer = d2 < best_d2;
      best = closer ? i : best;
      best_d2 = closer ? d2 : best_d2;
    }
    *squared_distance = best_d2;
    return best;
  }

 private:
  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();  // low corner of cell (0, 0, 0)
  float cell_m_ = 0.f, inv_cell_m_ = 0.f;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<Eigen::Vector3f> points_;
  std::vector<std::uint32_t> cell_begin_;  // cell c lists candidates_[cell_begin_[c], cell_begin_[c + 1])
  std::vector<std::uint16_t> candidates_;  // point indices, ascending within a cell
};

}  // namespace objscan::recognition
