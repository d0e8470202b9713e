// ROS access for plugins. Plugins also run without ROS (engine benchmarks and tests): then
// Node() is null and they skip publishing.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <geometry_msgs/Vector3.h>
#include <ros/ros.h>

#include "rotors_core/common.h"

namespace rotors_gazebo_plugins {

/// A node handle in /<robot_namespace>, or nullptr when ROS is not initialised in this process.
std::shared_ptr<ros::NodeHandle> MakeNode(const std::string& robot_namespace);

inline ros::Time ToRos(const rotors_sim::common::Time& t) {
  ros::Time r;
  r.fromNSec(static_cast<uint64_t>(t.Nanoseconds()));
  return r;
}

inline geometry_msgs::Vector3 ToVector3Msg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

}  // namespace rotors_gazebo_plugins
