// A position-controlled motor (RotorS' motorType "position", the omav's tilt units), free of any
// engine: Gazebo's PID on the wrapped angle error, as RotorS' motor model drives a tilt joint.
#pragma once

#include <string>

namespace rotors_gazebo_plugins {

/// Gazebo's common::PID gains and limits (the <joint_control_pid> element: p, i, d, iMax, iMin,
/// cmdMax, cmdMin).
struct TiltServoParams {
  double p = 0.0;                       ///< [N m/rad]
  double i = 0.0;                       ///< [N m/(rad s)]
  double d = 0.0;                       ///< [N m s/rad]
  double i_max = 0.0, i_min = 0.0;      ///< limits of the integral term [N m]
  double cmd_max = 0.0, cmd_min = 0.0;  ///< limits of the torque [N m]
  /// Empty when valid, else one line naming the bad value and the fix.
  std::string Validate() const;
};

class TiltServoModel {
 public:
  explicit TiltServoModel(const TiltServoParams& params) : params_(params) {}

  /// e = wrap_[-pi, pi)(wrap_[0, 2pi)(theta) - wrap_[0, 2pi)(theta_ref)) (RotorS' error).
  static double AngleError(double theta_rad, double theta_ref_rad);

  /// Joint torque for the coming step of dt_s: tau = clamp(-(p e + clamp(i int e) + d de/dt)).
  double Torque(double theta_rad, double theta_ref_rad, double dt_s);

  void Reset() {
    integral_ = 0.0;
    previous_error_ = 0.0;
  }

 private:
  TiltServoParams params_;
  double integral_ = 0.0;        ///< [rad s] int e dt
  double previous_error_ = 0.0;  ///< [rad]
};

}  // namespace rotors_gazebo_plugins
