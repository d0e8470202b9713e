// The parts of the rotors_sim._engine module (pybind11).
#pragma once

#include <Eigen/Core>
#include <pybind11/pybind11.h>

#include "rotors_control/lee_controller.h"

namespace rotors_sim {
namespace physics {
class World;
}
}  // namespace rotors_sim

namespace rotors_python {

/// A controller that answers each odometry message with rotor speeds [rad/s], as the ROS
/// controller nodes do. A World can run it in C++ at every new message (World.attach_controller).
class OdometryController {
 public:
  virtual ~OdometryController() = default;
  virtual Eigen::VectorXd Answer(const rotors_control::VehicleState& state, double stamp_s) = 0;
};

/// The state as the ROS nodes take it from nav_msgs/Odometry (mav_msgs::eigenOdometryFromMsg):
/// the quaternion normalized (identity when about 0), velocities in the body frame.
rotors_control::VehicleState StateFromOdometry(const Eigen::Vector3d& position_W, const Eigen::Vector4d& q_xyzw,
                                               const Eigen::Vector3d& velocity_B,
                                               const Eigen::Vector3d& angular_velocity_B);

/// The engine's world inside a rotors_sim._engine.World (SimError for anything else).
rotors_sim::physics::World& PhysicsWorldOf(const pybind11::handle& world);

void BindWorld(pybind11::module_& m);
void BindControllers(pybind11::module_& m);
void BindFrames(pybind11::module_& m);
void BindFlightBatch(pybind11::module_& m);
void BindRowMath(pybind11::module_& m);
}  // namespace rotors_python
