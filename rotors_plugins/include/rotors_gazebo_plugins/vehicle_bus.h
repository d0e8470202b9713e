// In-process data shared by the plugins of one vehicle (keyed by robot namespace): the latest
// motor command (controller interface -> motor models, no ROS round trip), the real rotor speeds
// (motor models -> multirotor base, bag) and the wind velocity (wind plugin -> motor models).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

struct VehicleBus {
  std::vector<double> motor_command_rad_s;   ///< empty until the first valid command
  std::vector<double> rotor_speed_rad_s;     ///< signed real speed per motor number
  int rotor_count = 0;                       ///< number of motor models registered
  Eigen::Vector3d wind_velocity_W = Eigen::Vector3d::Zero();  ///< [m/s]

  /// The bus of a namespace (created on first use; lives as long as the process).
  static VehicleBus& For(const std::string& robot_namespace);
  /// Drops a namespace's bus (when its model is deleted, so a re-spawn starts clean).
  static void Release(const std::string& robot_namespace);
  void RegisterRotor(int motor_number);
};

}  // namespace rotors_gazebo_plugins
