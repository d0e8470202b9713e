// Gazebo's material scripts: <material><script><uri>folders</uri><name>X</name></script> names a
// material of the OGRE .material files in those folders; its first pass gives the colours and
// the first texture unit the texture (its file in one of the folders) and the texture scale.
// Engine-free: parsing and file lookup only.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace rotors_sim {
namespace geometry {

struct OgreMaterial {
  std::array<float, 4> ambient{1, 1, 1, 1};
  std::array<float, 4> diffuse{1, 1, 1, 1};
  std::string texture;               ///< the texture_unit's image file name, or empty
  std::array<float, 2> scale{1, 1};  ///< texture_unit scale: 0.1 repeats the texture 10 times
  float max_anisotropy = 1.0f;       ///< texture_unit max_anisotropy with "filtering anisotropic"
};

/// Every material of one .material file's text (a syntax error: SimError naming `source` and the line).
std::map<std::string, OgreMaterial> ParseOgreMaterials(const std::string& text, const std::string& source);

/// The material `name` from the .material files in `uris` (folders or files, resolved), its texture
/// made an absolute path found in one of the folders; SimError naming what was searched when the
/// material or its texture is not there.
OgreMaterial FindOgreMaterial(const std::vector<std::string>& uris, const std::string& name);

}  // namespace geometry
}  // namespace rotors_sim
