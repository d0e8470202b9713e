// ROS access for plugins. Plugins also run without ROS (engine benchmarks, tests, the Python
// module): then MakeNode() is null, and Advertise() gives a publisher that only feeds the world's
// MessageTaps when they are enabled (Python reads them), or nothing at all (publishing is skipped).
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <geometry_msgs/Vector3.h>
#include <ros/ros.h>

#include "rotors_core/common.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_gazebo_plugins {

/// A node handle in /<robot_namespace>, or nullptr when ROS is not initialised in this process.
std::shared_ptr<ros::NodeHandle> MakeNode(const std::string& robot_namespace);

/// The world a sensor's link belongs to (where its plugin's taps and vehicle bus live).
rotors_sim::physics::World& WorldOf(const rotors_sim::sensors::Sensor& sensor);

/// `topic` resolved as a node handle in /<robot_namespace> resolves it ("/ns/topic", or `topic` if absolute).
std::string ResolveTopic(const std::string& robot_namespace, const std::string& topic);

/// A publisher of `topic` (relative to the node's namespace) on ROS when `node` is not null, and
/// into the world's MessageTaps when they are enabled (`tap_on_request`: only once a reader names
/// the topic, for messages that cost much to build). Empty (false) when neither.
template <class M>
rotors_sim::ListenedPublisher Advertise(const std::shared_ptr<ros::NodeHandle>& node,
                                        const std::string& robot_namespace, const std::string& topic,
                                        rotors_sim::physics::World& world, uint32_t queue_size = 10, bool latch = false,
                                        bool tap_on_request = false) {
  const std::string resolved = node ? node->resolveName(topic) : ResolveTopic(robot_namespace, topic);
  rotors_sim::TappedMessage* tap = rotors_sim::MessageTaps::Of(world).Slot(resolved, tap_on_request);
  if (tap && tap->datatype.empty())
    tap->datatype = ros::message_traits::DataType<M>::value();  // before the first message
  if (!node && !tap) return {};
  ros::Publisher publisher;
  if (node) publisher = node->advertise<M>(topic, queue_size, latch);
  return rotors_sim::ListenedPublisher(publisher, resolved, rotors_sim::PublishCounts::Of(world), tap);
}

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
