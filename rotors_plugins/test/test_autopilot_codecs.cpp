// The autopilot codecs on their own (no engine, no ROS, no socket): each against the field units
// and layouts the autopilot's own code reads (PX4's SimulatorMavlink.cpp, ArduPilot's SIM_JSON.cpp,
// Betaflight's sitl.c), and the standard atmosphere they share.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "rotors_gazebo_plugins/autopilot/ardupilot_json.h"
#include "rotors_gazebo_plugins/autopilot/betaflight_packets.h"
#include "rotors_gazebo_plugins/autopilot/px4_mavlink.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"

namespace rotors_gazebo_plugins {
namespace {

VehicleSnapshot AtRestFacingEast() {
  VehicleSnapshot s;
  s.time_s = 1.5;
  s.has_imu = true;
  s.gyro_B = {0.1, 0.2, 0.3};    // FLU
  s.accel_B = {0.0, 0.0, 9.81};  // FLU: at rest the specific force points up
  s.has_mag = true;
  s.mag_B_T = {2e-5, 1e-6, -4e-5};  // FLU [T]
  s.has_baro = true;
  s.pressure_Pa = StandardAtmospherePressure(500.0);
  s.has_gps = true;
  s.gps_latitude_longitude_altitude = {47.3667, 8.55, 500.0};
  s.gps_hor_std_m = 1.0;
  s.gps_ver_std_m = 1.0;
  s.gps_velocity_W = {1.0, 2.0, -0.5};  // ENU
  s.a_W = {0.1, 0.2, 0.3};              // ENU
  return s;
}

TEST(StandardAtmosphere, PressureAltitudeInvertsThePressureWithinTheGeopotentialCorrection) {
  EXPECT_NEAR(StandardAtmospherePressure(0.0), 101325.0, 1e-9);
  // the pressure of 500 m geometric is that of 499.96 m geopotential: h R_e / (R_e + h)
  EXPECT_NEAR(PressureAltitude(StandardAtmospherePressure(500.0)), 500.0 * 6356766.0 / (6356766.0 + 500.0), 1e-6);
  EXPECT_NEAR(StandardAtmosphereTemperature_C(1000.0), 15.0 - 6.5, 1e-12);
  // the density, against the 1976 standard's table (U.S. Standard Atmosphere 1976, geometric altitude)
  EXPECT_NEAR(StandardAtmosphereDensity(0.0), 1.2250, 5e-5);
  EXPECT_NEAR(StandardAtmosphereDensity(500.0), 1.1673, 2e-4);
  EXPECT_NEAR(StandardAtmosphereDensity(1000.0), 1.1117, 2e-4);
}

TEST(Px4HilSensor, FieldsInPx4sUnitsAndFrames) {
  const mavlink_hil_sensor_t m = px4::HilSensor(AtRestFacingEast(), true, true, false);
  EXPECT_EQ(m.time_usec, 1500000u);
  // FLU -> FRD: y and z flip
  EXPECT_FLOAT_EQ(m.xgyro, 0.1f);
  EXPECT_FLOAT_EQ(m.ygyro, -0.2f);
  EXPECT_FLOAT_EQ(m.zgyro, -0.3f);
  EXPECT_FLOAT_EQ(m.zacc, -9.81f);
  // tesla -> gauss
  EXPECT_FLOAT_EQ(m.xmag, 0.2f);
  EXPECT_FLOAT_EQ(m.zmag, 0.4f);
  // Pa -> hPa; the pressure altitude and the temperature at it
  EXPECT_NEAR(m.abs_pressure, StandardAtmospherePressure(500.0) / 100.0, 1e-3);
  EXPECT_NEAR(m.pressure_alt, 500.0, 0.1);
  EXPECT_NEAR(m.temperature, 15.0 - 6.5 * 0.5, 1e-3);
  EXPECT_EQ(m.fields_updated, px4::kAccel | px4::kGyro | px4::kMag | px4::kBaro);
  EXPECT_EQ(px4::HilSensor(AtRestFacingEast(), false, false, false).fields_updated, px4::kAccel | px4::kGyro);
}

TEST(Px4HilGps, CentimetresNedAndUtcTime) {
  const uint64_t utc_at_zero_us = 1790000000000000ull;
  const mavlink_hil_gps_t m = px4::HilGps(AtRestFacingEast(), utc_at_zero_us);
  EXPECT_EQ(m.time_usec, utc_at_zero_us + 1500000u);
  EXPECT_EQ(m.lat, 473667000);
  EXPECT_EQ(m.alt, 500000);
  EXPECT_EQ(m.eph, 100);  // [cm]: PX4 multiplies by 0.01
  EXPECT_EQ(m.epv, 100);
  EXPECT_EQ(m.vn, 200);  // ENU (1, 2, -0.5) m/s -> NED (2, 1, 0.5) cm/s
  EXPECT_EQ(m.ve, 100);
  EXPECT_EQ(m.vd, 50);
  EXPECT_EQ(m.fix_type, 3);
  EXPECT_GE(m.satellites_visible, 6);  // EKF2_REQ_NSATS
}

TEST(Px4HilStateQuaternion, AccelerationInNedTimesAThousand) {
  const mavlink_hil_state_quaternion_t m = px4::HilStateQuaternion(AtRestFacingEast());
  // PX4 reads xacc / 1000 as the NED acceleration [m/s^2]
  EXPECT_EQ(m.xacc, 200);
  EXPECT_EQ(m.yacc, 100);
  EXPECT_EQ(m.zacc, -300);
}

TEST(Px4HilOpticalFlow, GyroIntegralsNanWithoutAGyro) {
  VehicleSnapshot s = AtRestFacingEast();
  s.has_flow = true;
  EXPECT_TRUE(std::isnan(px4::HilOpticalFlow(s).integrated_xgyro));
  s.flow_integrated_gyro_rad = {0.01, 0.0, 0.0};
  EXPECT_FLOAT_EQ(px4::HilOpticalFlow(s).integrated_xgyro, 0.01f);
}

// PX4's mixer output (SimulatorMavlink::send_controls): motors 0..1, surfaces -1..1, the armed bit in
// mode, PX4's clock in time_usec; framed and fed back through MavlinkEndpoint as the link does.
TEST(Px4ActuatorControls, DecodedClampedOrRefusedInOneLine) {
  mavlink_hil_actuator_controls_t sent{};
  sent.time_usec = 1234567;
  sent.mode = px4::kArmed;
  sent.flags = px4::kLockstepFlag;
  for (int i = 0; i < 16; ++i) sent.controls[i] = 0.05f * static_cast<float>(i) - 0.2f;
  auto feed = [](const mavlink_hil_actuator_controls_t& c) {
    mavlink_message_t m;
    mavlink_msg_hil_actuator_controls_encode(1, 1, &m, &c);
    uint8_t bytes[MAVLINK_MAX_PACKET_LEN];
    const uint16_t n = mavlink_msg_to_send_buffer(bytes, &m);
    px4::MavlinkEndpoint simulator(1, 51);
    mavlink_message_t got{};
    int count = 0;
    simulator.Feed(bytes, n, [&](const mavlink_message_t& message) {
      got = message;
      ++count;
    });
    EXPECT_EQ(count, 1);
    EXPECT_EQ(simulator.BadFrames(), 0u);
    return got;
  };
  px4::ActuatorControls a;
  std::string clamped;
  EXPECT_EQ(px4::DecodeActuatorControls(feed(sent), &a, &clamped), "");
  EXPECT_EQ(clamped, "");
  EXPECT_TRUE(a.armed);
  EXPECT_EQ(a.time_usec, 1234567u);
  ASSERT_EQ(a.controls.size(), 16u);
  for (int i = 0; i < 16; ++i) EXPECT_DOUBLE_EQ(a.controls[i], static_cast<double>(sent.controls[i]));

  sent.mode = 0;
  sent.controls[3] = 1.5f;
  EXPECT_EQ(px4::DecodeActuatorControls(feed(sent), &a, &clamped), "");
  EXPECT_EQ(clamped, "HIL_ACTUATOR_CONTROLS controls[3] = 1.500000 is outside -1..1: clamped");
  EXPECT_DOUBLE_EQ(a.controls[3], 1.0);
  EXPECT_FALSE(a.armed);

  sent.controls[5] = NAN;
  a = px4::ActuatorControls{};
  EXPECT_EQ(px4::DecodeActuatorControls(feed(sent), &a, &clamped),
            "HIL_ACTUATOR_CONTROLS controls[5] = nan: the message is ignored, the last valid outputs stay in force");
  EXPECT_TRUE(a.controls.empty());
  EXPECT_EQ(a.time_usec, 1234567u);  // the answer still counts for lockstep
}

// MavlinkEndpoint::Feed: a message split across reads comes out once; a corrupt frame is counted and
// dropped without losing the next one.
TEST(Px4MavlinkEndpoint, FeedReassemblesSplitFramesAndCountsBadOnes) {
  mavlink_heartbeat_t h{};
  h.type = MAV_TYPE_QUADROTOR;
  px4::MavlinkEndpoint px4_side(1, 1), simulator(1, 51);
  const std::vector<uint8_t> frame = px4_side.Frame(h);
  int messages = 0;
  auto count = [&](const mavlink_message_t& m) { messages += m.msgid == MAVLINK_MSG_ID_HEARTBEAT; };
  simulator.Feed(frame.data(), 5, count);
  EXPECT_EQ(messages, 0);
  simulator.Feed(frame.data() + 5, frame.size() - 5, count);
  EXPECT_EQ(messages, 1);
  std::vector<uint8_t> corrupt = frame;
  corrupt[frame.size() - 1] ^= 0xff;  // the checksum's last byte
  simulator.Feed(corrupt.data(), corrupt.size(), count);
  EXPECT_EQ(messages, 1);
  EXPECT_EQ(simulator.BadFrames(), 1u);
  simulator.Feed(frame.data(), frame.size(), count);
  EXPECT_EQ(messages, 2);
}

TEST(ArdupilotServoFrames, OrderAndPwm) {
  using ardupilot::FrameOrder;
  EXPECT_EQ(ardupilot::OrderOf(5, false, 0), FrameOrder::kFirst);
  EXPECT_EQ(ardupilot::OrderOf(6, true, 5), FrameOrder::kNext);
  EXPECT_EQ(ardupilot::OrderOf(5, true, 5), FrameOrder::kRepeated);
  EXPECT_EQ(ardupilot::OrderOf(0, true, 5), FrameOrder::kBackwards);
  double u = -9.0;
  EXPECT_FALSE(ardupilot::PwmToInput(0, false, &u));  // 0 us: no output
  EXPECT_EQ(u, -9.0);
  ASSERT_TRUE(ardupilot::PwmToInput(1250, false, &u));
  EXPECT_DOUBLE_EQ(u, 0.25);
  ASSERT_TRUE(ardupilot::PwmToInput(1250, true, &u));
  EXPECT_DOUBLE_EQ(u, -0.5);
  ASSERT_TRUE(ardupilot::PwmToInput(2100, true, &u));
  EXPECT_DOUBLE_EQ(u, 1.0);
  ardupilot::ServoFrame frame, back;
  frame.frame_rate = 400;
  frame.frame_count = 77;
  frame.pwm_us.assign(16, 1500);
  const std::vector<uint8_t> bytes = ardupilot::WriteServoPacket(frame);
  ASSERT_EQ(bytes.size(), 40u);
  EXPECT_EQ(ardupilot::ReadServoPacket(bytes.data(), static_cast<int>(bytes.size()), &back), "");
  EXPECT_EQ(back.frame_count, 77u);
  EXPECT_NE(ardupilot::ReadServoPacket(bytes.data(), 39, &back), "");
}

/// SIM_JSON finds `"key":` with strstr and reads the number after it with atof.
double SimJsonNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  return std::atof(json.c_str() + at + key.size() + 3);
}

TEST(ArdupilotStateJson, KeysAsSimJsonFindsThem) {
  VehicleSnapshot s = AtRestFacingEast();
  s.has_range = true;
  s.range_m = INFINITY;
  s.range_max_m = 25.0;
  s.has_diff_pressure = true;
  s.airspeed_m_s = 3.0;
  int non_finite = 0;
  const std::string json = ardupilot::StateJson(s, &non_finite);
  EXPECT_EQ(non_finite, 0);
  EXPECT_EQ(json.front(), '\n');
  EXPECT_EQ(json.back(), '\n');
  EXPECT_EQ(json.find(": "), std::string::npos);  // SIM_JSON skips exactly `"key":`
  EXPECT_DOUBLE_EQ(SimJsonNumber(json, "timestamp"), 1.5);
  EXPECT_DOUBLE_EQ(SimJsonNumber(json, "rng_1"), 50.0);  // no return: twice the maximum, out of range high
  s.range_m = -INFINITY;                                 // REP 117: closer than the minimum
  EXPECT_DOUBLE_EQ(SimJsonNumber(ardupilot::StateJson(s, &non_finite), "rng_1"), 0.0);  // out of range low
  s.range_m = 3.25;
  EXPECT_DOUBLE_EQ(SimJsonNumber(ardupilot::StateJson(s, &non_finite), "rng_1"), 3.25);
  EXPECT_DOUBLE_EQ(SimJsonNumber(json, "airspeed"), 3.0);
  EXPECT_NE(json.find("\"no_time_sync\":true"), std::string::npos);
  // "velocity" before any key it is a prefix of
  EXPECT_LT(json.find("\"velocity\""), json.find("\"velocity_"));
}

TEST(BetaflightPackets, LayoutAsSitlReadsIt) {
  const betaflight::FdmPacket p = betaflight::StatePacket(AtRestFacingEast());
  uint8_t bytes[sizeof(p)];
  std::memcpy(bytes, &p, sizeof(p));
  double timestamp, pressure, gyro_y;
  std::memcpy(&timestamp, bytes, 8);
  std::memcpy(&gyro_y, bytes + 16, 8);
  std::memcpy(&pressure, bytes + 136, 8);
  EXPECT_EQ(timestamp, 1.5);
  EXPECT_EQ(gyro_y, -0.2);  // FRD
  EXPECT_NEAR(pressure, StandardAtmospherePressure(500.0), 1e-9);
  const betaflight::RcPacket rc = betaflight::MakeRcPacket(2.0, {1500, 1000, 2000, 1500, 1800});
  EXPECT_EQ(rc.channels[4], 1800);
}

}  // namespace
}  // namespace rotors_gazebo_plugins
