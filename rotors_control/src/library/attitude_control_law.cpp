#include "rotors_control/attitude_control_law.h"

#include <Eigen/Dense>

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
}

Eigen::Vector3d AttitudeControlLaw::AngularAcceleration(const Eigen::Matrix3d& R, const Eigen::Vector3d& omega,
                                                        const Eigen::Matrix3d& R_d,
                                                        const Eigen::Vector3d& omega_d) const {
  // Lee2010 eq. (10): e_R = 1/2 vee(R_d^T R - R^T R_d)
  const Eigen::Vector3d e_R = 0.5 * Vee(R_d.transpose() * R - R.transpose() * R_d);
  // Lee2010 eq. (11): e_w = w - R^T R_d w_d
  const Eigen::Vector3d omega_d_B = R.transpose() * R_d * omega_d;
  const Eigen::Vector3d e_omega = omega - omega_d_B;
  // Lee2010 eq. (16) divided by J: -K~_R e_R - K~_w e_w + J^-1 (w x J w) - hat(w) R^T R_d w_d
  return -k_R_normalized_.cwiseProduct(e_R) - k_omega_normalized_.cwiseProduct(e_omega) +
         J_inv_ * omega.cross(J_ * omega) - Hat(omega) * omega_d_B;
}

Eigen::Vector3d AttitudeControlLaw::RateAcceleration(const Eigen::Vector3d& omega,
                                                     const Eigen::Vector3d& omega_des) const {
  return -k_omega_normalized_.cwiseProduct(omega - omega_des) + J_inv_ * omega.cross(J_ * omega);
}

}  // namespace rotors_control
