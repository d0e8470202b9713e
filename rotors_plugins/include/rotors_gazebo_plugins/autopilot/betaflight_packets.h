// Betaflight's SITL packets (src/platform/SIMULATOR/target/SITL/target.h and sitl.c of Betaflight
// 4.6), engine- and ROS-free: the state it reads on UDP 9003, the RC on 9004, the motor outputs it
// sends to 9002. Frames, as its sitl.c reads them: the gyro in body FRD (it flips y and z into its
// own FLU), the accelerometer as minus the specific force in body FLU (it negates it), the attitude
// q NED <- FRD (what the ArduCopter Gazebo plugin it was written for sends: with it, its angle mode
// levels the vehicle; with q NWU <- FLU the pitch loop diverged), and, for its virtual GPS,
// longitude, latitude and altitude with the velocity in ENU.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rotors_gazebo_plugins/autopilot/vehicle_snapshot.h"

namespace rotors_gazebo_plugins {
namespace betaflight {

constexpr int kRcChannels = 16;  // SIMULATOR_MAX_RC_CHANNELS
constexpr int kMotors = 4;       // servo_packet.motor_speed

#pragma pack(push, 1)
struct FdmPacket {
  double timestamp;                       ///< [s] sim time
  double imu_angular_velocity_rpy[3];     ///< [rad/s] body FRD
  double imu_linear_acceleration_xyz[3];  ///< [m/s^2] minus the specific force, body FLU
  double imu_orientation_quat[4];         ///< w x y z, NED <- FRD
  double velocity_xyz[3];                 ///< [m/s] ENU (virtual GPS)
  double position_xyz[3];                 ///< longitude [deg], latitude [deg], altitude [m] (virtual GPS)
  double pressure;                        ///< [Pa]
};
struct RcPacket {
  double timestamp;                ///< [s]
  uint16_t channels[kRcChannels];  ///< [us] 1000..2000: AETR then AUX1..
};
struct ServoPacket {
  float motor_speed[kMotors];  ///< [0, 1] (3D: [-1, 1]), in the ArduCopter plugin's order
};
#pragma pack(pop)
static_assert(sizeof(FdmPacket) == 144, "Betaflight's fdm_packet is 18 doubles");
static_assert(sizeof(RcPacket) == 40, "Betaflight's rc_packet is a double and 16 uint16");
static_assert(sizeof(ServoPacket) == 16, "Betaflight's servo_packet is 4 floats");

/// The state packet of a snapshot: its IMU reading (the plugin fills it), the barometer's pressure
/// where the vehicle has one (else the standard atmosphere at the true altitude).
FdmPacket StatePacket(const VehicleSnapshot& s);

/// An RC packet of up to 16 channels [us] (VehicleBus::SetRcChannels checked them); the rest 1000 us.
RcPacket MakeRcPacket(double time_s, const std::vector<int>& channels_us);

/// The motor outputs of a received datagram of `n` bytes: "" or why it is not a servo packet
/// (the size, NaN, outside [-1, 1]).
std::string ReadServoPacket(const void* data, int n, std::array<double, kMotors>* outputs);

}  // namespace betaflight
}  // namespace rotors_gazebo_plugins
