// Engine-internal: the opaque solver handles of the public API (rotors_core/physics/solver_handles.h)
// are ODE's objects. Ode() and Handle() convert between the two; nothing outside the engine (src/) does.
#pragma once

#include <ode/ode.h>

#include "rotors_core/physics/solver_handles.h"

namespace rotors_sim {
namespace physics {

inline dBodyID Ode(BodyHandle* h) { return reinterpret_cast<dBodyID>(h); }
inline dGeomID Ode(GeomHandle* h) { return reinterpret_cast<dGeomID>(h); }
inline dJointID Ode(JointHandle* h) { return reinterpret_cast<dJointID>(h); }
inline dWorldID Ode(SolverWorldHandle* h) { return reinterpret_cast<dWorldID>(h); }
inline dSpaceID Ode(SpaceHandle* h) { return reinterpret_cast<dSpaceID>(h); }
inline dJointGroupID Ode(ContactGroupHandle* h) { return reinterpret_cast<dJointGroupID>(h); }

inline BodyHandle* Handle(dBodyID b) { return reinterpret_cast<BodyHandle*>(b); }
inline GeomHandle* Handle(dGeomID g) { return reinterpret_cast<GeomHandle*>(g); }
inline JointHandle* Handle(dJointID j) { return reinterpret_cast<JointHandle*>(j); }
inline SolverWorldHandle* Handle(dWorldID w) { return reinterpret_cast<SolverWorldHandle*>(w); }
inline SpaceHandle* Handle(dSpaceID s) { return reinterpret_cast<SpaceHandle*>(s); }
inline ContactGroupHandle* Handle(dJointGroupID g) { return reinterpret_cast<ContactGroupHandle*>(g); }

}  // namespace physics
}  // namespace rotors_sim
