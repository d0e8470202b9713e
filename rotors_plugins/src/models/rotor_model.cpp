#include "rotors_gazebo_plugins/models/rotor_model.h"

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

RotorModel::RotorModel(const RotorParams& params) : params_(params) {}

RotorWrench RotorModel::ComputeWrench(const Eigen::Vector3d& airspeed_R) const {
  const double e_z[3] = {0.0, 0.0, 1.0};
  const double v_A_R[3] = {airspeed_R.x(), airspeed_R.y(), airspeed_R.z()};
  const RotorLoadsT<double> loads =
      RotorLoads(omega_, e_z, v_A_R, params_.motor_constant, params_.rotor_drag_coefficient,
                 params_.rolling_moment_coefficient, ReactionFactor());
  RotorWrench w;
  w.thrust_R = Eigen::Map<const Eigen::Vector3d>(loads.thrust_F);
  w.drag_R = Eigen::Map<const Eigen::Vector3d>(loads.drag_F);
  w.rolling_moment_R = Eigen::Map<const Eigen::Vector3d>(loads.rolling_moment_F);
  w.reaction_moment_R = Eigen::Map<const Eigen::Vector3d>(loads.reaction_moment_F);
  return w;
}

double RotorModel::UpdateSpeed(double omega_cmd, double dt_s) {
  omega_ = RotorSpeedStep(omega_, omega_cmd, params_.max_rot_velocity, std::exp(-dt_s / params_.time_constant_up_s),
                          std::exp(-dt_s / params_.time_constant_down_s));
  return omega_;
}

}  // namespace rotors_gazebo_plugins
