#include "rotors_control/lee_controller.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rotors_control {

std::string LeeControllerParameters::Validate() const {
  const std::string vehicle_why = vehicle.Validate();
  if (!vehicle_why.empty()) return vehicle_why;
  std::ostringstream why;
  if (!(position_gain.minCoeff() >= 0.0)) why << "position_gain must be >= 0";
  else if (!(velocity_gain.minCoeff() >= 0.0)) why << "velocity_gain must be >= 0";
  else if (!(attitude.attitude_gain.minCoeff() >= 0.0)) why << "attitude_gain must be >= 0";
  else if (!(attitude.angular_rate_gain.minCoeff() >= 0.0)) why << "angular_rate_gain must be >= 0";
  else if (!(max_tilt_angle_rad >= 0.0 && max_tilt_angle_rad < M_PI / 2))
    why << "max_tilt_angle = " << max_tilt_angle_rad << " rad must be in [0, pi/2) (0: no limit)";
  return why.str();
}

bool TrajectoryPoint::IsFinite() const {
  return position_W.allFinite() && velocity_W.allFinite() && acceleration_W.allFinite() && std::isfinite(yaw_rad) &&
         std::isfinite(yaw_rate_rad_s);
}

namespace {
/// The limits' part of a law's constants.
void SetLimits(const AccelerationLimits& limits, LeeConstantsT<double>* c) {
  c->limits_active = limits.Active() ? 1.0 : 0.0;
  c->tilt_limited = limits.max_tilt_rad > 0.0 ? 1.0 : 0.0;
  c->tan_max_tilt = std::tan(limits.max_tilt_rad);
  c->thrust_limited = std::isfinite(limits.max_m_s2) ? 1.0 : 0.0;
  c->max_m_s2 = limits.max_m_s2;
  c->min_up_m_s2 = limits.min_up_m_s2;
}

AccelerationLimits LimitsOf(const LeeControllerParameters& p) {
  AccelerationLimits limits;
  limits.max_tilt_rad = p.max_tilt_angle_rad;
  if (p.vehicle.AllRotorsLimited()) {
    double max_thrust_N = 0.0;
    for (const RotorGeometry& r : p.vehicle.rotors)
      max_thrust_N += r.rotor_force_constant * r.max_rot_velocity_rad_s * r.max_rot_velocity_rad_s;  // eq. 1
    limits.max_m_s2 = max_thrust_N / p.vehicle.mass_kg;
  }
  if (limits.Active()) limits.min_up_m_s2 = kMinUpwardAccelerationFraction * p.vehicle.gravity_m_s2;
  return limits;
}
}  // namespace

Eigen::Vector3d SaturatedAcceleration(const Eigen::Vector3d& a_des_W, const AccelerationLimits& limits) {
  LeeConstantsT<double> c{};
  SetLimits(limits, &c);
  const double a[3] = {a_des_W.x(), a_des_W.y(), a_des_W.z()};
  double out[3];
  law::SaturatedAcceleration(c, a, out);
  return {out[0], out[1], out[2]};
}

LeeController::LeeController(const LeeControllerParameters& params)
    : params_(Validated(params)),
      attitude_law_(params.attitude, params.vehicle.inertia_kg_m2),
      mixer_(params.vehicle),
      limits_(LimitsOf(params_)) {
  for (const RotorGeometry& r : params_.vehicle.rotors) nominal_force_constants_.push_back(r.rotor_force_constant);
  speed_factors_.assign(nominal_force_constants_.size(), 1.0);
  UpdateConstants();
}

void LeeController::UpdateConstants() {
  LeeConstantsT<double>& c = constants_;
  c.mass_kg = params_.vehicle.mass_kg;
  c.gravity_m_s2 = params_.vehicle.gravity_m_s2;
  for (int k = 0; k < 3; ++k) {
    c.position_gain[k] = params_.position_gain[k];
    c.velocity_gain[k] = params_.velocity_gain[k];
  }
  SetLimits(limits_, &c);
  attitude_law_.CopyLawConstants(c.k_R, c.k_omega, c.J, c.J_inv);
  mixer_.CopyLawConstants(c.mixer, c.omega_max_squared, &c.rotors_limited);
}

std::string LeeController::SetRotorSpeedFactor(size_t rotor, double speed_factor) {
  if (rotor >= nominal_force_constants_.size())
    return "rotor " + std::to_string(rotor) + " does not exist (the vehicle has " +
           std::to_string(nominal_force_constants_.size()) + ")";
  if (!(speed_factor >= 0.0 && speed_factor <= 1.0))
    return "speed_factor " + std::to_string(speed_factor) + " must be in [0, 1]";
  LeeControllerParameters p = params_;
  // omega_real = s omega_cmd: thrust and moment k_F omega_real^2 = (s^2 k_F) omega_cmd^2 (eqs. 1, 4)
  p.vehicle.rotors[rotor].rotor_force_constant = nominal_force_constants_[rotor] * speed_factor * speed_factor;
  try {
    mixer_ = MotorMixer(p.vehicle);
  } catch (const std::invalid_argument& e) {
    return "rotor " + std::to_string(rotor) + " at " + std::to_string(speed_factor) + ": " + e.what();
  }
  params_ = p;
  limits_ = LimitsOf(params_);
  speed_factors_[rotor] = speed_factor;
  yaw_released_ = std::find(speed_factors_.begin(), speed_factors_.end(), 0.0) != speed_factors_.end();
  UpdateConstants();
  return {};
}

void LeeController::SetTrajectoryPoint(const TrajectoryPoint& point) {
  if (!has_reference_ || point.yaw_rad != reference_.yaw_rad)
    b1_reference_ = Eigen::Vector3d(std::cos(point.yaw_rad), std::sin(point.yaw_rad), 0.0);
  reference_ = point;
  has_reference_ = true;
}

LeeInputsT<double> LeeController::Inputs(const VehicleState& s) const {
  LeeInputsT<double> in{};
  const Eigen::Quaterniond& q = s.orientation_W_B;
  in.q_WB[0] = q.w(), in.q_WB[1] = q.x(), in.q_WB[2] = q.y(), in.q_WB[3] = q.z();
  for (int k = 0; k < 3; ++k) {
    in.position_W[k] = s.position_W[k];
    in.velocity_B[k] = s.velocity_B[k];
    in.angular_velocity_B[k] = s.angular_velocity_B[k];
    in.reference_position_W[k] = reference_.position_W[k];
    in.reference_velocity_W[k] = reference_.velocity_W[k];
    in.reference_acceleration_W[k] = reference_.acceleration_W[k];
    in.b1_reference[k] = b1_reference_[k];
  }
  in.reference_yaw_rate_rad_s = reference_.yaw_rate_rad_s;
  in.yaw_released = yaw_released_ ? 1.0 : 0.0;
  return in;
}

void LeeController::ComputeThrustAndAttitude(const VehicleState& s, double* thrust_N, Eigen::Matrix3d* R_WD) const {
  const LeeInputsT<double> in = Inputs(s);
  double R[9], R_d[9];
  law::RotationOf(in.q_WB, R);
  law::ThrustAndAttitude(constants_, in, R, thrust_N, R_d);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) (*R_WD)(i, j) = R_d[i * 3 + j];
}

RotorVector LeeController::RotorSpeeds(const VehicleState& s) const {
  const int rotors = mixer_.Rotors();
  if (!has_reference_) return RotorVector::Zero(rotors);
  RotorVector omega(rotors);
  law::LeeRotorSpeeds(rotors, constants_, Inputs(s), omega.data());
  return omega;
}

}  // namespace rotors_control
