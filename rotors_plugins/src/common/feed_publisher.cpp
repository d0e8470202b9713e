#include "rotors_gazebo_plugins/ros/feed_publisher.h"

#include <algorithm>

#include <mav_msgs/common.h>
#include <tf2_ros/transform_broadcaster.h>

namespace rotors_gazebo_plugins {

void Fill(const ImuReading& reading, sensor_msgs::Imu* msg) {
  mav_msgs::quaternionEigenToMsg(reading.q_WI, &msg->orientation);  // ground truth, as RotorS (covariance -1)
  msg->angular_velocity = ToVector3Msg(reading.measured.angular_velocity_I);
  msg->linear_acceleration = ToVector3Msg(reading.measured.linear_acceleration_I);
}

void Fill(const BarometerReading& reading, sensor_msgs::FluidPressure* msg) {
  msg->fluid_pressure = reading.pressure_Pa;
}

void Fill(const MagnetometerReading& reading, sensor_msgs::MagneticField* msg) {
  msg->magnetic_field = ToVector3Msg(reading.field_B_T);
}

void Fill(const AirspeedReading& reading, geometry_msgs::Vector3Stamped* msg) {
  msg->vector = ToVector3Msg(reading.air_velocity_B_m_s);
}

void Fill(const RangeReading& reading, sensor_msgs::Range* msg) {
  msg->range = static_cast<float>(reading.range_m);
  msg->min_range = static_cast<float>(reading.min_range_m);
  msg->max_range = static_cast<float>(reading.max_range_m);
}

void Fill(const GpsReading& reading, sensor_msgs::NavSatFix* msg) {
  msg->latitude = reading.fix.latitude_longitude_altitude.x();
  msg->longitude = reading.fix.latitude_longitude_altitude.y();
  msg->altitude = reading.fix.latitude_longitude_altitude.z();
}

void Fill(const GroundSpeedReading& reading, geometry_msgs::TwistStamped* msg) {
  msg->twist.linear = ToVector3Msg(reading.velocity_W_m_s);
}

void Fill(const OpticalFlowReading& reading, mavros_msgs::OpticalFlowRad* msg) {
  msg->integration_time_us = reading.integration_time_us;
  msg->integrated_x = static_cast<float>(reading.integrated_xy_rad.x());
  msg->integrated_y = static_cast<float>(reading.integrated_xy_rad.y());
  msg->integrated_xgyro = static_cast<float>(reading.integrated_gyro_rad.x());
  msg->integrated_ygyro = static_cast<float>(reading.integrated_gyro_rad.y());
  msg->integrated_zgyro = static_cast<float>(reading.integrated_gyro_rad.z());
  msg->distance = static_cast<float>(reading.distance_m);
  msg->quality = static_cast<uint8_t>(reading.quality);
}

OdometryFeedPublisher::OdometryFeedPublisher() = default;
OdometryFeedPublisher::~OdometryFeedPublisher() = default;

void OdometryFeedPublisher::Start(SensorFeed<OdometryMeasurement>& feed, rotors_sim::physics::World& world,
                                  const std::string& robot_namespace, const OdometryTopics& topics,
                                  const std::string& parent_frame, const std::string& child_frame,
                                  const std::vector<double>& pose_covariance,
                                  const std::vector<double>& twist_covariance, bool broadcast_tf) {
  parent_frame_ = parent_frame;
  child_frame_ = child_frame;
  pose_covariance_ = pose_covariance;
  twist_covariance_ = twist_covariance;
  node_ = MakeNode(robot_namespace);
  pose_pub_ = Advertise<geometry_msgs::Pose>(node_, robot_namespace, topics.pose, world, 10);
  pose_cov_pub_ = Advertise<geometry_msgs::PoseWithCovarianceStamped>(node_, robot_namespace,
                                                                      topics.pose_with_covariance, world, 10);
  position_pub_ = Advertise<geometry_msgs::PointStamped>(node_, robot_namespace, topics.position, world, 10);
  transform_pub_ = Advertise<geometry_msgs::TransformStamped>(node_, robot_namespace, topics.transform, world, 10);
  odometry_pub_ = Advertise<nav_msgs::Odometry>(node_, robot_namespace, topics.odometry, world, 10);
  if (node_ && broadcast_tf) tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  if (!odometry_pub_) return;  // neither ROS nor in-process taps: the feed alone takes the readings
  connection_ = feed.Listen([this](const OdometryMeasurement& m, double t_s) { Publish(m, t_s); });
}

void OdometryFeedPublisher::Publish(const OdometryMeasurement& m, double t_s) {
  geometry_msgs::Pose pose;
  mav_msgs::pointEigenToMsg(m.p_W, &pose.position);
  mav_msgs::quaternionEigenToMsg(m.q_WS, &pose.orientation);
  std_msgs::Header header;
  header.stamp = StampOf(t_s);
  header.frame_id = parent_frame_;
  if (pose_pub_.getNumSubscribers() > 0) pose_pub_.publish(pose);
  if (pose_cov_pub_.getNumSubscribers() > 0) {
    geometry_msgs::PoseWithCovarianceStamped msg;
    msg.header = header;
    msg.pose.pose = pose;
    std::copy(pose_covariance_.begin(), pose_covariance_.end(), msg.pose.covariance.begin());
    pose_cov_pub_.publish(msg);
  }
  if (position_pub_.getNumSubscribers() > 0) {
    geometry_msgs::PointStamped msg;
    msg.header = header;
    msg.point = pose.position;
    position_pub_.publish(msg);
  }
  geometry_msgs::TransformStamped tf;
  tf.header = header;
  tf.child_frame_id = child_frame_;
  mav_msgs::vectorEigenToMsg(m.p_W, &tf.transform.translation);
  tf.transform.rotation = pose.orientation;
  if (transform_pub_.getNumSubscribers() > 0) transform_pub_.publish(tf);
  if (tf_) tf_->sendTransform(tf);
  if (odometry_pub_.getNumSubscribers() > 0) {
    nav_msgs::Odometry msg;
    msg.header = header;
    msg.child_frame_id = child_frame_;
    msg.pose.pose = pose;
    std::copy(pose_covariance_.begin(), pose_covariance_.end(), msg.pose.covariance.begin());
    msg.twist.twist.linear = ToVector3Msg(m.v_S);  // body (child) frame, as RotorS
    msg.twist.twist.angular = ToVector3Msg(m.omega_S);
    std::copy(twist_covariance_.begin(), twist_covariance_.end(), msg.twist.covariance.begin());
    odometry_pub_.publish(msg);  // as a shared copy (ListenedPublisher): a controller nodelet gets it at once
  }
}

}  // namespace rotors_gazebo_plugins
