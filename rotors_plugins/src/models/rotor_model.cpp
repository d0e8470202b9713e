#include "rotors_gazebo_plugins/models/rotor_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string RotorParams::Validate() const {
  std::ostringstream why;
  auto positive = [&why](const char* name, double v, const char* unit) {
    if (!(v > 0.0) || !std::isfinite(v)) why << name << " = " << v << " must be > 0 " << unit;
    return why.str().empty();
  };
  auto non_negative = [&why](const char* name, double v) {
    if (!(v >= 0.0) || !std::isfinite(v)) why << name << " = " << v << " must be >= 0";
    return why.str().empty();
  };
  positive("motorConstant", motor_constant, "N/(rad/s)^2") && non_negative("momentConstant", moment_constant) &&
      non_negative("rotorDragCoefficient", rotor_drag_coefficient) &&
      non_negative("rollingMomentCoefficient", rolling_moment_coefficient) &&
      positive("timeConstantUp", time_constant_up_s, "s") && positive("timeConstantDown", time_constant_down_s, "s") &&
      positive("maxRotVelocity", max_rot_velocity, "rad/s");
  if (why.str().empty() && turning_direction != 1 && turning_direction != -1)
    why << "turningDirection must be 'cw' or 'ccw'";
  return why.str();
}

RotorModel::RotorModel(const RotorParams& params)
    : params_(params), speed_(params.time_constant_up_s, params.time_constant_down_s) {}

RotorWrench RotorModel::ComputeWrench(const Eigen::Vector3d& airspeed_R) const {
  const double omega = Omega();
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  RotorWrench w;
  // eq. 1: F_T = omega^2 C_T e_z
  w.thrust_R = omega * omega * params_.motor_constant * e_z;
  // eq. 5: v_perp = v - (v . e_z) e_z, the airspeed in the rotor plane
  const Eigen::Vector3d v_perp_R = airspeed_R - airspeed_R.dot(e_z) * e_z;
  // eq. 2: F_D = -omega C_D v_perp
  w.drag_R = -omega * params_.rotor_drag_coefficient * v_perp_R;
  // eq. 3: M_R = omega C_R v_perp  (the book's sign; RotorS applies the opposite one)
  w.rolling_moment_R = omega * params_.rolling_moment_coefficient * v_perp_R;
  // eq. 4: M_D = -epsilon C_M F_T
  w.reaction_moment_R = -params_.turning_direction * params_.moment_constant * w.thrust_R;
  return w;
}

double RotorModel::UpdateSpeed(double omega_cmd, double dt_s) {
  const double u = std::clamp(omega_cmd, 0.0, params_.max_rot_velocity);
  return speed_.Update(u, dt_s);
}

}  // namespace rotors_gazebo_plugins
