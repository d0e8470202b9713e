#include "rotors_gazebo_plugins/models/tilt_servo_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string TiltServoParams::Validate() const {
  std::ostringstream why;
  for (const auto& [name, value] : {std::pair<const char*, double>{"p", p},
                                    {"i", i},
                                    {"d", d},
                                    {"iMax", i_max},
                                    {"iMin", i_min},
                                    {"cmdMax", cmd_max},
                                    {"cmdMin", cmd_min}})
    if (!std::isfinite(value)) return std::string("joint_control_pid ") + name + " must be finite";
  if (p < 0.0 || i < 0.0 || d < 0.0)
    why << "joint_control_pid p, i, d = " << p << ", " << i << ", " << d << " must be >= 0";
  else if (i_min > i_max) why << "joint_control_pid iMin = " << i_min << " is above iMax = " << i_max;
  else if (!(cmd_min < cmd_max))
    why << "joint_control_pid cmdMin = " << cmd_min << " must be below cmdMax = " << cmd_max << " [N m]";
  return why.str();
}

double TiltServoModel::AngleError(double theta_rad, double theta_ref_rad) {
  constexpr double kTwoPi = 2.0 * M_PI;
  auto wrap_0_2pi = [](double a) {
    a = std::fmod(a, kTwoPi);
    return a < 0.0 ? a + kTwoPi : a;
  };
  // wrap_[-pi, pi)(x) = wrap_[0, 2pi)(x + pi) - pi
  return wrap_0_2pi(wrap_0_2pi(theta_rad) - wrap_0_2pi(theta_ref_rad) + M_PI) - M_PI;
}

double TiltServoModel::Torque(double theta_rad, double theta_ref_rad, double dt_s) {
  const double e = AngleError(theta_rad, theta_ref_rad);
  integral_ += e * dt_s;
  // Gazebo's PID: the integral term is clamped, the integral itself is not
  const double i_term = std::clamp(params_.i * integral_, params_.i_min, params_.i_max);
  const double d_term = dt_s > 0.0 ? params_.d * (e - previous_error_) / dt_s : 0.0;
  previous_error_ = e;
  // tau = -(p e + I + D), clamped to [cmdMin, cmdMax]
  return std::clamp(-(params_.p * e + i_term + d_term), params_.cmd_min, params_.cmd_max);
}

}  // namespace rotors_gazebo_plugins
