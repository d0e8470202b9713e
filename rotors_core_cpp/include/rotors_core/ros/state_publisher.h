// Publishes what rviz and tools need to see the world: TF world -> each model's canonical link,
// /<model>/joint_states, /gazebo/model_states and /gazebo/link_states.
#pragma once

#include <map>
#include <string>

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/ros/real_time_pacer.h"

namespace rotors_sim {

class StatePublisher {
 public:
  /// rate_hz in sim time, at most max_wall_rate_hz per wall second (<= 0: no limit).
  StatePublisher(ros::NodeHandle nh, double rate_hz, double max_wall_rate_hz);
  /// Publishes if at least 1/rate has passed in sim time since the last time and the wall-time
  /// limit allows (or force).
  void Update(const physics::World& world, bool force = false);

 private:
  ros::NodeHandle nh_;
  double period_s_;
  double last_publish_s_ = -1e9;
  WallRateLimit wall_limit_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Publisher model_states_pub_, link_states_pub_;
  std::map<std::string, ros::Publisher> joint_state_pubs_;
};

}  // namespace rotors_sim
