// Lee position controller on SE(3) (reference section 7.2), with the upstream defects fixed:
// the rate error uses R^T R_d (Lee's convention) and the gyroscopic term is w x J w.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_law.h"
#include "rotors_control/motor_mixer.h"

namespace rotors_control {

/// The upward part of a saturated desired acceleration is at least this fraction of g.
constexpr double kMinUpwardAccelerationFraction = 0.2;

struct LeeControllerParameters {
  Eigen::Vector3d position_gain{6.0, 6.0, 6.0};  ///< K_p [N/m]
  Eigen::Vector3d velocity_gain{4.7, 4.7, 4.7};  ///< K_v [N s/m]
  /// Ours (RotorS issue #456): the desired acceleration is tilted at most this far from vertical.
  /// With it, or with max_rot_velocity on every rotor (the thrust limit), the desired acceleration
  /// is saturated with vertical priority (SaturatedAcceleration). 0 and no max_rot_velocity: RotorS.
  double max_tilt_angle_rad = 0.0;
  AttitudeGains attitude;
  MultirotorParameters vehicle;
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
  double max_tilt_rad = 0.0;                                  ///< 0: no tilt limit
  double max_m_s2 = std::numeric_limits<double>::infinity();  ///< all rotors at max_rot_velocity / m
  double min_up_m_s2 = 0.0;                                   ///< floor of the upward part
  bool Active() const { return max_tilt_rad > 0.0 || std::isfinite(max_m_s2); }
};

/// a_des with its upward part clamped to [min_up, max] first, then its horizontal part shortened
/// (direction kept) to what the tilt limit and the remaining thrust allow.
/// (law::SaturatedAcceleration, lee_law.h.)
Eigen::Vector3d SaturatedAcceleration(const Eigen::Vector3d& a_des_W, const AccelerationLimits& limits);

class LeeController {
 public:
  /// Throws std::invalid_argument naming the bad parameter.
  explicit LeeController(const LeeControllerParameters& params);

  void SetTrajectoryPoint(const TrajectoryPoint& point);
  /// Rotor `rotor` now turns at speed_factor times its command (a derated motor; 0: failed). The
  /// allocation models it with k_F s^2, so the other rotors take over its share (RotorS issue 511).
  /// With a rotor failed (0) the yaw reference is given up: the desired heading is the current one
  /// (a hexacopter on five rotors cannot make yaw torque of one sign; a yaw error that builds up
  /// would take Lee's SO(3) error towards pi, where it no longer holds roll and pitch).
  /// Returns "" or why the change was refused (the previous allocation is kept).
  std::string SetRotorSpeedFactor(size_t rotor, double speed_factor);
  bool YawReleased() const { return yaw_released_; }
  bool HasReference() const { return has_reference_; }
  /// Rotor speeds [rad/s]; zeros until the first reference (the rotors stay stopped).
  /// (law::LeeRotorSpeeds with this controller's constants and Inputs(state).)
  RotorVector RotorSpeeds(const VehicleState& state) const;
  /// The thrust [N] and desired attitude of the last RotorSpeeds() call (diagnostics/tests).
  void ComputeThrustAndAttitude(const VehicleState& state, double* thrust_N, Eigen::Matrix3d* R_WD) const;
  /// What the laws read (lee_law.h): the constants, and a step's inputs for `state` and the
  /// reference (a batch of vehicles steps many controllers' laws at once in lanes).
  const LeeConstantsT<double>& Constants() const { return constants_; }
  LeeInputsT<double> Inputs(const VehicleState& state) const;
  int Rotors() const { return mixer_.Rotors(); }

 private:
  void UpdateConstants();
  LeeControllerParameters params_;
  AttitudeControlLaw attitude_law_;
  MotorMixer mixer_;
  AccelerationLimits limits_;
  LeeConstantsT<double> constants_{};
  TrajectoryPoint reference_;
  Eigen::Vector3d b1_reference_ = Eigen::Vector3d::UnitX();  ///< (cos, sin, 0) of the reference's yaw
  bool has_reference_ = false;
  std::vector<double> nominal_force_constants_;  ///< k_F of each rotor when healthy
  std::vector<double> speed_factors_;            ///< 1 healthy, 0 failed
  bool yaw_released_ = false;                    ///< a rotor has failed: hold no yaw reference
};

}  // namespace rotors_control
