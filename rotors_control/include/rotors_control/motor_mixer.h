// Allocation (book eq. 10; reference section 7.1) and its inverse: rotor speeds from a desired
// angular acceleration and thrust.
#pragma once

#include <string>

#include <Eigen/Core>

#include "rotors_control/lee_law.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

/// One value per rotor, kept on the stack (no allocation per control step) up to 16 rotors.
using RotorVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxMixerRotors, 1>;

/// A (4 x N): [tau_x; tau_y; tau_z; T] = A * omega^2, with columns
/// (sin(theta) l k_F, -cos(theta) l k_F, -d k_F k_M, k_F).
Eigen::Matrix4Xd AllocationMatrix(const MultirotorParameters& vehicle);

class MotorMixer {
 public:
  /// Throws std::invalid_argument if A does not have rank 4 (the vehicle is not controllable).
  explicit MotorMixer(const MultirotorParameters& vehicle);
  /// omega = sqrt(max(0, A^T (A A^T)^-1 [J alpha; T])) (on the stack: no allocation per call): alpha [rad/s^2] body
  /// frame, thrust [N]. When every rotor has a max_rot_velocity and the thrust would push one beyond it, the thrust is
  /// lowered until none is (the torques keep priority: attitude control survives saturation).
  /// When a rotor would need a negative omega^2, the yaw acceleration moves to the nearest value
  /// that needs none (roll, pitch and thrust keep priority, as in PX4's mixer).
  RotorVector RotorSpeeds(const Eigen::Vector3d& alpha_B, double thrust_N) const;
  /// The largest thrust [N] <= thrust_N that keeps every rotor within its max_rot_velocity while
  /// producing the angular acceleration alpha_B (thrust_N itself when the rotors have no limit).
  double FeasibleThrust(const Eigen::Vector3d& alpha_B, double thrust_N) const;
  const Eigen::Matrix4Xd& Allocation() const { return A_; }
  /// The yaw input nearest to `yaw` with without_yaw + per_yaw * yaw >= 0 everywhere (`yaw` itself
  /// when no value achieves that).
  static double FeasibleYaw(const RotorVector& without_yaw, const RotorVector& per_yaw, double yaw);
  /// Its constants as the laws read them (lee_law.h): the rows of A^T (A A^T)^-1 blockdiag(J, 1),
  /// omega_max^2 and whether every rotor has a limit.
  void CopyLawConstants(double rows[kMaxMixerRotors][4], double omega_max_squared[kMaxMixerRotors],
                        double* rotors_limited) const;
  int Rotors() const { return rotors_; }

 private:
  Eigen::Matrix4Xd A_;
  int rotors_ = 0;
  double rows_[kMaxMixerRotors][4] = {};  ///< A^T (A A^T)^-1 blockdiag(J, 1), row by rotor
  double omega_max_squared_[kMaxMixerRotors] = {};
  double rotors_limited_ = 0.0;  ///< 1 when every rotor has a max_rot_velocity
};

}  // namespace rotors_control
