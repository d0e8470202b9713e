#include "rotors_control/motor_mixer.h"

#include <algorithm>
#include <cmath>
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

MotorMixer::MotorMixer(const MultirotorParameters& vehicle) : A_(AllocationMatrix(vehicle)) {
  if (vehicle.rotors.size() > static_cast<size_t>(RotorVector::MaxRowsAtCompileTime))
    throw std::invalid_argument("rotor_configuration has " + std::to_string(vehicle.rotors.size()) +
                                " rotors; the mixer takes at most 16");
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
  if (vehicle.AllRotorsLimited()) {
    omega_max_squared_.resize(vehicle.rotors.size());
    for (size_t i = 0; i < vehicle.rotors.size(); ++i)
      omega_max_squared_[i] = vehicle.rotors[i].max_rot_velocity_rad_s * vehicle.rotors[i].max_rot_velocity_rad_s;
  }
}

double MotorMixer::FeasibleThrust(const Eigen::Vector3d& alpha_B, double thrust_N) const {
  if (omega_max_squared_.size() == 0) return thrust_N;
  // omega^2 = M_alpha alpha + c T, with c the thrust column of A^T (A A^T)^-1 blockdiag(J, 1)
  const RotorVector torque_part = A_pinv_J_.leftCols<3>() * alpha_B;
  const RotorVector c = A_pinv_J_.col(3);
  double feasible = thrust_N;
  for (Eigen::Index i = 0; i < c.size(); ++i)
    if (c[i] > 0.0) feasible = std::min(feasible, (omega_max_squared_[i] - torque_part[i]) / c[i]);
  return std::max(feasible, 0.0);
}

double MotorMixer::FeasibleYaw(const RotorVector& without_yaw, const RotorVector& per_yaw, double yaw) {
  // omega_i^2 = without_yaw_i + per_yaw_i y >= 0 for every i bounds y to [lo, hi]
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < per_yaw.size(); ++i) {
    if (per_yaw[i] > 0.0) lo = std::max(lo, -without_yaw[i] / per_yaw[i]);
    if (per_yaw[i] < 0.0) hi = std::min(hi, without_yaw[i] / -per_yaw[i]);
  }
  return lo <= hi ? std::clamp(yaw, lo, hi) : yaw;  // empty: yaw cannot help, the rotors clip
}

RotorVector MotorMixer::RotorSpeeds(const Eigen::Vector3d& alpha_B, double thrust_N) const {
  // omega^2 = A^T (A A^T)^-1 blockdiag(J, 1) [alpha; T] = without_yaw + per_yaw alpha_z
  const RotorVector per_yaw = A_pinv_J_.col(2);
  const auto without_yaw = [&](double thrust) {
    return RotorVector(A_pinv_J_.leftCols<2>() * alpha_B.head<2>() + A_pinv_J_.col(3) * thrust);
  };
  // A rotor cannot push downwards: when one would have to, the yaw acceleration gives way (moves to
  // the nearest feasible value), so roll, pitch and thrust stay exact. A hexacopter with a failed
  // rotor gives up yaw this way and keeps its position. The thrust limit then uses that yaw.
  const RotorVector first = without_yaw(thrust_N);
  double alpha_z = FeasibleYaw(first, per_yaw, alpha_B.z());
  const double thrust = FeasibleThrust({alpha_B.x(), alpha_B.y(), alpha_z}, thrust_N);
  // with the thrust kept, the first pass stands: FeasibleYaw is a clamp, a second one changes nothing
  const RotorVector base = thrust == thrust_N ? first : without_yaw(thrust);
  if (thrust != thrust_N) alpha_z = FeasibleYaw(base, per_yaw, alpha_z);
  return (base + per_yaw * alpha_z).cwiseMax(0.0).cwiseSqrt();
}

}  // namespace rotors_control
