#include "rotors_control/vehicle_parameters.h"

#include <cmath>
#include <sstream>

namespace rotors_control {

std::string MultirotorParameters::Validate() const {
  std::ostringstream why;
  if (!(mass_kg > 0.0) || !std::isfinite(mass_kg)) {
    why << "mass = " << mass_kg << " must be > 0 kg";
  } else if (!(gravity_m_s2 > 0.0)) {
    why << "gravity = " << gravity_m_s2 << " must be > 0 m/s^2";
  } else if (!(inertia_kg_m2.diagonal().minCoeff() > 0.0) || !inertia_kg_m2.allFinite()) {
    why << "inertia diagonal [" << inertia_kg_m2.diagonal().transpose() << "] must be > 0 kg m^2";
  } else if (rotors.size() < 4) {
    why << "rotor_configuration has " << rotors.size() << " rotors; at least 4 are needed";
  } else {
    for (size_t i = 0; i < rotors.size(); ++i) {
      const RotorGeometry& r = rotors[i];
      if (!(r.rotor_force_constant > 0.0) || !(r.arm_length_m >= 0.0) || (r.direction != 1 && r.direction != -1)) {
        why << "rotor_configuration/" << i << " needs rotor_force_constant > 0, arm_length >= 0 and direction +1 or -1";
        break;
      }
      if (!(r.max_rot_velocity_rad_s >= 0.0) || !std::isfinite(r.max_rot_velocity_rad_s)) {
        why << "rotor_configuration/" << i << "/max_rot_velocity = " << r.max_rot_velocity_rad_s
            << " must be > 0 rad/s (or absent: no limit known)";
        break;
      }
    }
  }
  return why.str();
}

}  // namespace rotors_control
