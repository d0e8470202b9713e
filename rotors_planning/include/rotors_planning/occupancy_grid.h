// The occupied leaves of an OctoMap inside a box, as a dense voxel grid for fast clearance queries
// (a planner asks millions of times "is any occupied leaf closer than r to p?"). Cells are the
// octree's own cells (same resolution, aligned at the origin); space outside the box or not
// occupied in the tree (free or unknown) counts as free: the planner treats unknown as free.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace octomap {
class OcTree;
}

namespace rotors_planning {

class OccupancyGrid {
 public:
  /// The occupied leaves of `tree` whose cells overlap [min_W, max_W]. Throws std::invalid_argument
  /// for an empty box or one over 2^31 cells.
  OccupancyGrid(const octomap::OcTree& tree, const Eigen::Vector3d& min_W, const Eigen::Vector3d& max_W);

  double Resolution_m() const { return resolution_m_; }
  const Eigen::Vector3d& Min_W() const { return min_W_; }
  const Eigen::Vector3d& Max_W() const { return max_W_; }
  size_t OccupiedCount() const { return occupied_count_; }
  bool Contains(const Eigen::Vector3d& p_W) const;

  /// Distance from p to the nearest occupied cell (0 inside one), searched up to `search_m`;
  /// returns search_m when nothing occupied is that close.
  double Clearance_m(const Eigen::Vector3d& p_W, double search_m) const;
  /// Clearance_m(p) > radius_m: a sphere of radius_m around p touches no occupied cell.
  bool IsFree(const Eigen::Vector3d& p_W, double radius_m) const { return Clearance_m(p_W, radius_m) >= radius_m; }
  /// Every point of the segment a-b is free (sampled at a quarter of the resolution, each sample
  /// checked with the radius plus half a step).
  bool SegmentIsFree(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W, double radius_m) const;

 private:
  bool Occupied(int64_t i, int64_t j, int64_t k) const;

  double resolution_m_;
  Eigen::Vector3d min_W_, max_W_;
  Eigen::Vector3d origin_W_;  ///< [m] lower corner of cell (0, 0, 0), a multiple of the resolution
  int64_t nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<uint8_t> occupied_;
  size_t occupied_count_ = 0;
};

}  // namespace rotors_planning
