#include "rotors_gazebo_plugins/autopilot/betaflight_packets.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "rotors_gazebo_plugins/autopilot/frames.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"

namespace rotors_gazebo_plugins {
namespace betaflight {

FdmPacket StatePacket(const VehicleSnapshot& s) {
  FdmPacket p{};
  p.timestamp = s.time_s;
  const Eigen::Vector3d gyro_FRD = frames::FrdFromFlu(s.gyro_B);
  const Eigen::Vector3d minus_f_FLU = -s.accel_B;
  const Eigen::Quaterniond q_NED_FRD = frames::NedFrdFromEnuFlu(s.q_WB);
  for (int i = 0; i < 3; ++i) {
    p.imu_angular_velocity_rpy[i] = gyro_FRD[i];
    p.imu_linear_acceleration_xyz[i] = minus_f_FLU[i];
    p.velocity_xyz[i] = s.v_W[i];
  }
  p.imu_orientation_quat[0] = q_NED_FRD.w();
  p.imu_orientation_quat[1] = q_NED_FRD.x();
  p.imu_orientation_quat[2] = q_NED_FRD.y();
  p.imu_orientation_quat[3] = q_NED_FRD.z();
  const Eigen::Vector3d& lla = s.has_gps ? s.gps_latitude_longitude_altitude : s.latitude_longitude_altitude;
  p.position_xyz[0] = lla.y();
  p.position_xyz[1] = lla.x();
  p.position_xyz[2] = lla.z();
  p.pressure = s.has_baro ? s.pressure_Pa : StandardAtmospherePressure(s.latitude_longitude_altitude.z());
  return p;
}

RcPacket MakeRcPacket(double time_s, const std::vector<int>& channels_us) {
  RcPacket packet{};
  packet.timestamp = time_s;
  for (int i = 0; i < kRcChannels; ++i)
    packet.channels[i] = static_cast<uint16_t>(i < static_cast<int>(channels_us.size()) ? channels_us[i] : 1000);
  return packet;
}

std::string ReadServoPacket(const void* data, int n, std::array<double, kMotors>* outputs) {
  std::ostringstream why;
  if (n != static_cast<int>(sizeof(ServoPacket))) {
    why << "a datagram of " << n << " bytes is not Betaflight's servo packet (" << sizeof(ServoPacket) << " bytes)";
    return why.str();
  }
  ServoPacket packet;
  std::memcpy(&packet, data, sizeof(packet));
  for (int i = 0; i < kMotors; ++i) {
    const double u = packet.motor_speed[i];
    if (!std::isfinite(u) || u < -1.0 || u > 1.0) {
      why << "motor_speed[" << i << "] = " << u << " is not in [-1, 1]";
      return why.str();
    }
    (*outputs)[i] = u;
  }
  return {};
}

}  // namespace betaflight
}  // namespace rotors_gazebo_plugins
