// Loading controller and vehicle parameters from a node's private namespace (the layout of
// lee_controller_<mav>.yaml and <mav>.yaml), under one policy: a missing required parameter is one
// line naming it (the node stops), an optional one that is absent is announced with the value used,
// and a key the node never reads is reported by name (a typo would otherwise go unnoticed).
#pragma once

#include <string>
#include <vector>

#include <ros/ros.h>

#include "rotors_params/ros_param_reader.h"

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_position_controller.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

/// Reads parameters below one node handle and remembers every name it was asked for (the
/// project's one parameter reader, shared with the estimator).
using ParameterReader = rotors_params::RosParamReader;

/// mass, inertia/{xx, yy, zz} (off-diagonal terms optional, 0), rotor_configuration/<i>/{angle,
/// arm_length, rotor_force_constant, rotor_moment_constant, direction}, optional max_rot_velocity and
/// gravity (announced when absent: 9.81, RotorS' value). "" or the reason naming the parameter.
std::string LoadVehicleParameters(ParameterReader& reader, VehicleParameters* vehicle);
/// attitude_gain and angular_rate_gain {x, y, z}, both required.
std::string LoadAttitudeGains(ParameterReader& reader, AttitudeGains* gains);
/// position_gain, velocity_gain, the attitude gains, the vehicle and the optional max_tilt_angle.
std::string LoadLeeParameters(ParameterReader& reader, LeePositionControllerParameters* params);

/// Logs the announcements and unknown keys of `reader` (one line each) with the node's tag.
void ReportParameters(const ParameterReader& reader, const std::string& tag);

}  // namespace rotors_control
