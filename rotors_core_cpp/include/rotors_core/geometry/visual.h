// What a collision or visual element looks like, kept by the engine for whoever draws the world
// (rviz markers now, the camera renderer later). Engine-free data.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "rotors_core/geometry/shapes.h"

namespace rotors_sim {
namespace physics {
class Link;
}
namespace geometry {

struct Shape {
  enum class Type { kBox, kSphere, kCylinder, kPlane, kMesh, kHeightmap, kOcTree };
  Type type = Type::kBox;
  ignition::math::Vector3d box_size_m;
  double radius_m = 0.0, length_m = 0.0;  ///< sphere, cylinder
  ignition::math::Vector3d plane_normal{0, 0, 1};
  ignition::math::Vector3d plane_size_m{100, 100, 0};
  std::string mesh_file;  ///< resolved path (mesh, octomap)
  std::array<double, 3> mesh_scale{1, 1, 1};
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const HeightField> heightfield;  ///< in the element's frame
  std::shared_ptr<const octomap::OcTree> octree;   ///< in the element's frame
};

/// One texture of a heightmap (SDF <heightmap><texture>): its diffuse image, repeated every size_m,
/// and (from the second on) the <blend> that lays it over the ones before: from min_height_m up,
/// faded in over fade_m (heights in the visual frame). An image that is not here: "" (the visual's
/// colour in its place).
struct TerrainLayer {
  std::string diffuse_file;
  double size_m = 1.0;
  double min_height_m = 0.0, fade_m = 0.0;
};

/// A <visual> (or, for a model without visuals, nothing: collisions are not drawn).
struct Visual {
  std::string scoped_name;  ///< "model::link::visual"
  physics::Link* link = nullptr;
  ignition::math::Pose3d X_LV;  ///< visual frame in the link frame
  Shape shape;
  std::array<float, 4> rgba{0.7f, 0.7f, 0.7f, 1.0f};
  bool has_material = false;  ///< rgba from an SDF/URDF <material>: it overrides a mesh's own colours
  /// A material script's texture (OGRE texture_unit) on a primitive: its image file, and the
  /// texture scale (texture coordinates 0..1 per face of a box or over a plane, divided by it)
  std::string texture_file;
  std::array<float, 2> texture_scale{1.0f, 1.0f};
  float texture_max_anisotropy = 1.0f;       ///< 1: trilinear only
  bool cast_shadows = true;                  ///< <cast_shadows>: drawn into the sun's shadow map
  std::vector<TerrainLayer> terrain_layers;  ///< a heightmap's textures, blended by height (at most 4)
};

}  // namespace geometry
}  // namespace rotors_sim

namespace rotors_sim {
namespace geometry {

/// How the world is lit (SDF <light type="directional"> and <scene>), for whoever renders it.
struct Lighting {
  ignition::math::Vector3d sun_direction_W{-0.5, 0.1, -0.9};  ///< direction the light travels
  float sun_diffuse = 0.8f;                                   ///< grey level of the sun's diffuse colour
  float ambient = 0.4f;                                       ///< <scene><ambient>
  std::array<float, 3> background{0.7f, 0.7f, 0.7f};          ///< <scene><background>
  /// The sun casts shadows: <scene><shadows> (true unless set) and the sun's <cast_shadows>
  bool shadows = false;
};

}  // namespace geometry
}  // namespace rotors_sim
