// Opaque handles of the rigid-body solver's objects. The engine's API owns these types: code that
// uses the engine (plugins, tests, the ROS server) never sees the solver's own types or headers,
// so the solver can change without touching them. Inside the engine, src/physics/ode_handles.h
// converts them to ODE's.
#pragma once

namespace rotors_sim {
namespace physics {

struct BodyHandle;          ///< a rigid body (links welded to it ride on it)
struct GeomHandle;          ///< a collision shape
struct JointHandle;         ///< a hinge or slider constraint
struct SolverWorldHandle;   ///< the dynamics world
struct SpaceHandle;         ///< the collision space
struct ContactGroupHandle;  ///< the contact joints of one step

}  // namespace physics
}  // namespace rotors_sim
