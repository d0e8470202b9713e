// ROS publishing reads the vehicle bus. A sensor plugin puts its reading on its feed
// (sensor_feeds.h) and builds no message; a FeedPublisher listens to the feed and builds the
// message from each reading: the fixed fields (frame, covariance, radiation type) the plugin gives
// once as the prototype, the reading's fields through Fill(), the stamp from the reading's time.
// The message taps (the Python module, the ROS 2 front end) and bags see that message, so every
// reader of a sensor, in process or over ROS, reads the one reading the bus holds.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <mavros_msgs/OpticalFlowRad.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>

#include "rotors_core/common.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/sensor_feeds.h"

namespace tf2_ros {
class TransformBroadcaster;
}

namespace rotors_gazebo_plugins {

/// A feed's time [s] as the ROS stamp the sensor took it at (sim time is whole nanoseconds).
inline ros::Time StampOf(double t_s) { return ToRos(rotors_sim::common::Time::FromSeconds(t_s)); }

// A reading's fields in its message (everything else stays as the prototype has it).
void Fill(const ImuReading& reading, sensor_msgs::Imu* msg);
void Fill(const BarometerReading& reading, sensor_msgs::FluidPressure* msg);
void Fill(const MagnetometerReading& reading, sensor_msgs::MagneticField* msg);
void Fill(const AirspeedReading& reading, geometry_msgs::Vector3Stamped* msg);
void Fill(const RangeReading& reading, sensor_msgs::Range* msg);
void Fill(const GpsReading& reading, sensor_msgs::NavSatFix* msg);
void Fill(const GroundSpeedReading& reading, geometry_msgs::TwistStamped* msg);
void Fill(const OpticalFlowReading& reading, mavros_msgs::OpticalFlowRad* msg);

/// Publishes every reading put on one feed as one message type on one topic.
template <class Reading, class Msg>
class FeedPublisher {
 public:
  /// Advertises <robot_namespace>/<topic> (ROS, or the world's taps) and from now on publishes each
  /// reading put on `feed` as `prototype` with the reading's fields and stamp. False when nobody can
  /// listen (no ROS in this process, no taps): the feed still takes every reading.
  bool Start(SensorFeed<Reading>& feed, rotors_sim::physics::World& world, const std::string& robot_namespace,
             const std::string& topic, Msg prototype, uint32_t queue_size = 10) {
    node_ = MakeNode(robot_namespace);
    pub_ = Advertise<Msg>(node_, robot_namespace, topic, world, queue_size);
    if (!pub_) return false;
    msg_ = std::move(prototype);
    connection_ = feed.Listen([this](const Reading& reading, double t_s) {
      msg_.header.stamp = StampOf(t_s);
      Fill(reading, &msg_);
      pub_.publish(msg_);
    });
    return true;
  }

 private:
  Msg msg_;
  std::shared_ptr<ros::NodeHandle> node_;
  rotors_sim::ListenedPublisher pub_;  // no search through every topic per reading
  rotors_sim::event::ConnectionPtr connection_;
};

/// The odometry sensor's topics (RotorS' odometry plugin: pose, pose_with_covariance, position,
/// transform, odometry) and its TF, each built from the reading on the odometry feed, each only
/// while someone listens.
struct OdometryTopics {
  std::string pose = "pose", pose_with_covariance = "pose_with_covariance", position = "position",
              transform = "transform", odometry = "odometry";
};

class OdometryFeedPublisher {
 public:
  OdometryFeedPublisher();
  ~OdometryFeedPublisher();
  /// `parent_frame`, `child_frame`: the header's and the child frame ids; covariances row-major 6 x 6
  /// (pose: x y z roll pitch yaw; twist: linear, angular); `broadcast_tf`: also send the transform on TF.
  void Start(SensorFeed<OdometryMeasurement>& feed, rotors_sim::physics::World& world,
             const std::string& robot_namespace, const OdometryTopics& topics, const std::string& parent_frame,
             const std::string& child_frame, const std::vector<double>& pose_covariance,
             const std::vector<double>& twist_covariance, bool broadcast_tf);

 private:
  void Publish(const OdometryMeasurement& m, double t_s);

  std::string parent_frame_, child_frame_;
  std::vector<double> pose_covariance_, twist_covariance_;
  std::shared_ptr<ros::NodeHandle> node_;
  rotors_sim::ListenedPublisher pose_pub_, pose_cov_pub_, position_pub_, transform_pub_, odometry_pub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins
