// What the three autopilot interface plugins share (PX4's MAVLink, ArduPilot's JSON, Betaflight's
// SITL packets): the vehicle's state and sensor readings at each step (VehicleSnapshot), RotorS'
// <control_channels> from the autopilot's outputs to the motor command, the disarmed command when
// the link is lost, and one-line errors at most once a second per kind. Each protocol is a subclass
// that opens its links and, once per physics step before the step (world_update_begin), exchanges
// the snapshot for the autopilot's outputs (Exchange).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rotors_core/event.h"
#include "rotors_core/physics/physics_types.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/autopilot/control_channels.h"
#include "rotors_gazebo_plugins/autopilot/vehicle_snapshot.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class AutopilotInterface : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) final;
  void Reset() final;

 protected:
  /// Reads the protocol's own parameters through Params() and opens its links (SimError on bad ones).
  virtual void LoadProtocol() = 0;
  /// How many outputs the autopilot sends (input_index must be below it).
  virtual int OutputCount() const = 0;
  /// Once per step, before it: send what the autopilot reads, take what it answers (Apply / ApplyDisarmed).
  virtual void Exchange(const VehicleSnapshot& s) = 0;
  /// The world went back (reset): the next answer starts a new exchange.
  virtual void OnReset() {}
  /// For messages: "[px4_mavlink] model 'firefly'".
  virtual const char* Tag() const = 0;

  /// Outputs `u` (normalized: motors 0..1, servos -1..1) through the control channels to the motors.
  void Apply(const std::vector<double>& u, bool armed);
  /// The disarmed values (zero_position_disarmed) on every channel, once per `why` (a lost link).
  void ApplyDisarmed();
  /// The channels' references to the vehicle: motors and servos, and a fixed wing's normalized channels.
  void Command(const std::vector<double>& references);
  /// The snapshot with the ground truth's rates and specific force as its IMU reading when the vehicle
  /// has no IMU plugin (ArduPilot's and Betaflight's state always carries an IMU; PX4 gets none).
  static VehicleSnapshot WithTruthForMissingImu(VehicleSnapshot s);
  /// One line on stderr/rosconsole, at most once a second of wall time per kind of fault (`kind` and
  /// the line without its numbers).
  void Error(const std::string& kind, const std::string& line);
  void Info(const std::string& line);

  const std::string& Namespace() const { return namespace_; }
  /// The world's physics step and its sim time now [s].
  double PhysicsStep_s() const;
  double SimTime_s() const;
  VehicleBus& Bus() const { return *bus_; }

 private:
  VehicleSnapshot Snapshot();
  /// The feed (on the vehicle bus) of the sensor publishing on <param> (default_topic when absent);
  /// nullptr for an empty topic (the autopilot does without that sensor).
  template <class Reading>
  const SensorFeed<Reading>* FeedOf(SensorFeeds<Reading>& feeds, const std::string& param,
                                    const std::string& default_topic);
  void ReadControlChannels();
  /// Without <control_channels>: one per motor (false and a line when the autopilot has too few outputs).
  bool MakeDefaultChannels();

  std::string namespace_, model_name_;
  rotors_sim::physics::World* world_ = nullptr;
  rotors_sim::physics::LinkPtr link_;
  std::shared_ptr<VehicleBus> bus_;
  std::vector<ControlChannel> given_channels_;
  bool channels_given_ = false;
  ControlChannels channels_;  ///< made at the first step (the default needs every motor registered)
  bool channels_ready_ = false;
  const SensorFeed<ImuReading>* imu_ = nullptr;
  const SensorFeed<MagnetometerReading>* mag_ = nullptr;
  const SensorFeed<BarometerReading>* baro_ = nullptr;
  const SensorFeed<GpsReading>* gps_ = nullptr;
  const SensorFeed<GroundSpeedReading>* ground_speed_ = nullptr;
  const SensorFeed<RangeReading>* range_ = nullptr;
  const SensorFeed<OpticalFlowReading>* flow_ = nullptr;
  const SensorFeed<AirspeedReading>* airspeed_ = nullptr;
  std::map<std::string, std::chrono::steady_clock::time_point> last_error_;
  rotors_sim::event::ConnectionPtr update_;
};

}  // namespace rotors_gazebo_plugins
