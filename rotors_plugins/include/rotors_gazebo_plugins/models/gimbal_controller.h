// A three-axis camera gimbal's controller (RotorS' gazebo_gimbal_controller_plugin), free of any
// engine: the camera's attitude as Z-X-Y Euler angles (yaw, roll, pitch: R_WC = R_z(psi) R_x(phi)
// R_y(theta), the order of the gimbal's yaw, roll and pitch joints), each angle driven to its command
// by Gazebo's PID on the wrapped error (TiltServoModel), one torque per joint.
#pragma once

#include <Eigen/Core>

#include "rotors_gazebo_plugins/models/tilt_servo_model.h"

namespace rotors_gazebo_plugins {

struct GimbalParams {
  TiltServoParams yaw, roll, pitch;
  /// Empty when valid, else one line naming the axis and the bad value.
  std::string Validate() const;
};

class GimbalController {
 public:
  explicit GimbalController(const GimbalParams& params) : yaw_(params.yaw), roll_(params.roll), pitch_(params.pitch) {}

  /// (yaw, roll, pitch) [rad] of R_WC = R_z(yaw) R_x(roll) R_y(pitch); roll in [-pi/2, pi/2].
  static Eigen::Vector3d EulerZXY(const Eigen::Matrix3d& R_WC);

  /// Joint torques (yaw, roll, pitch) [N m] that drive the camera's angles to command_ypr [rad].
  Eigen::Vector3d Torques(const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& command_ypr, double dt_s);

  void Reset() {
    yaw_.Reset();
    roll_.Reset();
    pitch_.Reset();
  }

 private:
  TiltServoModel yaw_, roll_, pitch_;
};

}  // namespace rotors_gazebo_plugins
