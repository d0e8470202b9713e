// The headers every plugin library parses (about 280,000 preprocessed lines: roscpp, Eigen,
// sdformat, ignition math, the engine's physics and plugin API), compiled once for
// rotors_gazebo_plugins_common and reused by each plugin library (CMakeLists.txt): a plugin compiles
// in half the time. Only headers of installed packages and of rotors_core, none generated in the
// workspace, so the precompiled header needs nothing built before it.
#pragma once

#include <ros/ros.h>

#include <Eigen/Geometry>
#include <ignition/math/Pose3.hh>
#include <sdf/Element.hh>

#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
