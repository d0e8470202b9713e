// What the controller nodes add to the mav_msgs C++ API: the controller's state type from
// odometry, a rejecting (not normalising) quaternion check, and the motor command message.
#pragma once

#include <cmath>
#include <string>

#include <geometry_msgs/Quaternion.h>
#include <mav_msgs/conversions.h>
#include <nav_msgs/Odometry.h>

#include "rotors_control/lee_controller.h"

namespace rotors_control {

inline VehicleState StateFromOdometry(const nav_msgs::Odometry& msg) {
  mav_msgs::EigenOdometry odometry;
  mav_msgs::eigenOdometryFromMsg(msg, &odometry);
  VehicleState s;
  s.position_W = odometry.position_W;
  s.orientation_W_B = odometry.orientation_W_B;
  s.velocity_B = odometry.velocity_B;  // nav_msgs/Odometry twist is in the child (body) frame
  s.angular_velocity_B = odometry.angular_velocity_B;
  return s;
}

/// "" if q is a unit quaternion (within 1e-3), else the reason.
inline std::string CheckUnitQuaternion(const geometry_msgs::Quaternion& q) {
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!std::isfinite(norm)) return "the orientation has NaN or inf";
  if (std::abs(norm - 1.0) > 1e-3) return "the orientation quaternion has norm " + std::to_string(norm) + ", not 1";
  return {};
}

/// "" if the odometry can drive a controller (finite, unit quaternion), else the reason.
inline std::string CheckOdometry(const nav_msgs::Odometry& msg) {
  const auto& p = msg.pose.pose.position;
  const auto& v = msg.twist.twist.linear;
  const auto& w = msg.twist.twist.angular;
  if (!std::isfinite(p.x + p.y + p.z)) return "position has NaN or inf";
  if (!std::isfinite(v.x + v.y + v.z)) return "linear velocity has NaN or inf";
  if (!std::isfinite(w.x + w.y + w.z)) return "angular velocity has NaN or inf";
  return CheckUnitQuaternion(msg.pose.pose.orientation);
}

inline mav_msgs::Actuators ActuatorsMsg(const Eigen::VectorXd& omega, const ros::Time& stamp) {
  mav_msgs::Actuators msg;
  msg.header.stamp = stamp;
  mav_msgs::msgActuatorsFromEigen(mav_msgs::EigenActuators(omega), &msg);
  return msg;
}

}  // namespace rotors_control
