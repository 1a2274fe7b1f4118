#include "objscan/recognition/nearest_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "objscan/recognition/grid_fit.h"

namespace objscan::recognition {
namespace {

// Per axis, for the cells [lo, hi] near coordinate p: the squared gap from p to each cell (0 inside)
// and the squared distance to its far face.
struct AxisRange {
  int lo = 0, hi = -1;
  float gap2[64];
  float far2[64];
};

}  // namespace

NearestGrid::NearestGrid(const std::vector<Eigen::Vector3f>& points, float band_m, int max_cells,
                         float min_cell_m) {
  if (points.empty() || points.size() > 65535 || !(band_m > 0.f) || max_cells < 1) return;
  // A cell must not be smaller than band / 30 so a point's reach fits AxisRange.
  const GridFit fit = FitGrid(points, band_m, max_cells, std::max(min_cell_m, band_m / 30.f), 1);
  const float cell = fit.spacing_m;
  nx_ = fit.nx;
  ny_ = fit.ny;
  nz_ = fit.nz;
  origin_ = fit.origin;
  cell_m_ = cell;
  inv_cell_m_ = 1.f / cell;
  points_ = points;
  const std::size_t num_cells = static_cast<std::size_t>(nx_) * ny_ * nz_;
  const int dims[3] = {nx_, ny_, nz_};

  // Visits the cells within `reach` (per axis) of point p with their squared gap and far distance.
  const auto for_cells_near = [&](const Eigen::Vector3f& p, float reach, auto&& visit) {
    AxisRange axis[3];
    for (int d = 0; d < 3; ++d) {
      AxisRange& a = axis[d];
      a.lo = std::max(0, static_cast<int>(std::floor((p[d] - reach - origin_[d]) * inv_cell_m_)));
      a.hi = std::min({dims[d] - 1, static_cast<int>(std::floor((p[d] + reach - origin_[d]) * inv_cell_m_)),
                       a.lo + 63});
      for (int i = a.lo; i <= a.hi; ++i) {
        const float c0 = origin_[d] + i * cell, c1 = c0 + cell;
        const float gap = std::max({0.f, c0 - p[d], p[d] - c1});
        const float far = std::max(p[d] - c0, c1 - p[d]);
        a.gap2[i - a.lo] = gap * gap;
        a.far2[i - a.lo] = far * far;
      }
    }
    const float reach2 = reach * reach;
    for (int z = axis[2].lo; z <= axis[2].hi; ++z) {
      for (int y = axis[1].lo; y <= axis[1].hi; ++y) {
        const float gap_yz = axis[1].gap2[y - axis[1].lo] + axis[2].gap2[z - axis[2].lo];
        if (gap_yz > reach2) continue;  // the whole row is out of reach
        const float far_yz = axis[1].far2[y - axis[1].lo] + axis[2].far2[z - axis[2].lo];
        const std::size_t row = (static_cast<std::size_t>(z) * ny_ + y) * nx_;
        for (int x = axis[0].lo; x <= axis[0].hi; ++x) {
          const float gap2 = gap_yz + axis[0].gap2[x - axis[0].lo];
          if (gap2 > reach2) continue;
          visit(row + x, x, y, z, gap2, far_yz + axis[0].far2[x - axis[0].lo]);
        }
      }
    }
  };

  // bound2[c]: the least, over the points, of the squared distance to the farthest corner of the
  // cell, reached by point anchor[c]: the nearest point of any q in the cell is at most that far, so
  // only points whose gap to the cell is within it can be nearest there. Exact when it is within the
  // band (the minimising point then lies within the band of the whole cell, so it was visited).
  const float band2 = band_m * band_m;
  std::vector<float> bound2(num_cells, std::numeric_limits<float>::infinity());
  std::vector<int> anchor(num_cells, -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int index = static_cast<int>(i);
    for_cells_near(points[i], band_m, [&](std::size_t c, int, int, int, float, float far2) {
      // Selects rather than branches: which point wins is unpredictable.
      const bool closer = far2 < bound2[c];
      anchor[c] = closer ? index : anchor[c];
      bound2[c] = closer ? far2 : bound2[c];
    });
  }
  // A little slack for rounding (q's cell is found by a float floor, distances in float).
  for (float& b : bound2) b = b <= band2 ? b * 1.0001f + 1e-10f : -1.f;
  const float half = 0.5f * cell;
  const float slack = 1e-4f * cell + 1e-6f;
  // Point i can be nearest somewhere in cell c only if its gap to the cell is within the bound and
  // some q in the cell is at least as close to it as to the anchor (its side of their bisector
  // plane meets the cell).
  const auto candidate = [&](int i, std::size_t c, int x, int y, int z, float gap2) {
    if (!(gap2 <= bound2[c])) return false;
    // Plain float arithmetic: this runs for every (point, cell) pair that passes the gap test.
    const Eigen::Vector3f& p = points_[i];
    const Eigen::Vector3f& a = points_[anchor[c]];
    const float nx = p.x() - a.x(), ny = p.y() - a.y(), nz = p.z() - a.z();
    const float cx = origin_.x() + (x + 0.5f) * cell - 0.5f * (p.x() + a.x());
    const float cy = origin_.y() + (y + 0.5f) * cell - 0.5f * (p.y() + a.y());
    const float cz = origin_.z() + (z + 0.5f) * cell - 0.5f * (p.z() + a.z());
    const float l1 = std::abs(nx) + std::abs(ny) + std::abs(nz);
    return nx * cx + ny * cy + nz * cz + (half + slack) * l1 >= 0.f;
  };
  const float reach = band_m * 1.001f;
  // (cell, point) pairs in point order, then sorted by cell (stably: ascending points per cell).
  std::vector<std::pair<std::uint32_t, std::uint16_t>> pairs;
  pairs.reserve(points.size() * 8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for_cells_near(points[i], reach, [&](std::size_t c, int x, int y, int z, float gap2, float) {
      if (candidate(static_cast<int>(i), c, x, y, z, gap2))
        pairs.emplace_back(static_cast<std::uint32_t>(c), static_cast<std::uint16_t>(i));
    });
  }
  cell_begin_.assign(num_cells + 1, 0);
  for (const auto& [c, i] : pairs) ++cell_begin_[c + 1];
  for (std::size_t c = 0; c < num_cells; ++c) cell_begin_[c + 1] += cell_begin_[c];
  candidates_.resize(pairs.size());
  std::vector<std::uint32_t> next(cell_begin_.begin(), cell_begin_.end() - 1);
  for (const auto& [c, i] : pairs) candidates_[next[c]++] = i;
}

}  // namespace objscan::recognition
