#include "rotors_planning/trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rotors_planning {
namespace {
constexpr double kPeakSpeed = 15.0 / 8.0;                // max ds/dtau of the quintic profile
const double kPeakAcceleration = 10.0 / std::sqrt(3.0);  // max |d2s/dtau2|
}  // namespace

std::string TrajectoryLimits::Validate() const {
  std::ostringstream why;
  if (!(max_speed_mps > 0.0)) {
    why << "max_speed = " << max_speed_mps << " must be > 0 m/s";
  } else if (!(max_acceleration_mps2 > 0.0)) {
    why << "max_acceleration = " << max_acceleration_mps2 << " must be > 0 m/s^2";
  } else if (!(max_yaw_rate_radps > 0.0)) {
    why << "max_yaw_rate = " << max_yaw_rate_radps << " must be > 0 rad/s";
  }
  return why.str();
}

Eigen::Vector3d MinimumJerkProfile(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  const double t2 = tau * tau, t3 = t2 * tau;
  return {t3 * (10.0 - 15.0 * tau + 6.0 * t2), 30.0 * t2 * (1.0 - 2.0 * tau + t2),
          60.0 * tau * (1.0 - 3.0 * tau + 2.0 * t2)};
}

RestToRestTrajectory::RestToRestTrajectory(const std::vector<Eigen::Vector3d>& path_W, double yaw_start_rad,
                                           double yaw_goal_rad, const TrajectoryLimits& limits)
    : path_W_(path_W), end_times_s_{0.0}, yaw_shares_{0.0}, yaw_start_rad_(yaw_start_rad) {
  if (path_W.size() < 2) throw std::invalid_argument("a trajectory needs at least two vertices");
  const std::string why = limits.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
  yaw_delta_rad_ = std::remainder(yaw_goal_rad - yaw_start_rad, 2.0 * M_PI);
  double total_m = 0.0;
  for (size_t i = 1; i < path_W.size(); ++i) total_m += (path_W[i] - path_W[i - 1]).norm();
  for (size_t i = 1; i < path_W.size(); ++i) {
    const double length_m = (path_W[i] - path_W[i - 1]).norm();
    // v_peak = 15/8 L/T <= v_max and a_peak = 10/sqrt(3) L/T^2 <= a_max; yaw turns in proportion
    const double yaw_rad = total_m > 0.0 ? std::abs(yaw_delta_rad_) * length_m / total_m : std::abs(yaw_delta_rad_);
    const double T = std::max({kPeakSpeed * length_m / limits.max_speed_mps,
                               std::sqrt(kPeakAcceleration * length_m / limits.max_acceleration_mps2),
                               kPeakSpeed * yaw_rad / limits.max_yaw_rate_radps, 1e-3});
    end_times_s_.push_back(end_times_s_.back() + T);
    yaw_shares_.push_back(yaw_shares_.back() + (total_m > 0.0 ? length_m / total_m : 1.0 / (path_W.size() - 1)));
  }
}

TrajectorySample RestToRestTrajectory::Sample(double t_s) const {
  t_s = std::clamp(t_s, 0.0, Duration_s());
  const size_t edge = std::min<size_t>(
      std::upper_bound(end_times_s_.begin(), end_times_s_.end(), t_s) - end_times_s_.begin(), end_times_s_.size() - 1);
  const double t0 = end_times_s_[edge - 1], T = end_times_s_[edge] - t0;
  const Eigen::Vector3d s = MinimumJerkProfile((t_s - t0) / T);
  const Eigen::Vector3d delta = path_W_[edge] - path_W_[edge - 1];
  TrajectorySample out;
  // p(t) = p_a + s(tau) (p_b - p_a), tau = (t - t0) / T
  out.p_W = path_W_[edge - 1] + s[0] * delta;
  out.v_W = s[1] / T * delta;
  out.a_W = s[2] / (T * T) * delta;
  // yaw spread over the edges in proportion to their length, with the same profile
  const double share0 = yaw_shares_[edge - 1], share = yaw_shares_[edge] - share0;
  out.yaw_rad = std::remainder(yaw_start_rad_ + yaw_delta_rad_ * (share0 + share * s[0]), 2.0 * M_PI);
  out.yaw_rate_radps = yaw_delta_rad_ * share * s[1] / T;
  return out;
}

}  // namespace rotors_planning
