// Parameter helpers shared by all RotorS plugins: typed reads through the plugin's SdfParams
// (PluginBase::Params()), which records them so that the loader rejects every <plugin> child element
// the plugin did not read (a misspelt name is an error, not a silently ignored value as in RotorS
// issue #336).
#pragma once

#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <ignition/math/Vector3.hh>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/sdf_params.h"
#include "rotors_gazebo_plugins/models/imu_noise_model.h"
#include "rotors_gazebo_plugins/models/imu_vibration_model.h"
#include "rotors_gazebo_plugins/models/odometry_model.h"
#include "rotors_gazebo_plugins/models/rotor_model.h"
#include "rotors_gazebo_plugins/models/tilt_servo_model.h"
#include "rotors_gazebo_plugins/models/wind_model.h"

namespace rotors_gazebo_plugins {

using rotors_sim::ReadParam;
using rotors_sim::RequireParam;
using rotors_sim::SdfParams;

/// Reads "x y z" into an Eigen vector.
bool ReadVector(SdfParams& params, const std::string& name, Eigen::Vector3d* value);

/// Throws SimError("<what>") if `why` is not empty (for Params::Validate()).
void ThrowIfInvalid(const std::string& why);

/// The <robotNamespace> (required), without leading or trailing '/'.
std::string ReadRobotNamespace(SdfParams& params);

/// The link / joint of that name, or SimError("<param> 'name' is not a link of model 'm'").
rotors_sim::physics::LinkPtr RequireLink(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                         const char* param = "linkName");
rotors_sim::physics::JointPtr RequireJoint(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                           const char* param = "jointName");

/// Gazebo's PID elements (p, i, d, iMax, iMin, cmdMax, cmdMin) below the child element `name`, into
/// *pid: each required (require_all) or each optional over what *pid holds. False when there is no
/// such element; an element it does not know is refused by name.
bool ReadGazeboPid(SdfParams& params, const std::string& name, bool require_all, TiltServoParams* pid);

/// Seed from <randomEngineSeed> if given, else from the clock; returns the seed used.
uint64_t ReadSeed(SdfParams& params);

// The models' parameters as their plugins read them, one reader each: the plugins and the batched
// flight engine (rotors_sim.FlightBatch, which reads a spawned model's plugins) share them.

/// A motor plugin's rotor (motorType velocity): turningDirection and the seven constants, all
/// required (a missing constant would silently be another vehicle's), validated.
RotorParams ReadRotorParams(SdfParams& params);
/// rotorVelocitySlowdownSim (default 10, must be >= 1): the rotor joint turns this many times slower
/// than the rotor, so that rviz shows it without aliasing.
double ReadRotorSlowdown(SdfParams& params);
/// The wind plugin's windSpeed*, windForce* and windGust* parameters (RotorS' defaults), validated.
WindParams ReadWindParams(SdfParams& params);
/// The odometry plugin's noiseNormal* and noiseUniform* sigmas and bounds, validated.
OdometryNoiseParams ReadOdometryNoise(SdfParams& params);
/// The IMU plugin's noise densities, random walks, correlation times and turn-on biases, validated.
ImuNoiseParams ReadImuNoise(SdfParams& params);
/// The IMU's rotor vibration and ADIS16448 sampling (rotorVibration, balanceGrade, residualUnbalance,
/// bladeCount, bladePassThrustRipple, internalSampleRate, bartlettTaps, frameModeFrequency, frameModeDamping,
/// thrustNoiseDensity), validated.
ImuVibrationParams ReadImuVibration(SdfParams& params);

}  // namespace rotors_gazebo_plugins
