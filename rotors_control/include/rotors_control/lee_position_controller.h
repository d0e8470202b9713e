// Lee position controller on SE(3) (reference section 7.2), with the upstream defects fixed:
// the rate error uses R^T R_d (Lee's convention) and the gyroscopic term is w x J w.
#pragma once

#include <cmath>
#include <limits>
#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/motor_mixer.h"

namespace rotors_control {

/// The upward part of a saturated desired acceleration is at least this fraction of g.
constexpr double kMinUpwardAccelerationFraction = 0.2;

struct LeePositionControllerParameters {
  Eigen::Vector3d position_gain{6.0, 6.0, 6.0};   ///< K_p [N/m]
  Eigen::Vector3d velocity_gain{4.7, 4.7, 4.7};   ///< K_v [N s/m]
  /// Ours (RotorS issue #456): the desired acceleration is tilted at most this far from vertical.
  /// With it, or with max_rot_velocity on every rotor (the thrust limit), the desired acceleration
  /// is saturated with vertical priority (SaturatedAcceleration). 0 and no max_rot_velocity: RotorS.
  double max_tilt_angle_rad = 0.0;
  AttitudeGains attitude;
  VehicleParameters vehicle;
  std::string Validate() const;
};

/// State from odometry: position and attitude in the world, velocities in the body frame.
struct VehicleState {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation_W_B = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_B = Eigen::Vector3d::Zero();
};

/// A reference point: position, velocity, acceleration (world), yaw and yaw rate.
struct TrajectoryPoint {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  double yaw_rate_rad_s = 0.0;
  bool IsFinite() const;
};

/// Limits of the desired acceleration (RotorS issue #456; vertical priority as PX4's position control).
struct AccelerationLimits {
  double max_tilt_rad = 0.0;                                      ///< 0: no tilt limit
  double max_m_s2 = std::numeric_limits<double>::infinity();      ///< all rotors at max_rot_velocity / m
  double min_up_m_s2 = 0.0;                                       ///< floor of the upward part
  bool Active() const { return max_tilt_rad > 0.0 || std::isfinite(max_m_s2); }
};

/// a_des with its upward part clamped to [min_up, max] first, then its horizontal part shortened
/// (direction kept) to what the tilt limit and the remaining thrust allow.
Eigen::Vector3d SaturatedAcceleration(const Eigen::Vector3d& a_des_W, const AccelerationLimits& limits);

class LeePositionController {
 public:
  /// Throws std::invalid_argument naming the bad parameter.
  explicit LeePositionController(const LeePositionControllerParameters& params);

  void SetTrajectoryPoint(const TrajectoryPoint& point);
  bool HasReference() const { return has_reference_; }
  /// Rotor speeds [rad/s]; zeros until the first reference (the rotors stay stopped).
  Eigen::VectorXd RotorSpeeds(const VehicleState& state) const;
  /// The thrust [N] and desired attitude of the last RotorSpeeds() call (diagnostics/tests).
  void ComputeThrustAndAttitude(const VehicleState& state, double* thrust_N, Eigen::Matrix3d* R_WD) const;

 private:
  LeePositionControllerParameters params_;
  AttitudeControlLaw attitude_law_;
  MotorMixer mixer_;
  AccelerationLimits limits_;
  TrajectoryPoint reference_;
  bool has_reference_ = false;
};

}  // namespace rotors_control
