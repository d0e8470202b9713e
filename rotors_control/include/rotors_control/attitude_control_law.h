// Geometric attitude control on SO(3) (Lee, Leok, McClamroch 2010), shared by all controllers.
#pragma once

#include <Eigen/Core>

namespace rotors_control {

/// vee(S) for a skew-symmetric S; hat(v) = [v]x.
Eigen::Vector3d Vee(const Eigen::Matrix3d& S);
Eigen::Matrix3d Hat(const Eigen::Vector3d& v);

struct AttitudeGains {
  Eigen::Vector3d attitude_gain{3.0, 3.0, 0.035};        ///< K_R (RotorS code defaults)
  Eigen::Vector3d angular_rate_gain{0.52, 0.52, 0.025};  ///< K_omega
};

class AttitudeControlLaw {
 public:
  AttitudeControlLaw(const AttitudeGains& gains, const Eigen::Matrix3d& inertia);

  /// Desired angular acceleration [rad/s^2, body] to track R_d, omega_d (body of R_d):
  ///   e_R = 1/2 vee(R_d^T R - R^T R_d)                       Lee2010 eq. (10)
  ///   e_w = w - R^T R_d w_d                                   Lee2010 eq. (11)
  ///   alpha = -K~_R e_R - K~_w e_w + J^-1 (w x J w) - (hat(w) R^T R_d w_d)   eq. (16) / J,
  /// with K~ = K J^-1 (gains normalised by the inertia, as RotorS).
  Eigen::Vector3d AngularAcceleration(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& omega_B,
                                      const Eigen::Matrix3d& R_WD, const Eigen::Vector3d& omega_D) const;
  /// Rate-only law: alpha = -K~_w (w - w_d) + J^-1 (w x J w).
  Eigen::Vector3d RateAcceleration(const Eigen::Vector3d& omega_B, const Eigen::Vector3d& omega_des_B) const;
  /// Its constants as the laws read them (lee_law.h): K~_R, K~_w, J and J^-1 (row-major).
  void CopyLawConstants(double k_R[3], double k_omega[3], double J[9], double J_inv[9]) const;

 private:
  Eigen::Matrix3d J_, J_inv_;
  Eigen::Vector3d k_R_normalized_, k_omega_normalized_;
  double J_rows_[9], J_inv_rows_[9];  ///< J_ and J_inv_ row-major, for law::AngularAcceleration
};

}  // namespace rotors_control
