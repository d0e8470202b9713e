#include "rotors_gazebo_plugins/ros/plugin_ros.h"

#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"

namespace rotors_gazebo_plugins {

rotors_sim::physics::World& WorldOf(const rotors_sim::sensors::Sensor& sensor) {
  return *sensor.ParentLink()->GetModel()->GetWorldRaw();
}

std::shared_ptr<ros::NodeHandle> MakeNode(const std::string& robot_namespace) {
  if (!ros::isInitialized()) return nullptr;
  return std::make_shared<ros::NodeHandle>("/" + robot_namespace);
}

std::string ResolveTopic(const std::string& robot_namespace, const std::string& topic) {
  if (!topic.empty() && topic[0] == '/') return topic;
  std::string ns = robot_namespace;
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  return ns.empty() ? "/" + topic : "/" + ns + "/" + topic;
}

}  // namespace rotors_gazebo_plugins
