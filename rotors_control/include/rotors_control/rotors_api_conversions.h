// RotorS' parameter types (parameters.h, common.h) to our controller library's (vehicle_parameters.h,
// lee_controller.h): what the RotorS API classes hand to our control laws.
#pragma once

#include "rotors_control/common.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/parameters.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

MultirotorParameters MultirotorFromRotorS(const VehicleParameters& vehicle);

/// The reference our Lee controller takes from mav_msgs' trajectory point (position, velocity,
/// acceleration, yaw and yaw rate); used by RotorS' API class and by our node.
inline TrajectoryPoint TrajectoryPointFromEigen(const mav_msgs::EigenTrajectoryPoint& e) {
  TrajectoryPoint p;
  p.position_W = e.position_W;
  p.velocity_W = e.velocity_W;
  p.acceleration_W = e.acceleration_W;
  p.yaw_rad = e.getYaw();
  p.yaw_rate_rad_s = e.getYawRate();
  return p;
}
VehicleState VehicleStateFromRotorS(const EigenOdometry& odometry);

}  // namespace rotors_control
