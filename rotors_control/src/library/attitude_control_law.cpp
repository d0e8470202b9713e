#include "rotors_control/attitude_control_law.h"

#include <cstring>

#include <Eigen/Dense>

#include "rotors_control/lee_law.h"

namespace rotors_control {

Eigen::Vector3d Vee(const Eigen::Matrix3d& S) { return {S(2, 1), S(0, 2), S(1, 0)}; }

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

AttitudeControlLaw::AttitudeControlLaw(const AttitudeGains& gains, const Eigen::Matrix3d& inertia)
    : J_(inertia), J_inv_(inertia.inverse()) {
  // K~ = K^T J^-1 (RotorS' normalisation, "to make the tuning independent of the inertia")
  k_R_normalized_ = gains.attitude_gain.transpose() * J_inv_;
  k_omega_normalized_ = gains.angular_rate_gain.transpose() * J_inv_;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      J_rows_[i * 3 + j] = J_(i, j);
      J_inv_rows_[i * 3 + j] = J_inv_(i, j);
    }
}

void AttitudeControlLaw::CopyLawConstants(double k_R[3], double k_omega[3], double J[9], double J_inv[9]) const {
  for (int k = 0; k < 3; ++k) {
    k_R[k] = k_R_normalized_[k];
    k_omega[k] = k_omega_normalized_[k];
  }
  std::memcpy(J, J_rows_, sizeof(J_rows_));
  std::memcpy(J_inv, J_inv_rows_, sizeof(J_inv_rows_));
}

Eigen::Vector3d AttitudeControlLaw::AngularAcceleration(const Eigen::Matrix3d& R, const Eigen::Vector3d& omega,
                                                        const Eigen::Matrix3d& R_d,
                                                        const Eigen::Vector3d& omega_d) const {
  double R_rows[9], R_d_rows[9], k_R[3], k_omega[3], alpha[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      R_rows[i * 3 + j] = R(i, j);
      R_d_rows[i * 3 + j] = R_d(i, j);
    }
  for (int k = 0; k < 3; ++k) {
    k_R[k] = k_R_normalized_[k];
    k_omega[k] = k_omega_normalized_[k];
  }
  const double w[3] = {omega.x(), omega.y(), omega.z()}, w_d[3] = {omega_d.x(), omega_d.y(), omega_d.z()};
  law::AngularAcceleration(k_R, k_omega, J_rows_, J_inv_rows_, R_rows, w, R_d_rows, w_d, alpha);  // lee_law.h
  return {alpha[0], alpha[1], alpha[2]};
}

Eigen::Vector3d AttitudeControlLaw::RateAcceleration(const Eigen::Vector3d& omega,
                                                     const Eigen::Vector3d& omega_des) const {
  return -k_omega_normalized_.cwiseProduct(omega - omega_des) + J_inv_ * omega.cross(J_ * omega);
}

}  // namespace rotors_control
