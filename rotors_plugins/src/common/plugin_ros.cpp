#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

std::shared_ptr<ros::NodeHandle> MakeNode(const std::string& robot_namespace) {
  if (!ros::isInitialized()) return nullptr;
  return std::make_shared<ros::NodeHandle>("/" + robot_namespace);
}

}  // namespace rotors_gazebo_plugins
