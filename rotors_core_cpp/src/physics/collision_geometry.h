// SDF geometry -> engine shapes and ODE geoms (engine internal).
#pragma once

#include <memory>
#include <string>

#include <ode/ode.h>
#include <sdf/Geometry.hh>

#include "rotors_core/geometry/visual.h"

namespace rotors_sim {

/// Reads an SDF <geometry> (resolving mesh and image URIs relative to `sdf_file`). Throws
/// SimError naming `where`, the file and the problem.
geometry::Shape ReadShape(const sdf::Geometry& geometry, const std::string& where, const std::string& sdf_file);

/// An ODE geom in `space` for a shape, with what it needs kept alive. `X_CG` is the geom's pose
/// in the collision frame (identity but for heightfields, which ODE builds with y up).
struct CreatedGeom {
  dGeomID geom = nullptr;
  std::shared_ptr<void> keep_alive;
  ignition::math::Pose3d X_CG;
};
/// nullptr geom for an empty geometry. An octomap geom takes the position `p_WC` (it cannot be
/// rotated: one line if `X_WC` has a rotation).
CreatedGeom CreateGeom(dSpaceID space, const geometry::Shape& shape, const ignition::math::Pose3d& X_WC, bool on_body,
                       const std::string& where);

}  // namespace rotors_sim
