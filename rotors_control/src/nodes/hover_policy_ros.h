// rl_policy_node's ROS face (and the same as a nodelet, in_process:=true): odometry + a target
// (command/trajectory or command/pose) -> command/roll_pitch_yawrate_thrust, which
// roll_pitch_yawrate_thrust_controller_node turns into rotor speeds, as RotorS' MPC hands its
// commands over. The policy (HoverPolicy) is read from the file in ~policy (train_policy.py's .npz).
// The target is the position of the set point TrajectorySchedule releases (trajectory_schedule.h, as
// the Lee node takes them). Yaw is not followed (the policy has no yaw target); a target farther than
// the policy learnt is approached through a point on the way (HoverPolicy::Observation). Before the
// first target the node commands zero thrust. Each command is stamped with the odometry stamp it
// answers (lockstep keys on this).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <mav_msgs/RollPitchYawrateThrust.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_control/policy_file.h"
#include "ros_conversions.h"
#include "trajectory_schedule.h"
#include "warning_throttle.h"

namespace rotors_control {

class HoverPolicyRos {
 public:
  static constexpr const char* kTag = "rl_policy";
  static constexpr const char* kNodeletType = "rotors_control/RlPolicyNodelet";

  /// Reads ~policy (throws std::invalid_argument naming a missing parameter or a bad file).
  HoverPolicyRos(ros::NodeHandle nh, ros::NodeHandle private_nh) : policy_(Load(private_nh)) {
    command_pub_ = nh.advertise<mav_msgs::RollPitchYawrateThrust>("command/roll_pitch_yawrate_thrust", 1);
    trajectory_sub_ = nh.subscribe("command/trajectory", 1, &HoverPolicyRos::OnTrajectory, this);
    pose_sub_ = nh.subscribe("command/pose", 1, &HoverPolicyRos::OnPose, this);
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

  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    TrajectoryPoint point;
    const std::string why = schedule_.FromPose(*msg, &point);
    if (!why.empty()) {
      if (warnings_.Due(why)) ROS_WARN("[%s] ignoring command/pose: %s", kTag, why.c_str());
      return;
    }
    target_W_ = point.position_W;
    has_target_ = true;
  }
  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    double ahead_s = 0.0;
    const std::string why = schedule_.Set(*msg, t_odometry_s_, &ahead_s);
    if (!why.empty()) {
      if (warnings_.Due(why)) ROS_WARN("[%s] ignoring trajectory: %s", kTag, why.c_str());
      return;
    }
    if (ahead_s > 0.0)
      ROS_WARN_THROTTLE(1.0,
                        "[%s] trajectory stamped %.0f s ahead of the odometry (a wall-clock stamp?); its points "
                        "count from now",
                        kTag, ahead_s);
    ReleaseDue(t_odometry_s_);
  }
  void ReleaseDue(double t_s) {
    TrajectoryPoint point;
    if (!schedule_.ReleaseDue(t_s, &point)) return;
    target_W_ = point.position_W;
    has_target_ = true;
  }
  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring odometry: %s (no command sent)", kTag, why.c_str());
      return;
    }
    t_odometry_s_ = msg->header.stamp.toSec();
    ReleaseDue(t_odometry_s_);
    mav_msgs::RollPitchYawrateThrust out;
    out.header.stamp = msg->header.stamp;
    out.header.frame_id = msg->child_frame_id;
    if (has_target_) {
      const VehicleState s = StateFromOdometry(*msg);
      const RollPitchYawrateThrust c = policy_.Command(policy_.Action(
          policy_.Observation(s.position_W, s.orientation_W_B, s.velocity_B, s.angular_velocity_B, target_W_)));
      out.roll = c.roll_rad;
      out.pitch = c.pitch_rad;
      out.yaw_rate = c.yaw_rate_rad_s;
      out.thrust.z = c.thrust_n;
    }
    command_pub_.publish(out);
  }

  HoverPolicy policy_;
  Eigen::Vector3d target_W_ = Eigen::Vector3d::Zero();
  bool has_target_ = false;
  TrajectorySchedule schedule_;
  WarningThrottle warnings_{1.0};  ///< set points ignored: one line per kind per second
  double t_odometry_s_ = 0.0;      ///< stamp of the latest odometry
  ros::Publisher command_pub_;
  ros::Subscriber trajectory_sub_, pose_sub_, odometry_sub_;
};

}  // namespace rotors_control
