#include "rotors_gazebo_plugins/autopilot_interface.h"

#include <cctype>
#include <cmath>

#include <ros/console.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {
namespace {
/// The feed's reading when it has one since load or the last reset (and its count), else nullptr.
template <class Reading>
const Reading* Latest(const SensorFeed<Reading>* feed, uint64_t* count) {
  if (!feed || !feed->fresh) return nullptr;
  *count = feed->count;
  return &feed->latest;
}
}  // namespace

void AutopilotInterface::Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) {
  namespace_ = ReadRobotNamespace(Params());
  model_name_ = model->GetName();
  world_ = model->GetWorldRaw();
  std::string link_name = namespace_.empty() ? "base_link" : namespace_ + "/base_link";
  ReadParam(Params(), "linkName", &link_name);
  link_ = RequireLink(model, link_name);
  bus_ = VehicleBus::For(*world_, namespace_);
  // the sensors the autopilot reads: their feeds on the vehicle bus, by the topics their plugins
  // publish (relative to the namespace; the plugins may load before or after this one)
  auto& sensors = bus_->sensors;
  imu_ = FeedOf(sensors.imu, "imuSubTopic", "imu");
  mag_ = FeedOf(sensors.magnetometer, "magSubTopic", "magnetic_field");
  baro_ = FeedOf(sensors.barometer, "baroSubTopic", "air_pressure");
  gps_ = FeedOf(sensors.gps, "gpsSubTopic", "gps");
  ground_speed_ = FeedOf(sensors.ground_speed, "groundSpeedSubTopic", "ground_speed");
  range_ = FeedOf(sensors.range, "lidarSubTopic", "lidar");
  flow_ = FeedOf(sensors.optical_flow, "opticalFlowSubTopic", "px4flow/raw/optical_flow_rad");
  airspeed_ = FeedOf(sensors.airspeed, "airspeedSubTopic", "air_speed");
  ReadControlChannels();
  LoadProtocol();
  if (channels_given_) {
    channels_ = ControlChannels(given_channels_, OutputCount());
    channels_ready_ = true;
  }
  update_ = rotors_sim::event::Events::ConnectWorldUpdateBegin([this](const rotors_sim::common::UpdateInfo&) {
    if (!channels_ready_ && !MakeDefaultChannels()) return;
    Exchange(Snapshot());
  });
}

bool AutopilotInterface::MakeDefaultChannels() {
  const int channel_count = bus_->rotor_count + bus_->normalized_channels;
  if (static_cast<int>(given_channels_.size()) != channel_count) {
    given_channels_.clear();
    // one channel per motor: output i -> motor i, 0..1 -> 0..maxRotVelocity (a servo: -1..1 rad);
    // then a fixed wing's normalized channels, output for output
    for (int i = 0; i < channel_count; ++i) {
      ControlChannel c;
      c.input_index = i;
      if (i < bus_->rotor_count) {
        c.name = "motor_" + std::to_string(i);
        c.input_scaling = bus_->is_servo[i] ? 1.0 : bus_->max_rot_velocity_rad_s[i];
        c.joint_control_type = bus_->is_servo[i] ? "position" : "velocity";
      } else {
        c.name = "normalized_" + std::to_string(i - bus_->rotor_count);
        c.joint_control_type = "normalized";
      }
      given_channels_.push_back(c);
    }
  }
  for (const ControlChannel& c : given_channels_) {
    const std::string why = c.Validate(OutputCount());
    if (!why.empty()) {
      Error("channels", "the vehicle's " + std::to_string(channel_count) + " actuators need more outputs than the " +
                            std::to_string(OutputCount()) + " the autopilot sends (" + why +
                            "): give <control_channels>; the motors stay stopped");
      return false;
    }
  }
  channels_ = ControlChannels(given_channels_, OutputCount());
  channels_ready_ = true;
  return true;
}

void AutopilotInterface::Reset() { OnReset(); }

VehicleSnapshot AutopilotInterface::WithTruthForMissingImu(VehicleSnapshot s) {
  if (!s.has_imu) {
    s.gyro_B = s.omega_B;
    s.accel_B = s.specific_force_B;
  }
  return s;
}

double AutopilotInterface::PhysicsStep_s() const { return world_->Physics().max_step_size_s; }

double AutopilotInterface::SimTime_s() const { return world_->SimTime().Double(); }

template <class Reading>
const SensorFeed<Reading>* AutopilotInterface::FeedOf(SensorFeeds<Reading>& feeds, const std::string& param,
                                                      const std::string& default_topic) {
  std::string topic = default_topic;
  ReadParam(Params(), param, &topic);
  if (topic.empty()) return nullptr;
  return &feeds.Of(ResolveTopic(namespace_, topic));
}

void AutopilotInterface::ReadControlChannels() {
  if (!Params().Has("control_channels")) return;
  channels_given_ = true;
  const sdf::ElementPtr list = Params().Element()->GetElement("control_channels");
  for (sdf::ElementPtr e = list->GetFirstElement(); e; e = e->GetNextElement()) {
    if (e->GetName() != "channel")
      throw rotors_sim::SimError("<control_channels> holds <channel> elements, not <" + e->GetName() + ">");
    ControlChannel c;
    if (e->HasAttribute("name")) c.name = e->GetAttribute("name")->GetAsString();
    rotors_sim::SdfParams p(e);
    p.Require("input_index", &c.input_index);
    p.Read("input_offset", &c.input_offset);
    p.Read("input_scaling", &c.input_scaling);
    p.Read("zero_position_disarmed", &c.zero_position_disarmed);
    p.Read("zero_position_armed", &c.zero_position_armed);
    p.Read("joint_control_type", &c.joint_control_type);
    p.Read("joint_name", &c.joint_name);
    p.Read("gztopic", &c.gztopic);
    p.RejectUnread();
    given_channels_.push_back(c);
  }
}

VehicleSnapshot AutopilotInterface::Snapshot() {
  VehicleSnapshot s;
  s.time_s = world_->SimTime().Double();
  const auto X_WB = link_->WorldPose();
  s.p_W = {X_WB.Pos().X(), X_WB.Pos().Y(), X_WB.Pos().Z()};
  s.q_WB = Eigen::Quaterniond(X_WB.Rot().W(), X_WB.Rot().X(), X_WB.Rot().Y(), X_WB.Rot().Z());
  const auto v_W = link_->WorldLinearVel();
  s.v_W = {v_W.X(), v_W.Y(), v_W.Z()};
  const auto w_B = link_->RelativeAngularVel();
  s.omega_B = {w_B.X(), w_B.Y(), w_B.Z()};
  // specific force: f_B = R_WB^T (a_W - g_W)
  const auto a_W = link_->WorldLinearAccel();
  s.a_W = {a_W.X(), a_W.Y(), a_W.Z()};
  const auto f_B = X_WB.Rot().RotateVectorReverse(a_W - world_->Gravity());
  s.specific_force_B = {f_B.X(), f_B.Y(), f_B.Z()};
  const auto& o = world_->Origin();
  s.latitude_longitude_altitude =
      GeodeticFromWorld(GeodeticOrigin{o.latitude_deg, o.longitude_deg, o.elevation_m, o.heading_deg}, s.p_W);

  if (const auto* imu = Latest(imu_, &s.imu_count)) {
    s.has_imu = true;
    s.gyro_B = imu->measured.angular_velocity_I;
    s.accel_B = imu->measured.linear_acceleration_I;
  }
  if (const auto* mag = Latest(mag_, &s.mag_count)) {
    s.has_mag = true;
    s.mag_B_T = mag->field_B_T;
  }
  if (const auto* baro = Latest(baro_, &s.baro_count)) {
    s.has_baro = true;
    s.pressure_Pa = baro->pressure_Pa;
  }
  if (const auto* gps = Latest(gps_, &s.gps_count)) {
    s.has_gps = true;
    s.gps_latitude_longitude_altitude = gps->fix.latitude_longitude_altitude;
    s.gps_hor_std_m = gps->horizontal_std_m;
    s.gps_ver_std_m = gps->vertical_std_m;
    uint64_t speed_count = 0;
    if (const auto* speed = Latest(ground_speed_, &speed_count)) s.gps_velocity_W = speed->velocity_W_m_s;
  }
  if (const auto* range = Latest(range_, &s.range_count)) {
    s.has_range = true;
    s.range_m = range->range_m;
    s.range_min_m = range->min_range_m;
    s.range_max_m = range->max_range_m;
  }
  if (const auto* flow = Latest(flow_, &s.flow_count)) {
    s.has_flow = true;
    s.flow_integration_time_us = flow->integration_time_us;
    s.flow_integrated_xy_rad = flow->integrated_xy_rad;
    s.flow_integrated_gyro_rad = flow->integrated_gyro_rad;
    s.flow_distance_m = flow->distance_m;
    s.flow_quality = flow->quality;
  }
  if (const auto* airspeed = Latest(airspeed_, &s.diff_pressure_count)) {
    s.has_diff_pressure = true;
    // a pitot tube's differential pressure: q = rho v_x^2 / 2, rho the standard atmosphere's at the
    // vehicle's altitude
    const double rho = StandardAtmosphereDensity(s.latitude_longitude_altitude.z());
    const double v_x = airspeed->air_velocity_B_m_s.x();
    s.diff_pressure_Pa = 0.5 * rho * v_x * v_x;
    s.airspeed_m_s = airspeed->air_velocity_B_m_s.norm();
  }
  return s;
}

void AutopilotInterface::Apply(const std::vector<double>& u, bool armed) {
  ++bus_->autopilot_answers;
  Command(channels_.References(u, armed));
}

void AutopilotInterface::Command(const std::vector<double>& references) {
  // the motors' channels make the motor command, the normalized ones a fixed wing's actuator command
  std::vector<double> motors, normalized;
  for (size_t i = 0; i < references.size(); ++i)
    (channels_.Channels()[i].joint_control_type == "normalized" ? normalized : motors).push_back(references[i]);
  std::string why;
  if (bus_->rotor_count > 0 || !motors.empty()) why = bus_->SetMotorCommand(motors);
  if (why.empty() && !normalized.empty()) why = bus_->SetNormalizedCommand(normalized);
  if (!why.empty()) Error("command", "actuator command refused: " + why);
}

void AutopilotInterface::ApplyDisarmed() {
  if (channels_ready_) Command(channels_.Disarmed());
}

void AutopilotInterface::Error(const std::string& kind, const std::string& line) {
  // one line a second for each kind of fault: the kind and the line without its numbers
  std::string key = kind + ":";
  for (char c : line)
    if (!std::isdigit(static_cast<unsigned char>(c))) key += c;
  const auto now = std::chrono::steady_clock::now();
  auto it = last_error_.find(key);
  if (it != last_error_.end() && now - it->second < std::chrono::seconds(1)) return;
  last_error_[key] = now;
  ROS_ERROR("%s model '%s': %s", Tag(), model_name_.c_str(), line.c_str());
}

void AutopilotInterface::Info(const std::string& line) {
  ROS_INFO("%s model '%s': %s", Tag(), model_name_.c_str(), line.c_str());
}

}  // namespace rotors_gazebo_plugins
