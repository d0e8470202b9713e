// An OctoMap of a world's static collision geometry inside a box (what RotorS' octomap plugin
// serves on world/get_octomap). Cells are the octree's own cells at the requested resolution; a
// cell is occupied when its cube overlaps a static collision (a cube is tested first for a
// whole block of cells, and split only where it hits something).
#pragma once

#include <memory>

#include <ignition/math/Vector3.hh>

#include "rotors_core/physics/physics_types.h"

namespace octomap {
class OcTree;
}

namespace rotors_sim {
namespace geometry {

struct OccupancyRequest {
  ignition::math::Vector3d center_W;   ///< [m] centre of the box
  ignition::math::Vector3d lengths_m;  ///< [m] edge lengths of the box
  double leaf_size_m = 0.25;           ///< [m] octree resolution
  std::string Validate() const;        ///< empty when valid, else a one-line reason
};

/// Occupied leaves only; free space stays unknown. Throws SimError for an invalid request.
std::unique_ptr<octomap::OcTree> BuildOccupancy(const physics::World& world, const OccupancyRequest& request);

}  // namespace geometry
}  // namespace rotors_sim
