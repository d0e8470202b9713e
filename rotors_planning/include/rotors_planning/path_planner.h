// Collision-free paths through an occupancy map with OMPL's RRT-Connect in R^3 (position only; a
// multirotor turns in place), shortened greedily by line of sight. A path keeps `clearance_m`
// (the vehicle's radius plus a margin) from every occupied cell; unknown space is free.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rotors_planning/occupancy_grid.h"

namespace rotors_planning {

struct PathPlannerParams {
  double radius_m = 0.3;         ///< [m] the vehicle's radius (from its URDF)
  double margin_m = 0.25;        ///< [m] kept on top of the radius
  double planning_time_s = 2.0;  ///< [s] RRT-Connect's budget per query
  double escape_m = 1.5;         ///< [m] how far a start closer than the clearance may move out first
  unsigned int seed = 1;         ///< OMPL's seed, set once per process (0: OMPL picks one)
  double Clearance_m() const { return radius_m + margin_m; }
  std::string Validate() const;  ///< empty when valid, else a one-line reason
};

struct PlannedPath {
  bool ok = false;
  std::string reason;                ///< why not, one line, when !ok
  std::vector<Eigen::Vector3d> p_W;  ///< [m] vertices from start to goal
  size_t raw_vertices = 0;           ///< RRT-Connect's path before shortening (2: a straight line)
  double planning_time_s = 0.0;      ///< [s] wall time of the query
};

class PathPlanner {
 public:
  /// Throws std::invalid_argument with Validate()'s reason.
  explicit PathPlanner(const PathPlannerParams& params);

  /// A path from start to goal inside the grid's box. A start below the box's floor (a vehicle on
  /// the ground) climbs vertically to it first; a start closer than the clearance to an obstacle
  /// moves out to the nearest free point within escape_m first. Never throws for bad goals: the
  /// reason says what is wrong with them.
  PlannedPath Plan(const OccupancyGrid& grid, const Eigen::Vector3d& start_W, const Eigen::Vector3d& goal_W) const;

  const PathPlannerParams& Params() const { return params_; }

 private:
  std::vector<Eigen::Vector3d> Search(const OccupancyGrid& grid, const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W,
                                      size_t* raw_vertices) const;
  bool Escape(const OccupancyGrid& grid, const Eigen::Vector3d& start_W, Eigen::Vector3d* free_W) const;

  PathPlannerParams params_;
};

/// The path's vertices shortened greedily: from each kept vertex, straight to the farthest later
/// vertex in line of sight (keeping clearance_m).
std::vector<Eigen::Vector3d> Shortcut(const OccupancyGrid& grid, const std::vector<Eigen::Vector3d>& path_W,
                                      double clearance_m);

}  // namespace rotors_planning
