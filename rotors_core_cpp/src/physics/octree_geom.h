// An OctoMap as an ODE geometry (engine internal): every occupied leaf is a solid cube. A body
// colliding with it is tested against the cubes of the leaves inside its bounding box only, so
// the cost does not grow with the size of the map.
#pragma once

#include <memory>

#include <ode/ode.h>

namespace octomap {
class OcTree;
}

namespace rotors_sim {

/// A static geom in `space` holding `tree` (kept alive by the geom), its origin at p_W.
dGeomID CreateOcTreeGeom(dSpaceID space, std::shared_ptr<const octomap::OcTree> tree, const double p_W[3]);

bool IsOcTreeGeom(dGeomID g);

/// Volume test for mapping (not contacts: those leave out faces inside the solid): whether an
/// occupied leaf overlaps the axis-aligned box of edge `lengths` [m] centred at centre_W.
bool OcTreeGeomOverlapsBox(dGeomID g, const double centre_W[3], const double lengths[3]);

}  // namespace rotors_sim
