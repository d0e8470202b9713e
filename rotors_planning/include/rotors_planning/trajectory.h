// A smooth trajectory along a path: one quintic polynomial per edge, at rest at every vertex
// (piecewise polynomials as mav_trajectory_generation, with zero velocity and acceleration at the
// joints). The MAV stays on the checked straight edges exactly, so the path's clearance holds for
// the trajectory; position, velocity and acceleration are continuous.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_planning {

struct TrajectoryLimits {
  double max_speed_mps = 1.5;          ///< [m/s]
  double max_acceleration_mps2 = 1.5;  ///< [m/s^2]
  double max_yaw_rate_radps = 1.0;     ///< [rad/s]
  std::string Validate() const;        ///< empty when valid, else a one-line reason
};

struct TrajectorySample {
  Eigen::Vector3d p_W, v_W, a_W;  ///< [m], [m/s], [m/s^2]
  double yaw_rad = 0.0, yaw_rate_radps = 0.0;
};

class RestToRestTrajectory {
 public:
  /// One edge per pair of consecutive vertices; yaw goes from yaw_start to yaw_goal over the whole
  /// path (the shorter way). Each edge's duration is the shortest that keeps the limits.
  /// Throws std::invalid_argument for fewer than two vertices or invalid limits.
  RestToRestTrajectory(const std::vector<Eigen::Vector3d>& path_W, double yaw_start_rad, double yaw_goal_rad,
                       const TrajectoryLimits& limits);

  double Duration_s() const { return end_times_s_.back(); }
  TrajectorySample Sample(double t_s) const;

 private:
  std::vector<Eigen::Vector3d> path_W_;
  std::vector<double> end_times_s_;  ///< [s] end of each edge; the first entry (0) is the start
  std::vector<double> yaw_shares_;   ///< share of the yaw turn done at the end of each edge
  double yaw_start_rad_, yaw_delta_rad_;
};

/// Quintic rest-to-rest profile s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 on tau in [0, 1]: returns
/// (s, ds/dtau, d2s/dtau2). Its peaks: ds/dtau = 15/8 at tau = 1/2, d2s/dtau2 = 10/sqrt(3).
Eigen::Vector3d MinimumJerkProfile(double tau);

}  // namespace rotors_planning
