// What a plugin puts on its vehicle's bus about itself when it loads (VehicleBus::Register): the
// model it runs, with the parameters it read and validated, so that another engine (the batched
// flight engine's VehicleDescription) simulates the same vehicle from the plugins' own reading of
// the xacro, with their checks, and never reads a plugin's parameters a second time. ROS-free.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <variant>

#include <Eigen/Core>

#include "rotors_gazebo_plugins/models/imu_noise_model.h"
#include "rotors_gazebo_plugins/models/odometry_model.h"
#include "rotors_gazebo_plugins/models/rotor_model.h"
#include "rotors_gazebo_plugins/models/wind_field.h"
#include "rotors_gazebo_plugins/models/wind_model.h"

namespace rotors_gazebo_plugins {

/// A motor model: a rotor (motorType velocity: RotorS' equations with `params`), or a servo or a
/// joint effort (motorType position / force: no rotor).
struct MotorRecord {
  int motor_number = 0;
  std::string motor_type = "velocity";
  std::string joint_name, link_name;
  RotorParams params;     ///< a rotor's constants
  double slowdown = 1.0;  ///< rotorVelocitySlowdownSim: the joint turns omega / slowdown (visual only)
};

/// The odometry sensor.
struct OdometryRecord {
  std::string topic;  ///< odometryTopic as given (relative to the namespace)
  std::string link_name;
  int divisor = 1, delay_steps = 0;
  double unknown_delay_s = 0.0;
  bool outage_map = false;  ///< covarianceImage given
  OdometryNoiseParams noise;
  uint64_t seed = 0;
};

/// The IMU.
struct ImuRecord {
  std::string link_name;
  ImuNoiseParams noise;
  bool rotor_vibration = false;
  uint64_t seed = 0;
};

/// The wind plugin.
struct WindRecord {
  WindParams params;
  uint64_t seed = 0;
  std::string link_name;
  Eigen::Vector3d offset_L = Eigen::Vector3d::Zero();  ///< where the force acts, in the link frame
  std::string speed_topic;                             ///< windSpeedSubTopic: the speed comes over ROS ("" none)
  std::shared_ptr<const WindField> field;
  std::shared_ptr<const WindProfile> profile;
};

/// A plugin that only measures or records (a barometer, a bag): another engine may leave it out.
struct MeasuringRecord {
  std::string what;  ///< "pressure (/firefly/air_pressure)"
};

/// A plugin of the vehicle's plumbing that has no model of its own (the multirotor base plugin, the
/// controller interface): another engine has its own of both.
struct PlumbingRecord {};

using PluginRecord = std::variant<MotorRecord, OdometryRecord, ImuRecord, WindRecord, MeasuringRecord, PlumbingRecord>;

}  // namespace rotors_gazebo_plugins
