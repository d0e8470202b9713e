// rl_policy_node's ROS face (and the same as a nodelet, in_process:=true): odometry + a target
// (command/trajectory or command/pose) -> command/roll_pitch_yawrate_thrust, which
// roll_pitch_yawrate_thrust_controller_node turns into rotor speeds, as RotorS' MPC hands its
// commands over. The policy (HoverPolicy) is read from the file in ~policy (train_policy.py's .npz).
// The target is the position of the set point SetPointInput releases (trajectory_schedule.h, as the
// Lee node takes them). Yaw is not followed (the policy has no yaw target); a target farther than
// the policy learnt is approached through a point on the way (HoverPolicy::Observation). Before the
// first target the node commands zero thrust. Each command is stamped with the odometry stamp it
// answers (lockstep keys on this).
#pragma once

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <mav_msgs/RollPitchYawrateThrust.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "rotors_control/policy_file.h"
#include "ros_conversions.h"
#include "trajectory_schedule.h"

namespace rotors_control {

class HoverPolicyRos {
 public:
  static constexpr const char* kTag = "rl_policy";
  static constexpr const char* kNodeletType = "rotors_control/RlPolicyNodelet";

  /// Reads ~policy (throws std::invalid_argument naming a missing parameter or a bad file).
  HoverPolicyRos(ros::NodeHandle nh, ros::NodeHandle private_nh)
      : policy_(Load(private_nh)),
        set_points_(nh, kTag, [this](const TrajectoryPoint& p) { target_W_ = p.position_W; }) {
    command_pub_ = nh.advertise<mav_msgs::RollPitchYawrateThrust>("command/roll_pitch_yawrate_thrust", 1);
    odometry_sub_ = nh.subscribe("odometry", 1, &HoverPolicyRos::OnOdometry, this, ros::TransportHints().tcpNoDelay());
  }

 private:
  static HoverPolicy Load(const ros::NodeHandle& private_nh) {
    std::string path;
    if (!private_nh.getParam("policy", path) || path.empty())
      throw std::invalid_argument(
          "parameter ~policy (the policy file, e.g. rotors_control/policies/"
          "firefly_hover_randomized.npz) is missing");
    HoverPolicy policy(LoadHoverPolicy(path));
    ROS_INFO("[%s] policy %s: %zu layers, thrust %.3f N at a_3 = 0, tilt up to %.2f rad", kTag, path.c_str(),
             policy.Parameters().layers.size(), policy.Parameters().hover_thrust_n, policy.Parameters().max_tilt_rad);
    return policy;
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring odometry: %s (no command sent)", kTag, why.c_str());
      return;
    }
    set_points_.Release(msg->header.stamp.toSec());
    mav_msgs::RollPitchYawrateThrust out;
    out.header.stamp = msg->header.stamp;
    out.header.frame_id = msg->child_frame_id;
    if (target_W_) {
      const VehicleState s = StateFromOdometry(*msg);
      const RollPitchYawrateThrust c = policy_.Command(policy_.Action(
          policy_.Observation(s.position_W, s.orientation_W_B, s.velocity_B, s.angular_velocity_B, *target_W_)));
      out.roll = c.roll_rad;
      out.pitch = c.pitch_rad;
      out.yaw_rate = c.yaw_rate_rad_s;
      out.thrust.z = c.thrust_n;
    }
    command_pub_.publish(out);
  }

  HoverPolicy policy_;
  std::optional<Eigen::Vector3d> target_W_;  ///< none before the first set point
  SetPointInput set_points_;
  ros::Publisher command_pub_;
  ros::Subscriber odometry_sub_;
};

}  // namespace rotors_control
