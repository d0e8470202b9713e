#include "rotors_gazebo_plugins/autopilot/px4_mavlink.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "rotors_gazebo_plugins/autopilot/frames.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"

namespace rotors_gazebo_plugins {
namespace px4 {
namespace {

int16_t ClampInt16(double v) { return static_cast<int16_t>(std::max(-32767.0, std::min(32767.0, std::round(v)))); }
uint16_t ClampUint16(double v) { return static_cast<uint16_t>(std::max(0.0, std::min(65534.0, std::round(v)))); }
}  // namespace

uint64_t Microseconds(double t_s) { return static_cast<uint64_t>(std::llround(t_s * 1e6)); }

mavlink_hil_sensor_t HilSensor(const VehicleSnapshot& s, bool new_mag, bool new_baro, bool new_diff_pressure) {
  mavlink_hil_sensor_t m{};
  m.time_usec = Microseconds(s.time_s);
  const Eigen::Vector3d accel_FRD = frames::FrdFromFlu(s.accel_B), gyro_FRD = frames::FrdFromFlu(s.gyro_B);
  m.xacc = static_cast<float>(accel_FRD.x());
  m.yacc = static_cast<float>(accel_FRD.y());
  m.zacc = static_cast<float>(accel_FRD.z());
  m.xgyro = static_cast<float>(gyro_FRD.x());
  m.ygyro = static_cast<float>(gyro_FRD.y());
  m.zgyro = static_cast<float>(gyro_FRD.z());
  m.fields_updated = kAccel | kGyro;
  const Eigen::Vector3d mag_FRD_G = frames::FrdFromFlu(s.mag_B_T) * 1e4;  // 1 G = 1e-4 T
  m.xmag = static_cast<float>(mag_FRD_G.x());
  m.ymag = static_cast<float>(mag_FRD_G.y());
  m.zmag = static_cast<float>(mag_FRD_G.z());
  if (new_mag) m.fields_updated |= kMag;
  m.abs_pressure = static_cast<float>(s.pressure_Pa / 100.0);  // [hPa]
  m.pressure_alt = static_cast<float>(PressureAltitude(s.pressure_Pa));
  m.temperature = static_cast<float>(StandardAtmosphereTemperature_C(m.pressure_alt));
  if (new_baro) m.fields_updated |= kBaro;
  m.diff_pressure = static_cast<float>(s.diff_pressure_Pa / 100.0);  // [hPa]
  if (new_diff_pressure) m.fields_updated |= kDiffPressure;
  m.id = 0;
  return m;
}

mavlink_hil_gps_t HilGps(const VehicleSnapshot& s, uint64_t utc_at_sim_zero_us) {
  mavlink_hil_gps_t m{};
  m.time_usec = utc_at_sim_zero_us + Microseconds(s.time_s);
  m.fix_type = 3;  // 3D fix
  m.lat = static_cast<int32_t>(std::llround(s.gps_latitude_longitude_altitude.x() * 1e7));
  m.lon = static_cast<int32_t>(std::llround(s.gps_latitude_longitude_altitude.y() * 1e7));
  m.alt = static_cast<int32_t>(std::llround(s.gps_latitude_longitude_altitude.z() * 1e3));
  m.eph = ClampUint16(s.gps_hor_std_m * 100.0);
  m.epv = ClampUint16(s.gps_ver_std_m * 100.0);
  const Eigen::Vector3d v_NED = frames::NedFromEnu(s.gps_velocity_W);
  m.vel = ClampUint16(std::hypot(v_NED.x(), v_NED.y()) * 100.0);
  m.vn = ClampInt16(v_NED.x() * 100.0);
  m.ve = ClampInt16(v_NED.y() * 100.0);
  m.vd = ClampInt16(v_NED.z() * 100.0);
  double course_deg = std::atan2(v_NED.y(), v_NED.x()) * 180.0 / M_PI;
  if (course_deg < 0.0) course_deg += 360.0;
  m.cog = m.vel > 0 ? static_cast<uint16_t>(std::min(35999.0, std::round(course_deg * 100.0))) : UINT16_MAX;
  m.satellites_visible = 10;
  m.id = 0;
  return m;
}

mavlink_hil_state_quaternion_t HilStateQuaternion(const VehicleSnapshot& s) {
  mavlink_hil_state_quaternion_t m{};
  m.time_usec = Microseconds(s.time_s);
  const Eigen::Quaterniond q = frames::NedFrdFromEnuFlu(s.q_WB);
  m.attitude_quaternion[0] = static_cast<float>(q.w());
  m.attitude_quaternion[1] = static_cast<float>(q.x());
  m.attitude_quaternion[2] = static_cast<float>(q.y());
  m.attitude_quaternion[3] = static_cast<float>(q.z());
  const Eigen::Vector3d omega_FRD = frames::FrdFromFlu(s.omega_B);
  m.rollspeed = static_cast<float>(omega_FRD.x());
  m.pitchspeed = static_cast<float>(omega_FRD.y());
  m.yawspeed = static_cast<float>(omega_FRD.z());
  m.lat = static_cast<int32_t>(std::llround(s.latitude_longitude_altitude.x() * 1e7));
  m.lon = static_cast<int32_t>(std::llround(s.latitude_longitude_altitude.y() * 1e7));
  m.alt = static_cast<int32_t>(std::llround(s.latitude_longitude_altitude.z() * 1e3));
  const Eigen::Vector3d v_NED = frames::NedFromEnu(s.v_W);
  m.vx = ClampInt16(v_NED.x() * 100.0);
  m.vy = ClampInt16(v_NED.y() * 100.0);
  m.vz = ClampInt16(v_NED.z() * 100.0);
  m.ind_airspeed = m.true_airspeed = ClampUint16(s.v_W.norm() * 100.0);
  const Eigen::Vector3d a_NED_1000 = frames::NedFromEnu(s.a_W) * 1000.0;
  m.xacc = ClampInt16(a_NED_1000.x());
  m.yacc = ClampInt16(a_NED_1000.y());
  m.zacc = ClampInt16(a_NED_1000.z());
  return m;
}

mavlink_distance_sensor_t DistanceSensor(const VehicleSnapshot& s) {
  mavlink_distance_sensor_t m{};
  m.time_boot_ms = static_cast<uint32_t>(std::llround(s.time_s * 1e3));
  m.min_distance = ClampUint16(s.range_min_m * 100.0);
  m.max_distance = ClampUint16(s.range_max_m * 100.0);
  m.current_distance = ClampUint16(s.range_m * 100.0);
  m.type = MAV_DISTANCE_SENSOR_LASER;
  m.id = 0;
  m.orientation = MAV_SENSOR_ROTATION_PITCH_270;  // downward
  m.covariance = 0;
  m.signal_quality = 0;  // unknown
  return m;
}

std::string DecodeActuatorControls(const mavlink_message_t& m, ActuatorControls* out, std::string* clamped) {
  clamped->clear();
  if (m.msgid != MAVLINK_MSG_ID_HIL_ACTUATOR_CONTROLS)
    return "message " + std::to_string(m.msgid) + " is not HIL_ACTUATOR_CONTROLS";
  mavlink_hil_actuator_controls_t a;
  mavlink_msg_hil_actuator_controls_decode(&m, &a);
  out->time_usec = a.time_usec;  // also when the controls cannot be applied: the answer came
  std::vector<double> u(16);
  for (int i = 0; i < 16; ++i) {
    const double v = a.controls[i];
    if (!std::isfinite(v))
      return "HIL_ACTUATOR_CONTROLS controls[" + std::to_string(i) + "] = " + std::to_string(v) +
             ": the message is ignored, the last valid outputs stay in force";
    if ((v < -1.0 || v > 1.0) && clamped->empty())
      *clamped = "HIL_ACTUATOR_CONTROLS controls[" + std::to_string(i) + "] = " + std::to_string(v) +
                 " is outside -1..1: clamped";
    u[i] = std::max(-1.0, std::min(1.0, v));
  }
  out->controls = std::move(u);
  out->armed = (a.mode & kArmed) != 0;
  return "";
}

mavlink_hil_optical_flow_t HilOpticalFlow(const VehicleSnapshot& s) {
  mavlink_hil_optical_flow_t m{};
  m.time_usec = Microseconds(s.time_s);
  m.sensor_id = 0;
  m.integration_time_us = s.flow_integration_time_us;
  m.integrated_x = static_cast<float>(s.flow_integrated_xy_rad.x());
  m.integrated_y = static_cast<float>(s.flow_integrated_xy_rad.y());
  const bool has_gyro = !s.flow_integrated_gyro_rad.isZero(0.0);
  const float no_gyro = std::numeric_limits<float>::quiet_NaN();
  m.integrated_xgyro = has_gyro ? static_cast<float>(s.flow_integrated_gyro_rad.x()) : no_gyro;
  m.integrated_ygyro = has_gyro ? static_cast<float>(s.flow_integrated_gyro_rad.y()) : no_gyro;
  m.integrated_zgyro = has_gyro ? static_cast<float>(s.flow_integrated_gyro_rad.z()) : no_gyro;
  m.quality = static_cast<uint8_t>(std::max(0, std::min(255, s.flow_quality)));
  m.time_delta_distance_us = s.flow_integration_time_us;
  m.distance = static_cast<float>(s.flow_distance_m);
  return m;
}

std::vector<uint8_t> MavlinkEndpoint::Finish(uint32_t id, const void* payload, uint8_t min_length, uint8_t length,
                                             uint8_t crc_extra) {
  mavlink_message_t msg{};
  std::memcpy(_MAV_PAYLOAD_NON_CONST(&msg), payload, length);  // the packed structs are the little-endian wire layout
  msg.msgid = id;
  mavlink_finalize_message_buffer(&msg, system_id_, component_id_, &send_status_, min_length, length, crc_extra);
  std::vector<uint8_t> bytes(MAVLINK_MAX_PACKET_LEN);
  bytes.resize(mavlink_msg_to_send_buffer(bytes.data(), &msg));
  return bytes;
}

#define RSIM_MAVLINK_FRAME(type, NAME)                                                                     \
  std::vector<uint8_t> MavlinkEndpoint::Frame(const type& m) {                                             \
    return Finish(MAVLINK_MSG_ID_##NAME, &m, MAVLINK_MSG_ID_##NAME##_MIN_LEN, MAVLINK_MSG_ID_##NAME##_LEN, \
                  MAVLINK_MSG_ID_##NAME##_CRC);                                                            \
  }
RSIM_MAVLINK_FRAME(mavlink_hil_sensor_t, HIL_SENSOR)
RSIM_MAVLINK_FRAME(mavlink_hil_gps_t, HIL_GPS)
RSIM_MAVLINK_FRAME(mavlink_hil_state_quaternion_t, HIL_STATE_QUATERNION)
RSIM_MAVLINK_FRAME(mavlink_distance_sensor_t, DISTANCE_SENSOR)
RSIM_MAVLINK_FRAME(mavlink_hil_optical_flow_t, HIL_OPTICAL_FLOW)
RSIM_MAVLINK_FRAME(mavlink_heartbeat_t, HEARTBEAT)
#undef RSIM_MAVLINK_FRAME

void MavlinkEndpoint::Feed(const uint8_t* data, size_t n,
                           const std::function<void(const mavlink_message_t&)>& on_message) {
  for (size_t i = 0; i < n; ++i) {
    mavlink_message_t message;
    mavlink_status_t status;
    const uint8_t result = mavlink_frame_char_buffer(&parse_buffer_, &parse_status_, data[i], &message, &status);
    if (result == MAVLINK_FRAMING_OK) on_message(message);
    else if (result == MAVLINK_FRAMING_BAD_CRC || result == MAVLINK_FRAMING_BAD_SIGNATURE) ++bad_frames_;
  }
}

}  // namespace px4
}  // namespace rotors_gazebo_plugins
