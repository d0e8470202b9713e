// A pose controller for the omav (tilt-rotor, overactuated): ours. RotorS flies the omav only
// through its MAVLink interface with an external controller; here a 6-DoF PD law computes the
// body wrench for any position AND attitude, and a static allocation turns it into 12 rotor
// speeds and 6 tilt angles (RotorS' 18-entry command).
//
// Allocation: arm i (at r_i, its axis x_i = R_z(yaw_i) e_x) tilted by alpha_i turns its thrust
// direction from e_z towards e_lat,i = -R_z(yaw_i) e_y:  d_i = cos(alpha_i) e_z + sin(alpha_i) e_lat,i.
// With v_i = f_i cos(alpha_i) and l_i = f_i sin(alpha_i) the wrench is linear in x = (v_i, l_i):
//   [F; M] = sum_i v_i [e_z; r_i x e_z + c_i e_z] + l_i [e_lat,i; r_i x e_lat,i + c_i e_lat,i] = A x
// where c_i = -s_i (k_M,upper - k_M,lower) / 2 is the drag moment per newton of the arm's two
// coaxial rotors (upper turning s_i = +1 ccw, lower the other way, each making f_i / 2). The
// least-norm x = A^+ w gives f_i = |(v_i, l_i)|, alpha_i = atan2(l_i, v_i), omega = sqrt(f_i / (2 k_F)).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_control/lee_controller.h"  // VehicleState

namespace rotors_control {

/// One tilt unit with two coaxial rotors (upper: motor i, lower: motor i + arms, tilt: i + 2 arms).
struct TiltRotorArm {
  Eigen::Vector3d position_B = Eigen::Vector3d::Zero();  ///< r_i [m], tilt axis through it
  double yaw_rad = 0.0;                                  ///< the arm's axis in the body xy plane
  double rotor_force_constant = 0.0;                     ///< k_F [N/(rad/s)^2] of each rotor
  double upper_moment_constant = 0.0;                    ///< k_M [m] of the upper rotor
  double lower_moment_constant = 0.0;                    ///< k_M [m] of the lower rotor
  int upper_direction = 1;                               ///< +1 ccw, -1 cw; the lower turns the other way
  double max_rot_velocity_rad_s = 0.0;                   ///< limit of each rotor
};

struct TiltRotorControllerParameters {
  double mass_kg = 0.0;
  double gravity_m_s2 = 9.81;
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();
  std::vector<TiltRotorArm> arms;
  Eigen::Vector3d position_gain{6.0, 6.0, 6.0};        ///< K_p [1/s^2]
  Eigen::Vector3d velocity_gain{4.7, 4.7, 4.7};        ///< K_v [1/s]
  Eigen::Vector3d attitude_gain{36.0, 36.0, 16.0};     ///< K_R [1/s^2]
  Eigen::Vector3d angular_rate_gain{10.0, 10.0, 8.0};  ///< K_omega [1/s]
  /// Empty when valid, else one line naming the bad value.
  std::string Validate() const;
};

/// A 6-DoF set point: position and full attitude (an overactuated MAV can hold any of them).
struct PoseReference {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation_W_D = Eigen::Quaterniond::Identity();
};

class TiltRotorAllocation {
 public:
  explicit TiltRotorAllocation(const std::vector<TiltRotorArm>& arms);
  /// The 6 x 2n matrix A above.
  const Eigen::MatrixXd& Matrix() const { return A_; }
  /// RotorS' command for the body wrench [N; N m]: n upper speeds, n lower speeds [rad/s], n tilt
  /// angles [rad]; speeds clamped to each rotor's limit.
  Eigen::VectorXd Command(const Eigen::Matrix<double, 6, 1>& wrench_B) const;
  /// The wrench the command makes (the forward model of the allocation, for tests).
  Eigen::Matrix<double, 6, 1> Wrench(const Eigen::VectorXd& command) const;

 private:
  std::vector<TiltRotorArm> arms_;
  Eigen::MatrixXd A_, A_pinv_;
};

class TiltRotorController {
 public:
  /// Throws std::invalid_argument naming the bad parameter.
  explicit TiltRotorController(const TiltRotorControllerParameters& params);
  void SetReference(const PoseReference& reference);
  bool HasReference() const { return has_reference_; }
  /// The body wrench [F_B; M_B] the PD law asks for.
  Eigen::Matrix<double, 6, 1> Wrench(const VehicleState& state) const;
  /// RotorS' 18-entry command; zeros until the first reference (rotors stopped, arms level).
  Eigen::VectorXd Command(const VehicleState& state) const;

 private:
  TiltRotorControllerParameters params_;
  TiltRotorAllocation allocation_;
  PoseReference reference_;
  bool has_reference_ = false;
};

}  // namespace rotors_control
