// Loads a world from an SDF .world file (physics, gravity, static models, world plugins).
#pragma once

#include <map>
#include <string>

#include "rotors_core/physics/physics_types.h"

namespace rotors_sim {

struct WorldLoadOptions {
  /// World plugins (by file name) the caller does not need, with the reason it prints when it skips one.
  std::map<std::string, std::string> skipped_plugins;
  /// The world's models load without a sensor that cannot be built (see SpawnRequest).
  bool skip_broken_sensors = false;
  /// false: no shadows whatever the world says (cameras render faster); true: as the world says
  bool shadows = true;
};

class WorldLoader {
 public:
  /// Throws SimError with one line naming the file and the problem.
  static physics::WorldPtr LoadFile(const std::string& path, const WorldLoadOptions& options = {});
  static physics::WorldPtr LoadString(const std::string& sdf_text, const std::string& source_name,
                                      const WorldLoadOptions& options = {});
};

}  // namespace rotors_sim
