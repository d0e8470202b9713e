// Engine poses and velocities as geometry_msgs, shared by the simulator's ROS face and the plugins.
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/Vector3.h>
#include <ignition/math/Pose3.hh>

namespace rotors_sim {

inline geometry_msgs::Vector3 Vector3Msg(const ignition::math::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.X();
  m.y = v.Y();
  m.z = v.Z();
  return m;
}

inline geometry_msgs::Quaternion QuaternionMsg(const ignition::math::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.w = q.W();
  m.x = q.X();
  m.y = q.Y();
  m.z = q.Z();
  return m;
}

inline geometry_msgs::Pose PoseMsg(const ignition::math::Pose3d& X) {
  geometry_msgs::Pose m;
  m.position.x = X.Pos().X();
  m.position.y = X.Pos().Y();
  m.position.z = X.Pos().Z();
  m.orientation = QuaternionMsg(X.Rot());
  return m;
}

/// Linear velocity v and angular velocity w, in whichever frame the caller expressed them.
inline geometry_msgs::Twist TwistMsg(const ignition::math::Vector3d& v, const ignition::math::Vector3d& w) {
  geometry_msgs::Twist m;
  m.linear = Vector3Msg(v);
  m.angular = Vector3Msg(w);
  return m;
}

}  // namespace rotors_sim
