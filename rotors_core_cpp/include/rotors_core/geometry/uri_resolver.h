// Where a resource URI of a world or model lives on disk (model://, package://, file://, absolute,
// relative to the file that names it). Engine-side: reads the environment, no ROS.
#pragma once

#include <string>
#include <vector>

namespace rotors_sim {
namespace geometry {

class UriResolver {
 public:
  /// Adds a folder that holds Gazebo model folders (model://NAME resolves to <folder>/NAME), after
  /// GAZEBO_MODEL_PATH and ROTORS_MODEL_PATH. The ROS server adds the packages' exported paths.
  static void AddModelPath(const std::string& folder);
  /// Every model folder searched, in order (environment first).
  static std::vector<std::string> ModelPaths();
  /// Where a relative file:// URI is looked for: GAZEBO_RESOURCE_PATH, then the engine's own
  /// resource folder (rotors_core_cpp/ holding media/materials/scripts/gazebo.material).
  static std::vector<std::string> ResourcePaths();
  /// The file a URI names, or throws SimError naming the URI and where it was looked for.
  /// model://NAME/... not found on the model paths is looked up in ROS package NAME (sdformat
  /// writes a URDF's package:// as model://).
  /// `base_file`: the SDF/URDF file the URI appears in ("" if it came from a string).
  static std::string Resolve(const std::string& uri, const std::string& base_file = "");
};

}  // namespace geometry
}  // namespace rotors_sim
