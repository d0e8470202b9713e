// PX4's simulator protocol (src/modules/simulation/simulator_mavlink/SimulatorMavlink.cpp), engine-
// and ROS-free: the messages the simulator sends, built from a VehicleSnapshot in PX4's units and
// frames (NED world, FRD body), and MAVLink 2 framing both ways on the C headers pymavlink's
// mavgen generates from the MAVLink project's common.xml at build time.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/mavlink.h"
#include "rotors_gazebo_plugins/autopilot/vehicle_snapshot.h"

namespace rotors_gazebo_plugins {
namespace px4 {

/// HIL_SENSOR fields_updated bits, as PX4 reads them
constexpr uint32_t kAccel = 0x7, kGyro = 0x38, kMag = 0x1C0, kAbsPressure = 0x200, kDiffPressure = 0x400,
                   kPressureAlt = 0x800, kTemperature = 0x1000;
constexpr uint32_t kBaro = kAbsPressure | kPressureAlt | kTemperature;
/// HIL_ACTUATOR_CONTROLS.mode bit: armed (MAV_MODE_FLAG_SAFETY_ARMED)
constexpr uint8_t kArmed = MAV_MODE_FLAG_SAFETY_ARMED;
/// HIL_ACTUATOR_CONTROLS.flags bit 0: PX4 runs lockstep
constexpr uint64_t kLockstepFlag = 1;

/// The time_usec of the messages: sim time in whole microseconds (HIL_SENSOR's; PX4 in lockstep
/// stamps its HIL_ACTUATOR_CONTROLS with the HIL_SENSOR time it last took).
uint64_t Microseconds(double t_s);

/// IMU (always), magnetometer, barometer and differential pressure (each when `new_*`), as
/// fields_updated says; accelerometer and gyroscope in body FRD, the field in gauss.
mavlink_hil_sensor_t HilSensor(const VehicleSnapshot& s, bool new_mag, bool new_baro, bool new_diff_pressure);
/// The GPS plugin's reading: 1e-7 deg, mm, cm/s NED, eph/epv in cm from its standard deviations;
/// time_usec UTC (PX4 takes it as the fix's UTC time): sim time + `utc_at_sim_zero_us`, as PX4's Gazebo
/// plugin adds the world's start wall time.
mavlink_hil_gps_t HilGps(const VehicleSnapshot& s, uint64_t utc_at_sim_zero_us);
/// Ground truth: q NED <- FRD, FRD rates, 1e-7 deg, mm, cm/s NED, the acceleration in NED [m/s^2 * 1000]
/// (PX4 reads xacc / 1000 as m/s^2, its Gazebo plugin sends a_NED * 1000).
mavlink_hil_state_quaternion_t HilStateQuaternion(const VehicleSnapshot& s);
/// A downward range sensor (ROTATION_PITCH_270), cm.
mavlink_distance_sensor_t DistanceSensor(const VehicleSnapshot& s);
/// The flow plugin's integrals; gyro integrals NaN when the flow sensor has none (all three 0 from our
/// plugin): PX4 then compensates rotation with its own gyro, as with PX4's Gazebo flow plugin.
mavlink_hil_optical_flow_t HilOpticalFlow(const VehicleSnapshot& s);

/// What PX4's HIL_ACTUATOR_CONTROLS asks of the vehicle: its 16 controls (PX4 writes motors 0..1 and
/// surfaces -1..1), whether it is armed, and its stamp (PX4's clock; 0: unstamped).
struct ActuatorControls {
  std::vector<double> controls;  ///< 16 values, clamped to -1..1
  bool armed = false;            ///< mode & MAV_MODE_FLAG_SAFETY_ARMED
  uint64_t time_usec = 0;
};
/// Decodes a HIL_ACTUATOR_CONTROLS message. "" with *out filled, or the line that says why it cannot be
/// applied (a control that is NaN or inf; the last valid outputs then stay in force; out->time_usec is
/// filled even then). A control outside -1..1 is clamped and named in *clamped (one line; empty when
/// none was).
std::string DecodeActuatorControls(const mavlink_message_t& m, ActuatorControls* out, std::string* clamped);

/// One end of a MAVLink 2 link: frames outgoing messages with its own system and component ids and
/// sequence (no process-wide channel state: several vehicles in one process each have their own),
/// and unframes incoming bytes, counting what it had to drop.
class MavlinkEndpoint {
 public:
  MavlinkEndpoint(uint8_t system_id, uint8_t component_id) : system_id_(system_id), component_id_(component_id) {}

  /// The bytes of one message on the wire.
  std::vector<uint8_t> Frame(const mavlink_hil_sensor_t& m);
  std::vector<uint8_t> Frame(const mavlink_hil_gps_t& m);
  std::vector<uint8_t> Frame(const mavlink_hil_state_quaternion_t& m);
  std::vector<uint8_t> Frame(const mavlink_distance_sensor_t& m);
  std::vector<uint8_t> Frame(const mavlink_hil_optical_flow_t& m);
  std::vector<uint8_t> Frame(const mavlink_heartbeat_t& m);

  /// Feeds received bytes; `on_message` gets each complete, checksummed message.
  void Feed(const uint8_t* data, size_t n, const std::function<void(const mavlink_message_t&)>& on_message);
  /// Frames dropped so far for a bad checksum (a corrupt or truncated frame, or an unknown message).
  uint64_t BadFrames() const { return bad_frames_; }
  /// Forget a partial frame (a new connection starts clean).
  void ResetParser() { parse_status_ = {}; }

 private:
  std::vector<uint8_t> Finish(uint32_t id, const void* payload, uint8_t min_length, uint8_t length, uint8_t crc_extra);
  uint8_t system_id_, component_id_;
  mavlink_status_t send_status_{};  // the sequence number
  mavlink_message_t parse_buffer_{};
  mavlink_status_t parse_status_{};
  uint64_t bad_frames_ = 0;
};

}  // namespace px4
}  // namespace rotors_gazebo_plugins
