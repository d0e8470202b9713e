// Vehicle parameters the controllers use (<mav>.yaml: mass, inertia, rotor_configuration).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_control {

struct RotorGeometry {
  double angle_rad = 0.0;  ///< from body +x about +z
  double arm_length_m = 0.215;
  double rotor_force_constant = 8.54858e-6;  ///< k_F [N/(rad/s)^2]
  double rotor_moment_constant = 1.6e-2;     ///< k_M [m]
  int direction = 1;                         ///< +1 ccw, -1 cw
  /// Optional (0: unknown). With it the mixer keeps the commanded torques when the thrust saturates.
  double max_rot_velocity_rad_s = 0.0;
};

struct MultirotorParameters {
  double mass_kg = 0.0;
  double gravity_m_s2 = 9.81;  ///< RotorS' controllers assume 9.81 (book section 3.6, reference section 9)
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();
  std::vector<RotorGeometry> rotors;
  /// Every rotor has a max_rot_velocity (the thrust limit is known).
  bool AllRotorsLimited() const {
    for (const RotorGeometry& r : rotors)
      if (!(r.max_rot_velocity_rad_s > 0.0)) return false;
    return !rotors.empty();
  }
  /// Empty when valid, else one line naming the bad value.
  std::string Validate() const;
};

/// Returns `params` if params.Validate() is empty, else throws std::invalid_argument with the reason
/// (for constructor initialiser lists).
template <typename Params>
const Params& Validated(const Params& params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
  return params;
}

}  // namespace rotors_control
