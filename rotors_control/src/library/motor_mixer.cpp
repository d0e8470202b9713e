#include "rotors_control/motor_mixer.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace rotors_control {

Eigen::Matrix4Xd AllocationMatrix(const VehicleParameters& vehicle) {
  Eigen::Matrix4Xd A(4, vehicle.rotors.size());
  for (size_t i = 0; i < vehicle.rotors.size(); ++i) {
    const Rotor& r = vehicle.rotors[i];
    const double k = r.rotor_force_constant;
    A(0, i) = std::sin(r.angle_rad) * r.arm_length_m * k;   // roll torque
    A(1, i) = -std::cos(r.angle_rad) * r.arm_length_m * k;  // pitch torque
    A(2, i) = -r.direction * k * r.rotor_moment_constant;   // yaw torque (eq. 4)
    A(3, i) = k;                                            // thrust (eq. 1)
  }
  return A;
}

MotorMixer::MotorMixer(const VehicleParameters& vehicle) : A_(AllocationMatrix(vehicle)) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A_);
  lu.setThreshold(1e-9);
  if (lu.rank() < 4) {
    throw std::invalid_argument("the allocation matrix has rank " + std::to_string(lu.rank()) +
                                ", it needs rank 4 for a controllable vehicle; check rotor_configuration "
                                "(angles, arm lengths, directions)");
  }
  Eigen::Matrix4d J_block = Eigen::Matrix4d::Identity();
  J_block.topLeftCorner<3, 3>() = vehicle.inertia_kg_m2;
  A_pinv_J_ = A_.transpose() * (A_ * A_.transpose()).inverse() * J_block;
}

Eigen::VectorXd MotorMixer::RotorSpeeds(const Eigen::Vector3d& alpha_B, double thrust_N) const {
  Eigen::Vector4d input;
  input << alpha_B, thrust_N;
  const Eigen::VectorXd omega_squared = (A_pinv_J_ * input).cwiseMax(0.0);
  return omega_squared.cwiseSqrt();
}

}  // namespace rotors_control
