// The Lee position controller's ROS face, the same as a node (lee_position_controller_node) and as a
// nodelet in the simulator's process (in_process:=true): odometry + command/trajectory |
// command/pose -> command/motor_speed.
// Ours: motor_failure (rotors_comm/MotorFailure) re-allocates without (or with a derated) rotor.
// Parameters from the private namespace (lee_controller_<mav>.yaml and <mav>.yaml). Trajectory
// point i is due at header.stamp + time_from_start_i (sim time; an unstamped trajectory counts from
// the latest odometry) and is released with the first odometry stamped at or after that time, so
// that in lockstep a set point sent ahead of time takes effect at the same step in every run. A
// point already due is applied at once (RotorS). The motor command is stamped with the odometry
// stamp it answers (lockstep keys on this).
#pragma once

#include <deque>
#include <boost/make_shared.hpp>
#include <stdexcept>

#include <geometry_msgs/PoseStamped.h>
#include <mav_msgs/Actuators.h>
#include <rotors_comm/MotorFailure.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_control/lee_controller.h"
#include "rotors_control/rotors_api_conversions.h"
#include "rotors_control/parameter_report_ros.h"
#include "ros_conversions.h"

namespace rotors_control {

class LeePositionControllerRos {
 public:
  static constexpr const char* kTag = "lee_position_controller";
  static constexpr const char* kNodeletType = "rotors_control/LeePositionControllerNodelet";

  /// Reads the parameters from `private_nh` (throws std::invalid_argument naming a missing or bad
  /// one) and connects the topics below `nh`.
  LeePositionControllerRos(ros::NodeHandle nh, ros::NodeHandle private_nh)
      : nh_(nh), controller_(LoadParameters(private_nh)) {
    motor_pub_ = nh_.advertise<mav_msgs::Actuators>(mav_msgs::default_topics::COMMAND_ACTUATORS, 1);
    trajectory_sub_ =
        nh_.subscribe(mav_msgs::default_topics::COMMAND_TRAJECTORY, 1, &LeePositionControllerRos::OnTrajectory, this);
    pose_sub_ = nh_.subscribe(mav_msgs::default_topics::COMMAND_POSE, 1, &LeePositionControllerRos::OnPose, this);
    failure_sub_ = nh_.subscribe("motor_failure", 10, &LeePositionControllerRos::OnMotorFailure, this);
    odometry_sub_ = nh_.subscribe(mav_msgs::default_topics::ODOMETRY, 1, &LeePositionControllerRos::OnOdometry, this,
                                  ros::TransportHints().tcpNoDelay());
  }

 private:
  static LeeControllerParameters LoadParameters(const ros::NodeHandle& private_nh) {
    LeeControllerParameters params;
    ParameterReader reader(private_nh);
    const std::string why = LoadLeeParameters(reader, &params);
    if (!why.empty()) throw std::invalid_argument(why);
    ReportParameters(reader, kTag);
    ROS_INFO("[lee_position_controller] saturation: max_tilt_angle %s, thrust %s",
             params.max_tilt_angle_rad > 0.0 ? (std::to_string(params.max_tilt_angle_rad) + " rad").c_str()
                                             : "not limited (no max_tilt_angle)",
             params.vehicle.AllRotorsLimited() ? "lowered to keep the torques when a rotor reaches max_rot_velocity"
                                               : "not limited (no rotor_configuration/i/max_rot_velocity)");
    return params;
  }

  /// A motor fault the simulator (or a real MAV's failure detection) announces: re-allocate.
  void OnMotorFailure(const rotors_comm::MotorFailureConstPtr& msg) {
    const std::string why = msg->motor_number < 0
                                ? "motor_number must be >= 0"
                                : controller_.SetRotorSpeedFactor(msg->motor_number, msg->speed_factor);
    if (!why.empty()) {
      ROS_ERROR_THROTTLE(1.0, "[lee_position_controller] motor_failure not applied: %s", why.c_str());
      return;
    }
    ROS_WARN("[lee_position_controller] motor %d at %.2f of its command: allocation updated", msg->motor_number,
             msg->speed_factor);
  }

  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    const std::string why = CheckUnitQuaternion(msg->pose.orientation);
    const auto& p = msg->pose.position;
    if (!why.empty() || !std::isfinite(p.x + p.y + p.z)) {
      ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring command/pose: %s",
                        why.empty() ? "position has NaN or inf" : why.c_str());
      return;
    }
    pending_.clear();
    TrajectoryPoint point;
    point.position_W = {p.x, p.y, p.z};
    point.yaw_rad = mav_msgs::yawFromQuaternion(mav_msgs::quaternionFromMsg(msg->pose.orientation));
    controller_.SetTrajectoryPoint(point);
  }

  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    if (msg->points.empty()) {
      ROS_WARN_THROTTLE(1.0,
                        "[lee_position_controller] Got MultiDOFJointTrajectory message, but message has no points; "
                        "ignored");
      return;
    }
    std::deque<std::pair<double, TrajectoryPoint>> points;
    for (size_t i = 0; i < msg->points.size(); ++i) {
      const auto& pt = msg->points[i];
      if (pt.transforms.empty()) {
        ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring trajectory: point %zu has no transform", i);
        return;
      }
      const std::string why = CheckUnitQuaternion(pt.transforms[0].rotation);
      if (!why.empty()) {
        ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring trajectory: point %zu: %s", i, why.c_str());
        return;
      }
      mav_msgs::EigenTrajectoryPoint eigen_point;
      mav_msgs::eigenTrajectoryPointFromMsg(pt, &eigen_point);
      const TrajectoryPoint p = TrajectoryPointFromEigen(eigen_point);
      if (!p.IsFinite()) {
        ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring trajectory: point %zu has NaN or inf", i);
        return;
      }
      // time_from_start: >= 0 and not decreasing, within a day
      const double t_s = pt.time_from_start.toSec();
      if (!(t_s >= 0.0 && t_s <= kMaxTimeFromStart_s && (points.empty() || t_s >= points.back().first))) {
        ROS_WARN_THROTTLE(1.0,
                          "[lee_position_controller] ignoring trajectory: point %zu has time_from_start %.3f s; it "
                          "must be in [0, %.0f] s and not below the point before",
                          i, t_s, kMaxTimeFromStart_s);
        return;
      }
      points.emplace_back(t_s, p);
    }
    double t0_s = msg->header.stamp.isZero() ? t_odometry_s_ : msg->header.stamp.toSec();
    if (t0_s - t_odometry_s_ > kMaxTimeFromStart_s) {
      ROS_WARN_THROTTLE(1.0,
                        "[lee_position_controller] trajectory stamped %.0f s ahead of the odometry (a wall-clock "
                        "stamp?); its points count from now",
                        t0_s - t_odometry_s_);
      t0_s = t_odometry_s_;
    }
    for (auto& point : points) point.first += t0_s;  // due times
    pending_ = std::move(points);
    ReleaseDue(t_odometry_s_);
  }

  /// Applies every pending point due at or before t_s (the latest applied wins).
  void ReleaseDue(double t_s) {
    while (!pending_.empty() && pending_.front().first <= t_s) {
      controller_.SetTrajectoryPoint(pending_.front().second);
      pending_.pop_front();
    }
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring odometry: %s (no command sent)", why.c_str());
      return;
    }
    t_odometry_s_ = msg->header.stamp.toSec();
    ReleaseDue(t_odometry_s_);
    // a shared pointer: in the simulator's process (in_process:=true) it reaches the plugins unserialized
    motor_pub_.publish(boost::make_shared<mav_msgs::Actuators>(
        ActuatorsMsg(controller_.RotorSpeeds(StateFromOdometry(*msg)), msg->header.stamp)));
  }

  static constexpr double kMaxTimeFromStart_s = 86400.0;
  ros::NodeHandle nh_;
  LeeController controller_;
  std::deque<std::pair<double, TrajectoryPoint>> pending_;  ///< (due sim time [s], point)
  double t_odometry_s_ = 0.0;                               ///< stamp of the latest odometry
  ros::Publisher motor_pub_;
  ros::Subscriber trajectory_sub_, pose_sub_, odometry_sub_, failure_sub_;
};

}  // namespace rotors_control
