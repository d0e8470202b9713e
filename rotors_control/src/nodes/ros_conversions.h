// Message <-> controller type conversions for the nodes.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Quaternion.h>
#include <mav_msgs/Actuators.h>
#include <nav_msgs/Odometry.h>

#include "rotors_control/lee_position_controller.h"

namespace rotors_control {

inline VehicleState StateFromOdometry(const nav_msgs::Odometry& odom) {
  VehicleState s;
  const auto& p = odom.pose.pose.position;
  const auto& q = odom.pose.pose.orientation;
  const auto& v = odom.twist.twist.linear;
  const auto& w = odom.twist.twist.angular;
  s.position_W = {p.x, p.y, p.z};
  s.orientation_W_B = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
  s.velocity_B = {v.x, v.y, v.z};  // nav_msgs/Odometry twist is in the child (body) frame
  s.angular_velocity_B = {w.x, w.y, w.z};
  return s;
}

/// "" if q is a unit quaternion (within 1e-3), else the reason.
inline std::string CheckUnitQuaternion(const geometry_msgs::Quaternion& q) {
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!std::isfinite(norm)) return "the orientation has NaN or inf";
  if (std::abs(norm - 1.0) > 1e-3) return "the orientation quaternion has norm " + std::to_string(norm) + ", not 1";
  return {};
}

inline double YawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

inline mav_msgs::Actuators ActuatorsMsg(const Eigen::VectorXd& omega, const ros::Time& stamp) {
  mav_msgs::Actuators msg;
  msg.header.stamp = stamp;
  msg.angular_velocities.assign(omega.data(), omega.data() + omega.size());
  return msg;
}

}  // namespace rotors_control
