// Loading controller and vehicle parameters from a node's private namespace (the loaders of
// parameter_loading.h with a RosParamReader), under one policy: a missing required parameter is one
// line naming it (the node stops), an optional one that is absent is announced with the value used,
// and a key the node never reads is reported by name (a typo would otherwise go unnoticed).
#pragma once

#include <string>
#include <vector>

#include <ros/ros.h>

#include "rotors_params/ros_param_reader.h"

#include "rotors_control/parameter_loading.h"

namespace rotors_control {

/// Reads parameters below one node handle and remembers every name it was asked for (the
/// project's one parameter reader, shared with the estimator).
using ParameterReader = rotors_params::RosParamReader;

/// Logs the announcements and unknown keys of `reader` (one line each) with the node's tag.
void ReportParameters(const ParameterReader& reader, const std::string& tag);

}  // namespace rotors_control
