// The bounding radius of a URDF mesh (package:// or file:// or a path), read with assimp.
#pragma once

#include <string>

namespace rotors_planning {

/// [m] the largest distance of the mesh's vertices from its origin, unscaled. Throws
/// std::invalid_argument naming the file when it cannot be found or read.
double MeshRadius_m(const std::string& uri);

}  // namespace rotors_planning
