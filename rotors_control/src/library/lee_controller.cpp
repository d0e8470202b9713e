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

Eigen::Vector3d SaturatedAcceleration(const Eigen::Vector3d& a_des_W, const AccelerationLimits& limits) {
  return SaturatedAcceleration(a_des_W, limits, std::tan(limits.max_tilt_rad));
}

Eigen::Vector3d SaturatedAcceleration(const Eigen::Vector3d& a_des_W, const AccelerationLimits& limits,
                                      double tan_max_tilt) {
  const double a_up = std::clamp(a_des_W.z(), limits.min_up_m_s2, std::max(limits.max_m_s2, limits.min_up_m_s2));
  double a_h_max = std::numeric_limits<double>::infinity();
  // tilt: |a_h| <= a_up tan(theta_max);  thrust: |a_h|^2 + a_up^2 <= a_max^2
  if (limits.max_tilt_rad > 0.0) a_h_max = a_up * tan_max_tilt;
  if (std::isfinite(limits.max_m_s2))
    a_h_max = std::min(a_h_max, std::sqrt(std::max(limits.max_m_s2 * limits.max_m_s2 - a_up * a_up, 0.0)));
  const Eigen::Vector2d a_h = a_des_W.head<2>();
  const double scale = a_h.norm() > a_h_max ? a_h_max / a_h.norm() : 1.0;
  return Eigen::Vector3d(scale * a_h.x(), scale * a_h.y(), a_up);
}

namespace {
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

LeeController::LeeController(const LeeControllerParameters& params)
    : params_(Validated(params)),
      attitude_law_(params.attitude, params.vehicle.inertia_kg_m2),
      mixer_(params.vehicle),
      limits_(LimitsOf(params_)),
      tan_max_tilt_(std::tan(limits_.max_tilt_rad)) {
  for (const RotorGeometry& r : params_.vehicle.rotors) nominal_force_constants_.push_back(r.rotor_force_constant);
  speed_factors_.assign(nominal_force_constants_.size(), 1.0);
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
  tan_max_tilt_ = std::tan(limits_.max_tilt_rad);
  speed_factors_[rotor] = speed_factor;
  yaw_released_ = std::find(speed_factors_.begin(), speed_factors_.end(), 0.0) != speed_factors_.end();
  return {};
}

void LeeController::SetTrajectoryPoint(const TrajectoryPoint& point) {
  if (!has_reference_ || point.yaw_rad != reference_.yaw_rad)
    b1_reference_ = Eigen::Vector3d(std::cos(point.yaw_rad), std::sin(point.yaw_rad), 0.0);
  reference_ = point;
  has_reference_ = true;
}

void LeeController::ComputeThrustAndAttitude(const VehicleState& s, double* thrust_N, Eigen::Matrix3d* R_WD) const {
  ComputeThrustAndAttitude(s, s.orientation_W_B.toRotationMatrix(), thrust_N, R_WD);
}

void LeeController::ComputeThrustAndAttitude(const VehicleState& s, const Eigen::Matrix3d& R, double* thrust_N,
                                             Eigen::Matrix3d* R_WD) const {
  const double m = params_.vehicle.mass_kg, g = params_.vehicle.gravity_m_s2;
  const Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  // Lee2010 eq. (6)-(7): e_p = p - p_d,  e_v = v - v_d  (odometry velocity is body frame: v_W = R v_B)
  const Eigen::Vector3d e_p = s.position_W - reference_.position_W;
  const Eigen::Vector3d e_v = R * s.velocity_B - reference_.velocity_W;
  // a = (K_p e_p + K_v e_v) / m - g e3 - a_d : the negative of the desired acceleration
  Eigen::Vector3d a = (params_.position_gain.cwiseProduct(e_p) + params_.velocity_gain.cwiseProduct(e_v)) / m - g * e3 -
                      reference_.acceleration_W;
  if (limits_.Active()) a = -SaturatedAcceleration(-a, limits_, tan_max_tilt_);
  // Lee2010 eq. (15): f = -m a . R e3
  *thrust_N = -m * a.dot(R * e3);
  // Desired attitude: b3_d = -a / |a|, b1_d from the yaw (the current one when yaw is given up),
  // b2_d = b3_d x b1_d normalised
  Eigen::Vector3d b1_d = b1_reference_;
  if (yaw_released_) {
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    b1_d = Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
  }
  const Eigen::Vector3d b3_d = -a / a.norm();
  const Eigen::Vector3d b2_d = b3_d.cross(b1_d).normalized();
  R_WD->col(0) = b2_d.cross(b3_d);
  R_WD->col(1) = b2_d;
  R_WD->col(2) = b3_d;
}

RotorVector LeeController::RotorSpeeds(const VehicleState& s) const {
  if (!has_reference_) return RotorVector::Zero(params_.vehicle.rotors.size());
  double thrust_N = 0.0;
  Eigen::Matrix3d R_WD;
  const Eigen::Matrix3d R = s.orientation_W_B.toRotationMatrix();
  ComputeThrustAndAttitude(s, R, &thrust_N, &R_WD);
  const Eigen::Vector3d omega_d(0.0, 0.0, yaw_released_ ? 0.0 : reference_.yaw_rate_rad_s);
  const Eigen::Vector3d alpha = attitude_law_.AngularAcceleration(R, s.angular_velocity_B, R_WD, omega_d);
  return mixer_.RotorSpeeds(alpha, thrust_N);
}

}  // namespace rotors_control
