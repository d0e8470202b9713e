// What the batched flight engine needs to know of a multirotor, read from the model the full world
// spawned from the same xacro: the solver body's mass and inertia, each rotor's mount and RotorS
// constants, the odometry sensor, the IMU and the wind as their plugins registered them on the
// vehicle bus when they loaded (plugin_records.h: the parameters they read and validated). One
// source of truth: a change in the xacro or a yaml reaches both engines.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_core/physics/physics_types.h"
#include "rotors_gazebo_plugins/plugin_records.h"
#include "rotors_gazebo_plugins/models/rotor_model.h"
#include "rotors_gazebo_plugins/models/wind_field.h"
#include "rotors_gazebo_plugins/models/wind_model.h"

namespace rotors_flight_batch {

/// A point of the vehicle in the body frame B (origin at the CoG, axes of the model frame).
struct Mount {
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();             ///< [m]
  Eigen::Quaterniond q_BS = Eigen::Quaterniond::Identity();  ///< the frame mounted there
};

/// One rotor: RotorS' constants (the motor plugin's reader) and where it sits and turns.
struct RotorMount {
  rotors_gazebo_plugins::RotorParams params;
  int motor_number = 0;
  Eigen::Vector3d p_B_origin = Eigen::Vector3d::Zero();  ///< rotor link origin (its airspeed) [m]
  Eigen::Vector3d p_B_cog = Eigen::Vector3d::Zero();     ///< rotor link CoG (where its force acts) [m]
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitZ();     ///< the rotor frame's z (thrust direction)
  double spin_inertia_kg_m2 = 0.0;                       ///< J_a of the rotor about its axis (the kinematic joint's)
  double slowdown = 10.0;                                ///< rotorVelocitySlowdownSim: the joint turns omega / slowdown
};

/// The odometry sensor as its plugin loaded it (topic, divisor, delays, noise, randomEngineSeed), and
/// where it sits.
struct OdometryDescription : rotors_gazebo_plugins::OdometryRecord {
  Mount mount;
};

/// The IMU as its plugin loaded it (noise, seed), and where it sits.
struct ImuDescription : rotors_gazebo_plugins::ImuRecord {
  Mount mount;
};

struct WindDescription {
  rotors_gazebo_plugins::WindParams params;
  uint64_t seed = 0;
  Eigen::Vector3d p_B_link = Eigen::Vector3d::Zero();   ///< the wind link's origin (the field's sample)
  Eigen::Vector3d p_B_force = Eigen::Vector3d::Zero();  ///< where the wind force acts (link + xyzOffset)
  bool before_motors = false;  ///< the plugin runs before the motors (they see this step's wind speed)
  std::shared_ptr<const rotors_gazebo_plugins::WindField> field;
  std::shared_ptr<const rotors_gazebo_plugins::WindProfile> profile;
};

struct VehicleDescription {
  std::string model_name, robot_namespace;
  double mass_kg = 0.0;
  Eigen::Matrix3d inertia_B_kg_m2 = Eigen::Matrix3d::Identity();  ///< about the CoG, body frame
  Eigen::Vector3d p_M_cog = Eigen::Vector3d::Zero();              ///< the CoG (body origin) in the model frame
  std::vector<RotorMount> rotors;                                 ///< by motor number
  std::optional<OdometryDescription> odometry;
  std::optional<ImuDescription> imu;
  std::optional<WindDescription> wind;
  std::vector<Eigen::Vector3d> contact_points_B;  ///< corners of the collision bounding box
  /// The radius [m] of the sphere about the CoG that holds every visual and collision of the vehicle
  /// (its rotors' discs too): what touches an obstacle.
  double reach_m = 0.0;
  Eigen::Vector3d gravity_W{0.0, 0.0, -9.8};
  double step_s = 0.001;
  std::vector<std::string> left_out;  ///< plugins that only measure and are not simulated here
};

/// The description of `model`, spawned at rest with zero roll and pitch. Throws SimError naming
/// what the batch cannot simulate (cameras, lasers, servos, fixed wings, autopilot links, several
/// bodies). `odometry_topic` picks the odometry plugin (by its odometryTopic) the batch simulates.
VehicleDescription DescribeVehicle(const rotors_sim::physics::Model& model, const std::string& odometry_topic);

}  // namespace rotors_flight_batch
