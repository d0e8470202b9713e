// The lower command levels of the seed: roll-pitch-yawrate-thrust (reference section 7.3),
// attitude-thrust and rate-thrust. Thrust commands are in newtons, passed straight through.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/motor_mixer.h"

namespace rotors_control {

struct AttitudeControllerParameters {
  AttitudeGains attitude;
  MultirotorParameters vehicle;
};

class AttitudeLevelController {
 public:
  explicit AttitudeLevelController(const AttitudeControllerParameters& params);

  /// Roll and pitch [rad] and yaw rate [rad/s]: R_d = Rz(yaw) Ry(pitch) Rx(roll) (z-y'-x'', the
  /// mav_msgs convention) with yaw the current yaw; w_d = (0, 0, yaw_rate).
  void SetRollPitchYawrateThrust(double roll, double pitch, double yaw_rate, double thrust_N);
  /// Desired attitude and thrust; w_d = 0.
  void SetAttitudeThrust(const Eigen::Quaterniond& q_WD, double thrust_N);
  /// Desired body rates [rad/s] and thrust.
  void SetRateThrust(const Eigen::Vector3d& omega_des_B, double thrust_N);
  bool HasCommand() const { return mode_ != Mode::kNone; }
  RotorVector RotorSpeeds(const VehicleState& state) const;

 private:
  enum class Mode { kNone, kRollPitchYawrate, kAttitude, kRate };
  AttitudeControlLaw law_;
  MotorMixer mixer_;
  Mode mode_ = Mode::kNone;
  double roll_ = 0, pitch_ = 0, yaw_rate_ = 0, thrust_N_ = 0;
  Eigen::Quaterniond q_WD_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d omega_des_B_ = Eigen::Vector3d::Zero();
};

}  // namespace rotors_control
