// Lee position controller on SE(3) (reference section 7.2), with the upstream defects fixed:
// the rate error uses R^T R_d (Lee's convention) and the gyroscopic term is w x J w.
#pragma once

#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/motor_mixer.h"

namespace rotors_control {

struct LeePositionControllerParameters {
  Eigen::Vector3d position_gain{6.0, 6.0, 6.0};   ///< K_p [N/m]
  Eigen::Vector3d velocity_gain{4.7, 4.7, 4.7};   ///< K_v [N s/m]
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
  TrajectoryPoint reference_;
  bool has_reference_ = false;
};

}  // namespace rotors_control
