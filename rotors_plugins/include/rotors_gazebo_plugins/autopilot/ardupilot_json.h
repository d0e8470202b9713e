// ArduPilot's JSON simulator interface (libraries/SITL/SIM_JSON.{h,cpp}), engine- and ROS-free:
// ArduPilot sends a binary servo packet each frame (16 channels, magic 18458, 40 bytes; or 32,
// magic 29569, 72 bytes; PWM in us); the simulator answers to its address with one JSON line,
// newline before and after, compact separators (ArduPilot finds keys with strstr and skips
// `"key":`). ArduPilot's frames: body FRD, world NED from the origin.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rotors_gazebo_plugins/autopilot/vehicle_snapshot.h"

namespace rotors_gazebo_plugins {
namespace ardupilot {

constexpr uint16_t kMagic16 = 18458, kMagic32 = 29569;

struct ServoFrame {
  uint16_t frame_rate = 0;  ///< [Hz] ArduPilot's loop rate
  uint32_t frame_count = 0;
  std::vector<uint16_t> pwm_us;  ///< 16 or 32 channels
};

/// "" and the frame, or why the datagram is not a servo packet (its size, its magic).
std::string ReadServoPacket(const void* data, int n, ServoFrame* frame);
/// A servo packet's bytes (the tests' autopilot side, and the protocol's round trip).
std::vector<uint8_t> WriteServoPacket(const ServoFrame& frame);

/// The state line: timestamp [s]; imu.gyro [rad/s] and imu.accel_body [m/s^2] (specific force) in
/// body FRD, the snapshot's IMU reading (the plugin fills it); position [m] and velocity [m/s] NED from
/// the world origin; quaternion w x y z, NED <- FRD; rng_1 [m] with a range sensor (no return, or
/// beyond its range: twice its maximum, which ArduPilot reads as "out of range high", as ArduPilot's
/// Gazebo plugin sends it; closer than its minimum: 0, "out of range low"); airspeed [m/s] with an airspeed sensor, its
/// wind-relative reading (ArduPilot takes it as airspeed and pitot); no_time_sync (ArduPilot does not pace itself to
/// real time: the world sets the pace). Numbers that are not finite are written as 0 and counted in *non_finite.
std::string StateJson(const VehicleSnapshot& s, int* non_finite);

/// What a servo frame's count says against the last one's (SIM_JSON resends a frame unchanged when it
/// got no answer; a restarted ArduPilot counts from 0 again).
enum class FrameOrder { kFirst, kNext, kRepeated, kBackwards };
FrameOrder OrderOf(uint32_t frame_count, bool have_last, uint32_t last_frame_count);

/// A servo channel's PWM [us] as the control channel's input u: motors 1000..2000 us -> 0..1,
/// surfaces centred on 1500 us -> -1..1 (clamped); 0 us is "no output" (false).
bool PwmToInput(uint16_t pwm_us, bool centred, double* u);

}  // namespace ardupilot
}  // namespace rotors_gazebo_plugins
