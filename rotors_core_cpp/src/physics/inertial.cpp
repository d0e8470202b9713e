#include "rotors_core/physics/inertial.h"

namespace rotors_sim {
namespace physics {

Inertial Inertial::Transformed(const Eigen::Matrix3d& R_FL, const Eigen::Vector3d& p_FL) const {
  // c_F = R_FL c_L + p_FL ;  J_F = R_FL J_L R_FL^T (about the same CoG)
  return Inertial(mass_kg_, R_FL * cog_L_ + p_FL, R_FL * J_cog_L_ * R_FL.transpose());
}

Inertial Inertial::operator+(const Inertial& other) const {
  const double m = mass_kg_ + other.mass_kg_;
  if (m <= 0.0) return Inertial();
  // c = (m_a c_a + m_b c_b) / m
  const Eigen::Vector3d c = (mass_kg_ * cog_L_ + other.mass_kg_ * other.cog_L_) / m;
  // Parallel-axis theorem: J_c = J_i + m_i (|d|^2 E - d d^T), d = c_i - c
  auto shifted = [&c](const Inertial& in) {
    const Eigen::Vector3d d = in.cog_L_ - c;
    return Eigen::Matrix3d(in.J_cog_L_ +
                           in.mass_kg_ * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  return Inertial(m, c, shifted(*this) + shifted(other));
}

}  // namespace physics
}  // namespace rotors_sim
