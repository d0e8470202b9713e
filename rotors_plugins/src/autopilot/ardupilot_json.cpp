#include "rotors_gazebo_plugins/autopilot/ardupilot_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "rotors_gazebo_plugins/autopilot/frames.h"

namespace rotors_gazebo_plugins {
namespace ardupilot {

std::string ReadServoPacket(const void* data, int n, ServoFrame* frame) {
  const int channels = n == 8 + 2 * 16 ? 16 : n == 8 + 2 * 32 ? 32 : 0;
  if (channels == 0)
    return "a datagram of " + std::to_string(n) +
           " bytes is not ArduPilot's servo packet (40 bytes for 16 channels, 72 for 32)";
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  uint16_t magic;
  std::memcpy(&magic, bytes, 2);
  const uint16_t expected = channels == 16 ? kMagic16 : kMagic32;
  if (magic != expected)
    return "servo packet magic " + std::to_string(magic) + " is not " + std::to_string(expected) + " (" +
           std::to_string(channels) + " channels): not ArduPilot's JSON interface, or another version";
  std::memcpy(&frame->frame_rate, bytes + 2, 2);
  std::memcpy(&frame->frame_count, bytes + 4, 4);
  frame->pwm_us.resize(channels);
  std::memcpy(frame->pwm_us.data(), bytes + 8, 2 * channels);
  return {};
}

std::vector<uint8_t> WriteServoPacket(const ServoFrame& frame) {
  const uint16_t magic = frame.pwm_us.size() == 32 ? kMagic32 : kMagic16;
  std::vector<uint8_t> bytes(8 + 2 * frame.pwm_us.size());
  std::memcpy(bytes.data(), &magic, 2);
  std::memcpy(bytes.data() + 2, &frame.frame_rate, 2);
  std::memcpy(bytes.data() + 4, &frame.frame_count, 4);
  std::memcpy(bytes.data() + 8, frame.pwm_us.data(), 2 * frame.pwm_us.size());
  return bytes;
}

namespace {
class JsonWriter {
 public:
  explicit JsonWriter(int* non_finite) : non_finite_(non_finite) {}
  std::string Number(double v) {
    if (!std::isfinite(v)) {
      ++*non_finite_;
      v = 0.0;
    }
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", v);
    return text;
  }
  std::string Vector(const Eigen::Vector3d& v) {
    return "[" + Number(v.x()) + "," + Number(v.y()) + "," + Number(v.z()) + "]";
  }

 private:
  int* non_finite_;
};
}  // namespace

FrameOrder OrderOf(uint32_t frame_count, bool have_last, uint32_t last_frame_count) {
  if (!have_last) return FrameOrder::kFirst;
  if (frame_count == last_frame_count) return FrameOrder::kRepeated;
  return frame_count < last_frame_count ? FrameOrder::kBackwards : FrameOrder::kNext;
}

bool PwmToInput(uint16_t pwm_us, bool centred, double* u) {
  if (pwm_us == 0) return false;
  // motors: u = (pwm - 1000) / 1000; surfaces: u = (pwm - 1500) / 500
  const double v = centred ? (pwm_us - 1500.0) / 500.0 : (pwm_us - 1000.0) / 1000.0;
  *u = std::max(centred ? -1.0 : 0.0, std::min(1.0, v));
  return true;
}

std::string StateJson(const VehicleSnapshot& s, int* non_finite) {
  *non_finite = 0;
  JsonWriter w(non_finite);
  const Eigen::Quaterniond q = frames::NedFrdFromEnuFlu(s.q_WB);
  std::ostringstream json;
  // "velocity" is written before any key it is a prefix of: ArduPilot matches keys by position
  json << "\n{\"timestamp\":" << w.Number(s.time_s) << ",\"imu\":{\"gyro\":" << w.Vector(frames::FrdFromFlu(s.gyro_B))
       << ",\"accel_body\":" << w.Vector(frames::FrdFromFlu(s.accel_B)) << "}"
       << ",\"position\":" << w.Vector(frames::NedFromEnu(s.p_W)) << ",\"quaternion\":[" << w.Number(q.w()) << ","
       << w.Number(q.x()) << "," << w.Number(q.y()) << "," << w.Number(q.z()) << "]"
       << ",\"velocity\":" << w.Vector(frames::NedFromEnu(s.v_W));
  if (s.has_range) {
    // REP 117: +inf nothing within range, -inf closer than the minimum. AP_RangeFinder_SITL takes
    // max(0, d), then OutOfRangeLow below RNGFNDx_MIN and OutOfRangeHigh above RNGFNDx_MAX (NaN or inf
    // would be NoData): no return goes out as twice the maximum, as ArduPilot's Gazebo plugin sends it,
    // too close as 0
    double range_m = s.range_m;
    if (std::isnan(range_m) || range_m > s.range_max_m) range_m = 2.0 * s.range_max_m;
    else if (range_m < 0.0) range_m = 0.0;
    json << ",\"rng_1\":" << w.Number(range_m);
  }
  if (s.has_diff_pressure) json << ",\"airspeed\":" << w.Number(s.airspeed_m_s);
  json << ",\"no_time_sync\":true}\n";
  return json.str();
}

}  // namespace ardupilot
}  // namespace rotors_gazebo_plugins
