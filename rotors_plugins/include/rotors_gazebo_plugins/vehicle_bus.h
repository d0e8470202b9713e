// In-process data shared by the plugins of one vehicle (keyed by world and robot namespace): the latest
// motor command (controller interface -> motor models, no ROS round trip), the real rotor speeds
// (motor models -> multirotor base, bag), the wind velocity (wind plugin -> motor models), injected
// motor faults (multirotor base's service -> motor models) and every sensor's latest reading
// (sensor plugins -> autopilot interfaces, the Python module; sensor_feeds.h).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rotors_core/event.h"
#include "rotors_gazebo_plugins/plugin_records.h"
#include "rotors_gazebo_plugins/sensor_feeds.h"

namespace rotors_sim {
class ModelPlugin;
namespace physics {
class World;
class Link;
}  // namespace physics
}  // namespace rotors_sim

namespace rotors_gazebo_plugins {

/// A motor that turns at speed_factor times its command from start_time_s on (0: failed).
struct MotorFault {
  double speed_factor = 1.0;
  double start_time_s = 0.0;  ///< [s] sim time
};

/// A rotor as its motor model mounts it (what an IMU needs to feel its vibration).
struct RotorMounting {
  std::shared_ptr<const rotors_sim::physics::Link> link;  ///< the rotor link (its hub is the link origin)
  Eigen::Vector3d axis_L = Eigen::Vector3d::UnitZ();      ///< spin axis, link frame (a positive speed turns about it)
  double rotor_mass_kg = 0.0;
  double motor_constant = 0.0;  ///< C_T [N/(rad/s)^2]
};

struct VehicleBus {
  std::vector<double> motor_command_rad_s;     ///< empty until the first valid command
  uint64_t motor_command_count = 0;            ///< valid commands so far (any source)
  std::vector<double> rotor_speed_rad_s;       ///< signed real speed per motor number
  int rotor_count = 0;                         ///< motor models registered (rotors and servos)
  std::vector<bool> is_servo;                  ///< per motor number: a servo (its command and "speed" are angles [rad])
  std::vector<double> max_rot_velocity_rad_s;  ///< per motor number: the motor model's maxRotVelocity (0: a servo)
  std::vector<RotorMounting> rotor_mountings;  ///< per motor number (no link: a servo, or not registered)
  Eigen::Vector3d wind_velocity_W = Eigen::Vector3d::Zero();  ///< [m/s]
  std::vector<MotorFault> motor_faults;                       ///< per motor number (healthy by default)
  /// Fixed wings: RotorS' normalized actuator command (mav_msgs/Actuators.normalized, by channel).
  std::vector<double> normalized_command;  ///< empty until the first valid command
  uint64_t normalized_command_count = 0;
  int normalized_channels = 0;  ///< how many channels the vehicle's fixed-wing plugin reads (0: none)
  /// The fixed-wing plugin's check of a normalized command ("" or why not: a deflection out of range)
  std::function<std::string(const std::vector<double>&)> normalized_check;

  /// RC channels [us] an autopilot interface forwards to its firmware (Betaflight's RC packet): AETR,
  /// then AUX1.. (ROS: the interface's rc topic; Python: World.set_rc).
  std::vector<int> rc_channels_us;
  uint64_t rc_count = 0;
  /// Outputs the vehicle's autopilot interface has applied so far (its answers).
  uint64_t autopilot_answers = 0;
  /// Each sensor's latest reading, by its resolved topic (a world reset makes them stale).
  SensorReadings sensors;

  /// What `plugin` (of this vehicle's model) loaded with: its model and validated parameters
  /// (plugin_records.h). A plugin registers once, at the end of its Load.
  void Register(const rotors_sim::ModelPlugin* plugin, PluginRecord record) { records_[plugin] = std::move(record); }
  /// The record `plugin` registered, nullptr when it registered none (a plugin another engine
  /// cannot stand in for: an autopilot link, a fixed wing's aerodynamics, a camera).
  const PluginRecord* RecordOf(const rotors_sim::ModelPlugin* plugin) const {
    auto it = records_.find(plugin);
    return it == records_.end() ? nullptr : &it->second;
  }

  /// The bus of a namespace in a world, shared by the plugins of the vehicle that hold it. It lives
  /// as long as one of them: a model deleted and re-spawned under the same namespace (with another
  /// rotor count, too) starts on a fresh bus. Buses live in the world (World::PluginState), so two
  /// worlds in one process with the same vehicle name never share motor commands.
  static std::shared_ptr<VehicleBus> For(rotors_sim::physics::World& world, const std::string& robot_namespace);
  void RegisterRotor(int motor_number, double max_rot_velocity_rad_s = 0.0);
  /// A rotor's mounting, registered by its motor model when it loads.
  void RegisterRotorMounting(int motor_number, const RotorMounting& mounting);
  /// A position-controlled motor (the omav's tilt units): its command entry is an angle [rad], any sign.
  void RegisterServo(int motor_number);
  /// The one way in for motor commands (the controller interface's ROS topics, the Python module):
  /// "" and the command in force, or the reason it was refused (wrong length, NaN, inf, a negative rotor speed),
  /// the last valid command staying in force.
  std::string SetMotorCommand(const std::vector<double>& speeds_rad_s);
  /// The one way in for a fixed wing's normalized command (surfaces and throttle by channel): "" or
  /// why it was refused (no fixed-wing plugin, too few channels, NaN or inf).
  std::string SetNormalizedCommand(const std::vector<double>& normalized);
  /// The one way in for RC channels: "" or why they were refused (more than 16, or outside 800..2200 us).
  std::string SetRcChannels(const std::vector<int>& channels_us);
  /// The factor motor `motor_number`'s command is scaled by at sim time t_s.
  double SpeedFactor(int motor_number, double t_s) const {
    if (motor_number >= static_cast<int>(motor_faults.size())) return 1.0;
    const MotorFault& f = motor_faults[motor_number];
    return t_s >= f.start_time_s ? f.speed_factor : 1.0;
  }

 private:
  rotors_sim::event::ConnectionPtr reset_connection_;  ///< the world's reset: sensors.Forget()
  std::map<const rotors_sim::ModelPlugin*, PluginRecord> records_;
};

}  // namespace rotors_gazebo_plugins
