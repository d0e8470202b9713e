// SDF collision geometry -> ODE geom (engine internal).
#pragma once

#include <string>

#include <ode/ode.h>
#include <sdf/Geometry.hh>

namespace rotors_sim {

/// Creates the geom in `space`, or nullptr for an empty geometry. Throws SimError for geometry
/// that the engine does not support (naming `where`).
dGeomID CreateGeom(dSpaceID space, const sdf::Geometry& geometry, const std::string& where);

}  // namespace rotors_sim
