#include "rotors_planning/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <octomap/OcTree.h>

namespace rotors_planning {

OccupancyGrid::OccupancyGrid(const octomap::OcTree& tree, const Eigen::Vector3d& min_W, const Eigen::Vector3d& max_W)
    : resolution_m_(tree.getResolution()), min_W_(min_W), max_W_(max_W) {
  if (!((max_W - min_W).array() > 0.0).all()) {
    throw std::invalid_argument("the map box is empty: min must be below max on every axis");
  }
  // cells of the octree are [k r, (k+1) r) on each axis
  origin_W_ = (min_W / resolution_m_).array().floor().matrix() * resolution_m_;
  const Eigen::Vector3d cells = ((max_W - origin_W_) / resolution_m_).array().ceil();
  if (cells.prod() > 2147483648.0) throw std::invalid_argument("the map box holds over 2^31 cells at this resolution");
  nx_ = static_cast<int64_t>(cells.x());
  ny_ = static_cast<int64_t>(cells.y());
  nz_ = static_cast<int64_t>(cells.z());
  occupied_.assign(static_cast<size_t>(nx_ * ny_ * nz_), 0);
  const octomap::point3d lo(min_W.x(), min_W.y(), min_W.z()), hi(max_W.x(), max_W.y(), max_W.z());
  for (auto it = tree.begin_leafs_bbx(lo, hi), end = tree.end_leafs_bbx(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    // a leaf may be a coarser cube (pruned): mark every fine cell it covers
    const double half = 0.5 * it.getSize();
    const Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    const Eigen::Vector3d a = ((c.array() - half - origin_W_.array()) / resolution_m_).round();
    const Eigen::Vector3d b = ((c.array() + half - origin_W_.array()) / resolution_m_).round();
    for (int64_t i = std::max<int64_t>(0, a.x()); i < std::min<int64_t>(nx_, b.x()); ++i) {
      for (int64_t j = std::max<int64_t>(0, a.y()); j < std::min<int64_t>(ny_, b.y()); ++j) {
        for (int64_t k = std::max<int64_t>(0, a.z()); k < std::min<int64_t>(nz_, b.z()); ++k) {
          uint8_t& cell = occupied_[static_cast<size_t>((i * ny_ + j) * nz_ + k)];
          occupied_count_ += cell == 0;
          cell = 1;
        }
      }
    }
  }
}

bool OccupancyGrid::Contains(const Eigen::Vector3d& p_W) const {
  return (p_W.array() >= min_W_.array()).all() && (p_W.array() <= max_W_.array()).all();
}

bool OccupancyGrid::Occupied(int64_t i, int64_t j, int64_t k) const {
  if (i < 0 || j < 0 || k < 0 || i >= nx_ || j >= ny_ || k >= nz_) return false;
  return occupied_[static_cast<size_t>((i * ny_ + j) * nz_ + k)] != 0;
}

double OccupancyGrid::Clearance_m(const Eigen::Vector3d& p_W, double search_m) const {
  const Eigen::Vector3d q = (p_W - origin_W_) / resolution_m_;  // in cells
  const double reach = search_m / resolution_m_;
  const Eigen::Array3d lo = (q.array() - reach).floor(), hi = (q.array() + reach).floor();
  double best_sq = reach * reach;
  for (int64_t i = static_cast<int64_t>(lo.x()); i <= static_cast<int64_t>(hi.x()); ++i) {
    // distance from q to the unit cube [i, i+1] on one axis
    const double dx = std::max({0.0, i - q.x(), q.x() - (i + 1)});
    if (dx * dx >= best_sq) continue;
    for (int64_t j = static_cast<int64_t>(lo.y()); j <= static_cast<int64_t>(hi.y()); ++j) {
      const double dy = std::max({0.0, j - q.y(), q.y() - (j + 1)});
      if (dx * dx + dy * dy >= best_sq) continue;
      for (int64_t k = static_cast<int64_t>(lo.z()); k <= static_cast<int64_t>(hi.z()); ++k) {
        const double dz = std::max({0.0, k - q.z(), q.z() - (k + 1)});
        const double d_sq = dx * dx + dy * dy + dz * dz;
        if (d_sq < best_sq && Occupied(i, j, k)) best_sq = d_sq;
      }
    }
  }
  return std::sqrt(best_sq) * resolution_m_;
}

bool OccupancyGrid::SegmentIsFree(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W, double radius_m) const {
  const double length = (b_W - a_W).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.25 * resolution_m_))));
  // every point of the segment is within half a step of a sample, so its clearance is at least the
  // sample's minus half a step
  const double half_step_m = 0.5 * length / steps;
  for (int s = 0; s <= steps; ++s) {
    if (!IsFree(a_W + (b_W - a_W) * (static_cast<double>(s) / steps), radius_m + half_step_m)) return false;
  }
  return true;
}

}  // namespace rotors_planning
