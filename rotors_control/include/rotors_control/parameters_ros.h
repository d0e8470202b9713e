// Loading controller and vehicle parameters from a node's private namespace (the layout of
// lee_controller_<mav>.yaml and <mav>.yaml), under one policy: a missing required parameter is one
// line naming it (the node stops), an optional one that is absent is announced with the value used,
// and a key the node never reads is reported by name (a typo would otherwise go unnoticed).
#pragma once

#include <set>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_position_controller.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

/// Reads parameters below one node handle and remembers every name it was asked for.
class ParameterReader {
 public:
  explicit ParameterReader(const ros::NodeHandle& nh) : nh_(nh) {}

  /// "" or "missing parameter <full name> (<hint>)".
  std::string Require(const std::string& name, double* value, const std::string& hint);
  /// Keeps *value when absent; returns the line announcing the default then, else "".
  std::string Optional(const std::string& name, double* value, const std::string& meaning);
  /// A gain {x, y, z}; "" or the reason.
  std::string RequireVector(const std::string& name, Eigen::Vector3d* value, const std::string& hint);
  bool Has(const std::string& name) const { return nh_.hasParam(name); }
  std::string Resolve(const std::string& name) const { return nh_.resolveName(name); }

  /// Parameters below the node handle that no Require/Optional asked for (full names).
  std::vector<std::string> UnknownKeys() const;
  /// The announcements of absent optional parameters, in the order asked.
  const std::vector<std::string>& Defaults() const { return defaults_; }

 private:
  ros::NodeHandle nh_;
  std::set<std::string> asked_;  // resolved names
  std::vector<std::string> defaults_;
};

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
