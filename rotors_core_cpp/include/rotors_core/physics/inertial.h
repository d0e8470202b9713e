// Mass properties of a link in its own frame, and the parallel-axis composition used to weld links.
#pragma once

#include <Eigen/Core>

namespace rotors_sim {
namespace physics {

class Inertial {
 public:
  Inertial() = default;
  /// mass [kg], centre of mass in the link frame [m], inertia about the CoG in link axes [kg m^2]
  Inertial(double mass_kg, const Eigen::Vector3d& cog_L, const Eigen::Matrix3d& J_cog_L)
      : mass_kg_(mass_kg), cog_L_(cog_L), J_cog_L_(J_cog_L) {}

  double Mass() const { return mass_kg_; }
  const Eigen::Vector3d& CoG() const { return cog_L_; }
  const Eigen::Matrix3d& MOI() const { return J_cog_L_; }

  /// Express this inertial in a frame F given the link's rotation R_FL and origin p_FL.
  Inertial Transformed(const Eigen::Matrix3d& R_FL, const Eigen::Vector3d& p_FL) const;

  /// Sum of two inertials expressed in the same frame (parallel-axis theorem:
  /// J = sum_i R J_i R^T + m_i (|d_i|^2 E - d_i d_i^T), d_i = c_i - c).
  Inertial operator+(const Inertial& other) const;

 private:
  double mass_kg_ = 0.0;
  Eigen::Vector3d cog_L_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d J_cog_L_ = Eigen::Matrix3d::Zero();
};

}  // namespace physics
}  // namespace rotors_sim
