// RotorS' rosparam helpers of the rotors_control API (RotorS' include/rotors_control/parameters_ros.h): a parameter
// with a default (announced when absent), and the vehicle (mass, inertia, rotor_configuration/<i>/...) as <mav>.yaml
// lays it out. Our own nodes use parameter_report_ros.h, which also names unread keys.
#pragma once

#include <map>
#include <string>

#include <ros/ros.h>

#include "rotors_control/parameters.h"

namespace rotors_control {

template <typename T>
inline void GetRosParameter(const ros::NodeHandle& nh, const std::string& key, const T& default_value, T* value) {
  ROS_ASSERT(value != nullptr);
  if (nh.getParam(key, *value)) return;
  ROS_WARN_STREAM("[rosparam]: could not find parameter " << nh.getNamespace() << "/" << key
                                                          << ", setting to default: " << default_value);
  *value = default_value;
}

/// rotor_configuration/0, /1, ... until one is missing; the default configuration stays when there
/// is none. Each rotor's absent fields keep Rotor's defaults.
inline void GetRotorConfiguration(const ros::NodeHandle& nh, RotorConfiguration* rotor_configuration) {
  std::map<std::string, double> fields;
  for (unsigned int i = 0; nh.getParam("rotor_configuration/" + std::to_string(i), fields); ++i) {
    if (i == 0) rotor_configuration->rotors.clear();
    const std::string prefix = "rotor_configuration/" + std::to_string(i) + "/";
    Rotor rotor;
    nh.getParam(prefix + "angle", rotor.angle);
    nh.getParam(prefix + "arm_length", rotor.arm_length);
    nh.getParam(prefix + "rotor_force_constant", rotor.rotor_force_constant);
    nh.getParam(prefix + "rotor_moment_constant", rotor.rotor_moment_constant);
    nh.getParam(prefix + "direction", rotor.direction);
    rotor_configuration->rotors.push_back(rotor);
  }
}

/// mass, inertia/{xx, xy, xz, yy, yz, zz} (symmetric) and the rotor configuration.
inline void GetVehicleParameters(const ros::NodeHandle& nh, VehicleParameters* vehicle_parameters) {
  GetRosParameter(nh, "mass", vehicle_parameters->mass_, &vehicle_parameters->mass_);
  Eigen::Matrix3d& J = vehicle_parameters->inertia_;
  const char* names[3][3] = {{"xx", "xy", "xz"}, {"xy", "yy", "yz"}, {"xz", "yz", "zz"}};
  for (int row = 0; row < 3; ++row) {
    for (int col = row; col < 3; ++col) {
      GetRosParameter(nh, std::string("inertia/") + names[row][col], J(row, col), &J(row, col));
      J(col, row) = J(row, col);
    }
  }
  GetRotorConfiguration(nh, &vehicle_parameters->rotor_configuration_);
}

}  // namespace rotors_control
