// What the laser plugins share: a ray sensor's scan as sensor_msgs (LaserScan, velodyne's
// PointCloud2, the block laser's PointCloud, Range), and LaserPlugin, the base that reads the
// common parameters, checks the sensor and publishes each new scan once.
#pragma once

#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sdf/Element.hh>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>

#include "rotors_core/plugin.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/sensors/ray_sensor.h"
#include "rotors_gazebo_plugins/ros/feed_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

using rotors_sim::sensors::RayScan;
using rotors_sim::sensors::RayScanSpec;

/// REP 117 LaserScan of a one-row scan: angle_min/max/increment from the beams, time_increment
/// the column period of a sweep (0 for an instantaneous scan), ranges as the sensor keeps them.
void ToLaserScanMsg(const RayScan& scan, const RayScanSpec& spec, double scan_time_s, bool over_time,
                    sensor_msgs::LaserScan* msg);

/// velodyne_pointcloud's point layout (PointXYZIRT): x y z float32 at 0 4 8, intensity float32 at
/// 16, ring uint16 at 20, time float32 at 24 (s since the header stamp), 32 bytes a point.
struct VelodyneCloudOptions {
  double min_range_m = 0.0, max_range_m = 1e9;  ///< returns outside are dropped (NaN if organised)
  double min_intensity = -1e300;
  bool organize = false;  ///< height = rings, width = columns, NaN where there is no return
};
/// d_S: the beams' directions (RaySensor::BeamDirections_S()).
void ToVelodyneCloudMsg(const RayScan& scan, const RayScanSpec& spec, const std::vector<Eigen::Vector3d>& d_S,
                        const VelodyneCloudOptions& options, sensor_msgs::PointCloud2* msg);

/// gazebo_ros_block_laser's sensor_msgs/PointCloud: every return as a point, channel "intensity".
void ToBlockCloudMsg(const RayScan& scan, const RayScanSpec& spec, const std::vector<Eigen::Vector3d>& d_S,
                     sensor_msgs::PointCloud* msg);

/// The nearest return of the whole beam cone (Note 9: an ultrasonic sensor measures the shortest
/// distance in its cone): -inf if any beam is closer than min range, +inf if none returns.
float NearestReturn(const RayScan& scan);

/// Adds N(0, sigma) to every finite range (a plugin's own <gaussianNoise>).
void AddRangeNoise(double sigma_m, std::mt19937_64* rng, RayScan* scan);

/// The base of the laser plugins: checks that the sensor is a ray sensor, reads robotNamespace
/// (default: the model's name), topicName, frameName (default: the sensor's link), updateRate and
/// the plugin's own parameters, and calls Publish for each new scan (at most updateRate).
class LaserPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr sdf) final;
  /// The noise generator at its seed again and the scan count from 0 (the sensor's restarts too).
  void Reset() final;

 protected:
  /// The plugin's default topic.
  virtual std::string DefaultTopic() const = 0;
  /// Reads the plugin's own parameters (besides the common ones) through `params` and checks the
  /// sensor; throws SimError with the problem. What it does not read is rejected by the loader.
  virtual void Configure(rotors_sim::SdfParams& /*params*/) {}
  /// Advertises topic_ (on node_ when ROS runs); false when there is nobody to publish to.
  virtual bool Advertise() = 0;
  /// topic_ on ROS (node_) and into the world's message taps once an in-process reader names it
  /// (World.listen: rotors_sim, the ROS 2 front end); false when there is neither.
  template <class M>
  bool AdvertiseListened(rotors_sim::ListenedPublisher* pub) {
    *pub = rotors_gazebo_plugins::Advertise<M>(node_, robot_namespace_, topic_, WorldOf(*sensor_), 4, false, true);
    return static_cast<bool>(*pub);
  }
  virtual void Publish(const RayScan& scan, const ros::Time& stamp) = 0;

  rotors_sim::sensors::RaySensorPtr sensor_;
  std::shared_ptr<ros::NodeHandle> node_;
  std::string robot_namespace_, topic_, frame_;
  std::mt19937_64 rng_;  ///< for the plugin's own noise, seeded by model, sensor and plugin name
  uint64_t seed_ = 0;

 private:
  double update_rate_hz_ = 0.0, last_published_s_ = -1.0;
  uint64_t published_scans_ = 0;
  rotors_sim::event::ConnectionPtr connection_;
};

/// What the single-range plugins share (the lidar, gazebo_ros_range): each range on the vehicle bus
/// (the autopilot interfaces read it there), whether or not anyone listens, and from there as
/// sensor_msgs/Range (prototype_ with the range, its limits and stamp).
class RangePlugin : public LaserPlugin {
 protected:
  bool Advertise() final;
  /// The range [m] (REP 117's +-inf out of range) with the sensor's limits, taken at `stamp`, on the bus.
  void PutRange(float range_m, const ros::Time& stamp);

  /// radiation_type and field_of_view, set in Configure(); frame_ and the sensor's limits, set in Advertise()
  sensor_msgs::Range prototype_;

 private:
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<RangeReading>* feed_ = nullptr;
  FeedPublisher<RangeReading, sensor_msgs::Range> publisher_;
};

}  // namespace rotors_gazebo_plugins
