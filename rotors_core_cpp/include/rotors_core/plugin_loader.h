// Finds plugin shared libraries by file name and instantiates them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rotors_core/plugin.h"

namespace rotors_sim {

class PluginLoader {
 public:
  /// Directories searched for a bare file name, in order: GAZEBO_PLUGIN_PATH,
  /// ROTORS_PLUGIN_PATH, LD_LIBRARY_PATH (':'-separated).
  static std::vector<std::string> SearchPath();
  /// Full path of `filename`, or throws SimError listing where it looked.
  static std::string Resolve(const std::string& filename);

  static std::unique_ptr<ModelPlugin> CreateModelPlugin(const std::string& filename);
  static std::unique_ptr<WorldPlugin> CreateWorldPlugin(const std::string& filename);
  static std::unique_ptr<SensorPlugin> CreateSensorPlugin(const std::string& filename);
};

}  // namespace rotors_sim
