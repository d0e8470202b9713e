// The sensors' readings on the vehicle bus, as plain values in SI units and our frames (no ROS): each
// sensor plugin puts its reading here when it takes one, and that is all it does with it. Every
// reader takes it from here: ROS publishing (ros/feed_publisher.h builds each message from the
// reading, and the message taps, bags and the ROS 2 front end see that message), the autopilot
// interfaces' snapshot, the Python module's accessors, a controller attached in the engine. A feed
// is keyed by the sensor's resolved topic name ("/firefly/imu"), so a reader picks one of two IMUs
// as a ROS node would.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_core/event.h"

#include "rotors_gazebo_plugins/models/imu_noise_model.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/models/odometry_model.h"

namespace rotors_gazebo_plugins {

/// An IMU's reading: the measured rates and specific force, and the IMU's true orientation (RotorS'
/// sensor_msgs/Imu carries the ground-truth orientation beside the measurement).
struct ImuReading {
  ImuSample measured;
  Eigen::Quaterniond q_WI = Eigen::Quaterniond::Identity();
};

/// A GPS fix: the model's sample and the fix's stated accuracy (1 sigma).
struct GpsReading {
  GpsSample fix;
  double horizontal_std_m = 0.0, vertical_std_m = 0.0;
};

struct GroundSpeedReading {
  Eigen::Vector3d velocity_W_m_s = Eigen::Vector3d::Zero();  ///< ENU
};

struct BarometerReading {
  double pressure_Pa = 0.0;
};

struct MagnetometerReading {
  Eigen::Vector3d field_B_T = Eigen::Vector3d::Zero();  ///< [T] the sensor's link frame
};

/// The air's velocity relative to the sensor, in its link frame (a pitot: the axis' component only).
struct AirspeedReading {
  Eigen::Vector3d air_velocity_B_m_s = Eigen::Vector3d::Zero();
};

/// One range (REP 117: +inf no return within range_max, -inf closer than range_min).
struct RangeReading {
  double range_m = 0.0, min_range_m = 0.0, max_range_m = 0.0;
};

/// An optical flow sensor's integrated sample (PX4Flow's, as MAVLink's OPTICAL_FLOW_RAD carries it).
struct OpticalFlowReading {
  uint32_t integration_time_us = 0;
  Eigen::Vector2d integrated_xy_rad = Eigen::Vector2d::Zero();
  Eigen::Vector3d integrated_gyro_rad = Eigen::Vector3d::Zero();  ///< 0: the sensor has no gyro
  double distance_m = -1.0;                                       ///< -1: unknown
  int quality = 0;                                                ///< 0: no valid flow .. 255
};

/// The latest reading of one sensor, and whoever listens for each new one.
template <class Reading>
struct SensorFeed {
  Reading latest{};
  double time_s = 0.0;  ///< [s] sim time the reading is stamped with
  uint64_t count = 0;   ///< readings since load (a reset does not restart it)
  bool fresh = false;   ///< a reading since load or the last reset

  /// The one way a reading enters: kept as the latest, then handed to every listener in turn.
  void Put(const Reading& reading, double t_s) {
    latest = reading;
    time_s = t_s;
    ++count;
    fresh = true;
    if (put_.ConnectionCount() > 0) put_(latest, time_s);
  }
  /// Calls `on_reading(reading, t_s)` for every reading put from now on, while the connection lives.
  rotors_sim::event::ConnectionPtr Listen(std::function<void(const Reading&, double)> on_reading) {
    return put_.Connect(std::move(on_reading));
  }

 private:
  rotors_sim::event::EventT<const Reading&, double> put_;
};

/// The feeds of one kind of sensor, by resolved topic. A reader may hold a feed before its plugin
/// loads (Of creates it empty); std::map keeps the addresses valid.
template <class Reading>
class SensorFeeds {
 public:
  SensorFeed<Reading>& Of(const std::string& topic) { return feeds_[topic]; }
  const SensorFeed<Reading>* Find(const std::string& topic) const {
    auto it = feeds_.find(topic);
    return it == feeds_.end() ? nullptr : &it->second;
  }
  /// The topics with a feed (a plugin's, or one a reader asked for).
  std::vector<std::string> Topics() const {
    std::vector<std::string> topics;
    for (const auto& kv : feeds_) topics.push_back(kv.first);
    return topics;
  }
  /// After a reset: no reader sees a reading from before it.
  void Forget() {
    for (auto& kv : feeds_) kv.second.fresh = false;
  }

 private:
  std::map<std::string, SensorFeed<Reading>> feeds_;
};

/// Every sensor reading of one vehicle.
struct SensorReadings {
  SensorFeeds<ImuReading> imu;                ///< [rad/s], specific force [m/s^2], IMU frame
  SensorFeeds<OdometryMeasurement> odometry;  ///< the odometry sensor's pose and body-frame twist
  SensorFeeds<GpsReading> gps;
  SensorFeeds<GroundSpeedReading> ground_speed;
  SensorFeeds<BarometerReading> barometer;
  SensorFeeds<MagnetometerReading> magnetometer;
  SensorFeeds<AirspeedReading> airspeed;
  SensorFeeds<RangeReading> range;
  SensorFeeds<OpticalFlowReading> optical_flow;

  void Forget() {
    imu.Forget();
    odometry.Forget();
    gps.Forget();
    ground_speed.Forget();
    barometer.Forget();
    magnetometer.Forget();
    airspeed.Forget();
    range.Forget();
    optical_flow.Forget();
  }
};

}  // namespace rotors_gazebo_plugins
