// Loads a world from an SDF .world file (physics, gravity, static models, world plugins).
#pragma once

#include <string>

#include "rotors_core/physics/physics_types.h"

namespace rotors_sim {

class WorldLoader {
 public:
  /// Throws SimError with one line naming the file and the problem.
  static physics::WorldPtr LoadFile(const std::string& path);
  static physics::WorldPtr LoadString(const std::string& sdf_text, const std::string& source_name);
};

}  // namespace rotors_sim
