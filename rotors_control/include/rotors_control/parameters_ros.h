// Loading controller and vehicle parameters from a node's private namespace (the layout of
// lee_controller_<mav>.yaml and <mav>.yaml).
#pragma once

#include <string>

#include <ros/ros.h>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_position_controller.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

/// mass, inertia/{xx..zz}, rotor_configuration/<i>/{angle, arm_length, rotor_force_constant,
/// rotor_moment_constant, direction} and the optional gravity (default 9.81). Returns "" or the
/// reason naming the missing or bad parameter.
std::string LoadVehicleParameters(const ros::NodeHandle& nh, VehicleParameters* vehicle);
/// A gain {x, y, z}; keeps *gain when absent. "" or the reason.
std::string LoadGain(const ros::NodeHandle& nh, const std::string& name, Eigen::Vector3d* gain);
std::string LoadAttitudeGains(const ros::NodeHandle& nh, AttitudeGains* gains);
std::string LoadLeeParameters(const ros::NodeHandle& nh, LeePositionControllerParameters* params);

}  // namespace rotors_control
