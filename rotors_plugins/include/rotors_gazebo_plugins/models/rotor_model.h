// One rotor (book section 2.1, eqs. 1-5) with its speed dynamics, free of any engine: the motor
// plugin feeds it the rotor's state and applies what it returns. The equations themselves are in
// rotor_equations.h, which the batched flight engine steps too.
#pragma once

#include <string>

#include <Eigen/Core>

#include "rotors_gazebo_plugins/models/rotor_equations.h"

namespace rotors_gazebo_plugins {

struct RotorParams {
  double motor_constant = 8.54858e-6;          ///< C_T [N/(rad/s)^2]  (SDF motorConstant)
  double moment_constant = 0.016;              ///< C_M [m]            (momentConstant)
  double rotor_drag_coefficient = 1.0e-4;      ///< C_D [N s/m per rad/s] (rotorDragCoefficient)
  double rolling_moment_coefficient = 1.0e-6;  ///< C_R [N s per rad/s] (rollingMomentCoefficient)
  double time_constant_up_s = 1.0 / 80.0;      ///< (timeConstantUp)
  double time_constant_down_s = 1.0 / 40.0;    ///< (timeConstantDown)
  double max_rot_velocity = 838.0;             ///< [rad/s] (maxRotVelocity)
  int turning_direction = -1;                  ///< epsilon: +1 ccw, -1 cw (turningDirection)
  /// Empty when valid, else one line naming the bad value and the fix.
  std::string Validate() const;
};

/// Wrench of one rotor, all in the rotor frame R (z = rotor axis), applied at the rotor hub.
struct RotorWrench {
  Eigen::Vector3d thrust_R = Eigen::Vector3d::Zero();           ///< F_T, eq. 1
  Eigen::Vector3d drag_R = Eigen::Vector3d::Zero();             ///< F_D, eq. 2
  Eigen::Vector3d rolling_moment_R = Eigen::Vector3d::Zero();   ///< M_R, eq. 3
  Eigen::Vector3d reaction_moment_R = Eigen::Vector3d::Zero();  ///< M_D, eq. 4
};

class RotorModel {
 public:
  explicit RotorModel(const RotorParams& params);

  /// Forces and moments at the current rotor speed omega [rad/s, >= 0 spins in turning_direction]
  /// for the airspeed v_A = v_hub - v_wind, expressed in the rotor frame (RotorLoads with e = e_z).
  RotorWrench ComputeWrench(const Eigen::Vector3d& airspeed_R) const;

  /// Advances the speed dynamics towards the command over dt (RotorSpeedStep); returns omega.
  double UpdateSpeed(double omega_cmd, double dt_s);

  double Omega() const { return omega_; }
  /// Signed real speed: turning_direction * omega [rad/s] (what RotorS publishes on motor_speed).
  double SignedOmega() const { return params_.turning_direction * omega_; }
  const RotorParams& Params() const { return params_; }
  /// -epsilon C_M: M_D = reaction_factor F_T (eq. 4).
  double ReactionFactor() const { return -params_.turning_direction * params_.moment_constant; }
  void Reset() { omega_ = 0.0; }

 private:
  RotorParams params_;
  double omega_ = 0.0;  ///< [rad/s], >= 0
};

}  // namespace rotors_gazebo_plugins
