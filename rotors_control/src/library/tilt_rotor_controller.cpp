#include "rotors_control/tilt_rotor_controller.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/QR>

#include "rotors_control/attitude_control_law.h"  // Vee

namespace rotors_control {

std::string TiltRotorControllerParameters::Validate() const {
  std::ostringstream why;
  if (!(mass_kg > 0.0)) {
    why << "mass = " << mass_kg << " must be > 0 kg";
  } else if (!(gravity_m_s2 > 0.0)) {
    why << "gravity = " << gravity_m_s2 << " must be > 0 m/s^2";
  } else if (!(inertia_kg_m2.diagonal().minCoeff() > 0.0) || !inertia_kg_m2.allFinite()) {
    why << "inertia must be finite with xx, yy, zz > 0";
  } else if (arms.size() < 3) {
    why << "tilt_rotor_configuration has " << arms.size() << " arms; a 6-DoF allocation needs at least 3";
  }
  for (size_t i = 0; why.str().empty() && i < arms.size(); ++i) {
    const TiltRotorArm& a = arms[i];
    if (!(a.rotor_force_constant > 0.0) || !(a.max_rot_velocity_rad_s > 0.0) || !a.position_B.allFinite() ||
        !std::isfinite(a.yaw_rad + a.upper_moment_constant + a.lower_moment_constant) ||
        (a.upper_direction != 1 && a.upper_direction != -1))
      why << "tilt_rotor_configuration/" << i
          << ": rotor_force_constant and max_rot_velocity must be > 0, the rest finite, upper_direction +1 or -1";
  }
  for (const auto& [name, gain] :
       {std::make_pair("position_gain", position_gain), std::make_pair("velocity_gain", velocity_gain),
        std::make_pair("attitude_gain", attitude_gain), std::make_pair("angular_rate_gain", angular_rate_gain)})
    if (why.str().empty() && !(gain.minCoeff() >= 0.0 && gain.allFinite()))
      why << name << " = (" << gain.transpose() << ") must be finite and >= 0";
  return why.str();
}

namespace {
Eigen::Vector3d Lateral(const TiltRotorArm& arm) {  // e_lat,i = -R_z(yaw_i) e_y
  return {std::sin(arm.yaw_rad), -std::cos(arm.yaw_rad), 0.0};
}
double DragMomentPerNewton(const TiltRotorArm& arm) {  // c_i
  return -arm.upper_direction * (arm.upper_moment_constant - arm.lower_moment_constant) / 2.0;
}
}  // namespace

TiltRotorAllocation::TiltRotorAllocation(const std::vector<TiltRotorArm>& arms) : arms_(arms), A_(6, 2 * arms.size()) {
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  for (size_t i = 0; i < arms_.size(); ++i) {
    const Eigen::Vector3d& r = arms_[i].position_B;
    const double c = DragMomentPerNewton(arms_[i]);
    const Eigen::Vector3d e_lat = Lateral(arms_[i]);
    A_.block<3, 1>(0, 2 * i) = e_z;
    A_.block<3, 1>(3, 2 * i) = r.cross(e_z) + c * e_z;
    A_.block<3, 1>(0, 2 * i + 1) = e_lat;
    A_.block<3, 1>(3, 2 * i + 1) = r.cross(e_lat) + c * e_lat;
  }
  A_pinv_ = A_.completeOrthogonalDecomposition().pseudoInverse();
}

Eigen::VectorXd TiltRotorAllocation::Command(const Eigen::Matrix<double, 6, 1>& wrench_B) const {
  const size_t n = arms_.size();
  const Eigen::VectorXd x = A_pinv_ * wrench_B;  // least-norm (v_i, l_i)
  Eigen::VectorXd command(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const double v = x(2 * i), l = x(2 * i + 1);
    // f_i >= 0 along d_i: a downward v_i is an arm turned over (alpha beyond +-pi/2)
    const double f = std::hypot(v, l);
    const double omega =
        std::min(std::sqrt(f / (2.0 * arms_[i].rotor_force_constant)), arms_[i].max_rot_velocity_rad_s);
    command(i) = omega;                     // upper
    command(n + i) = omega;                 // lower
    command(2 * n + i) = std::atan2(l, v);  // alpha_i
  }
  return command;
}

Eigen::Matrix<double, 6, 1> TiltRotorAllocation::Wrench(const Eigen::VectorXd& command) const {
  const size_t n = arms_.size();
  Eigen::VectorXd x(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const double k_F = arms_[i].rotor_force_constant;
    // the two rotors' thrust, f_i = k_F (omega_u^2 + omega_l^2), along d_i(alpha_i)
    const double f = k_F * (command(i) * command(i) + command(n + i) * command(n + i));
    x(2 * i) = f * std::cos(command(2 * n + i));
    x(2 * i + 1) = f * std::sin(command(2 * n + i));
  }
  return A_ * x;
}

namespace {
const TiltRotorControllerParameters& Validated(const TiltRotorControllerParameters& params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
  return params;
}
}  // namespace

TiltRotorController::TiltRotorController(const TiltRotorControllerParameters& params)
    : params_(Validated(params)), allocation_(params.arms) {}

void TiltRotorController::SetReference(const PoseReference& reference) {
  reference_ = reference;
  reference_.orientation_W_D.normalize();
  has_reference_ = true;
}

Eigen::Matrix<double, 6, 1> TiltRotorController::Wrench(const VehicleState& state) const {
  const Eigen::Matrix3d R_WB = state.orientation_W_B.toRotationMatrix();
  const Eigen::Matrix3d R_WD = reference_.orientation_W_D.toRotationMatrix();
  const Eigen::Vector3d e_p = state.position_W - reference_.position_W;
  const Eigen::Vector3d e_v = R_WB * state.velocity_B - reference_.velocity_W;
  // F_W = m (-K_p e_p - K_v e_v + g e_z + a_d): the force is made directly, whatever the attitude
  const Eigen::Vector3d F_W =
      params_.mass_kg * (-params_.position_gain.cwiseProduct(e_p) - params_.velocity_gain.cwiseProduct(e_v) +
                         params_.gravity_m_s2 * Eigen::Vector3d::UnitZ() + reference_.acceleration_W);
  // e_R = 1/2 vee(R_D^T R - R^T R_D) (Lee's attitude error); omega_D = 0
  const Eigen::Vector3d e_R = 0.5 * Vee(R_WD.transpose() * R_WB - R_WB.transpose() * R_WD);
  const Eigen::Vector3d& omega = state.angular_velocity_B;
  const Eigen::Matrix3d& J = params_.inertia_kg_m2;
  // M_B = J (-K_R e_R - K_omega omega) + omega x J omega
  const Eigen::Vector3d M_B =
      J * (-params_.attitude_gain.cwiseProduct(e_R) - params_.angular_rate_gain.cwiseProduct(omega)) +
      omega.cross(J * omega);
  Eigen::Matrix<double, 6, 1> wrench;
  wrench << R_WB.transpose() * F_W, M_B;
  return wrench;
}

Eigen::VectorXd TiltRotorController::Command(const VehicleState& state) const {
  if (!has_reference_) return Eigen::VectorXd::Zero(3 * params_.arms.size());
  return allocation_.Command(Wrench(state));
}

}  // namespace rotors_control
