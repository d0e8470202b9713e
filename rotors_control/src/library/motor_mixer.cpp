#include "rotors_control/motor_mixer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace rotors_control {

Eigen::Matrix4Xd AllocationMatrix(const MultirotorParameters& vehicle) {
  Eigen::Matrix4Xd A(4, vehicle.rotors.size());
  for (size_t i = 0; i < vehicle.rotors.size(); ++i) {
    const RotorGeometry& r = vehicle.rotors[i];
    const double k = r.rotor_force_constant;
    A(0, i) = std::sin(r.angle_rad) * r.arm_length_m * k;   // roll torque
    A(1, i) = -std::cos(r.angle_rad) * r.arm_length_m * k;  // pitch torque
    A(2, i) = -r.direction * k * r.rotor_moment_constant;   // yaw torque (eq. 4)
    A(3, i) = k;                                            // thrust (eq. 1)
  }
  return A;
}

MotorMixer::MotorMixer(const MultirotorParameters& vehicle)
    : A_(AllocationMatrix(vehicle)), rotors_(static_cast<int>(vehicle.rotors.size())) {
  if (vehicle.rotors.size() > static_cast<size_t>(kMaxMixerRotors))
    throw std::invalid_argument("rotor_configuration has " + std::to_string(vehicle.rotors.size()) +
                                " rotors; the mixer takes at most " + std::to_string(kMaxMixerRotors));
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A_);
  lu.setThreshold(1e-9);
  if (lu.rank() < 4) {
    throw std::invalid_argument("the allocation matrix has rank " + std::to_string(lu.rank()) +
                                ", it needs rank 4 for a controllable vehicle; check rotor_configuration "
                                "(angles, arm lengths, directions)");
  }
  Eigen::Matrix4d J_block = Eigen::Matrix4d::Identity();
  J_block.topLeftCorner<3, 3>() = vehicle.inertia_kg_m2;
  const Eigen::MatrixX4d A_pinv_J = A_.transpose() * (A_ * A_.transpose()).inverse() * J_block;
  for (int i = 0; i < rotors_; ++i)
    for (int k = 0; k < 4; ++k) rows_[i][k] = A_pinv_J(i, k);
  rotors_limited_ = vehicle.AllRotorsLimited() ? 1.0 : 0.0;
  for (int i = 0; i < rotors_ && vehicle.AllRotorsLimited(); ++i)
    omega_max_squared_[i] = vehicle.rotors[i].max_rot_velocity_rad_s * vehicle.rotors[i].max_rot_velocity_rad_s;
}

void MotorMixer::CopyLawConstants(double rows[kMaxMixerRotors][4], double omega_max_squared[kMaxMixerRotors],
                                  double* rotors_limited) const {
  std::memcpy(rows, rows_, sizeof(rows_));
  std::memcpy(omega_max_squared, omega_max_squared_, sizeof(omega_max_squared_));
  *rotors_limited = rotors_limited_;
}

double MotorMixer::FeasibleThrust(const Eigen::Vector3d& alpha_B, double thrust_N) const {
  const double alpha[3] = {alpha_B.x(), alpha_B.y(), alpha_B.z()};
  return law::FeasibleThrust(rotors_, rows_, omega_max_squared_, rotors_limited_, alpha, thrust_N);
}

double MotorMixer::FeasibleYaw(const RotorVector& without_yaw, const RotorVector& per_yaw, double yaw) {
  return law::FeasibleYaw(static_cast<int>(per_yaw.size()), without_yaw.data(), per_yaw.data(), yaw);
}

RotorVector MotorMixer::RotorSpeeds(const Eigen::Vector3d& alpha_B, double thrust_N) const {
  const double alpha[3] = {alpha_B.x(), alpha_B.y(), alpha_B.z()};
  RotorVector omega(rotors_);
  law::MixerRotorSpeeds(rotors_, rows_, omega_max_squared_, rotors_limited_, alpha, thrust_N, omega.data());
  return omega;
}

}  // namespace rotors_control
