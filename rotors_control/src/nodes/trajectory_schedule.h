// The set points of command/trajectory and command/pose as RotorS' position controllers take them,
// for every node that flies to set points (Lee's, the learnt policy's). Trajectory point i is due at
// header.stamp + time_from_start_i (sim time; an unstamped trajectory counts from the latest
// odometry) and is released with the first odometry stamped at or after that time, so that in
// lockstep a set point sent ahead of time takes effect at the same step in every run. A point
// already due is applied at once (RotorS). A pose replaces the schedule and applies at once.
#pragma once

#include <cmath>
#include <deque>
#include <functional>
#include <string>
#include <utility>

#include <geometry_msgs/PoseStamped.h>
#include <mav_msgs/conversions.h>
#include <mav_msgs/default_topics.h>
#include <mav_msgs/eigen_mav_msgs.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_control/lee_controller.h"  // TrajectoryPoint
#include "rotors_control/rotors_api_conversions.h"
#include "ros_conversions.h"
#include "warning_throttle.h"

namespace rotors_control {

class TrajectorySchedule {
 public:
  static constexpr double kMaxTimeFromStart_s = 86400.0;

  /// Schedules the trajectory's points; "" or the reason it was ignored (the schedule unchanged).
  /// `t_odometry_s`: the stamp of the latest odometry. A stamp more than a day ahead of it (a
  /// wall-clock stamp?) counts from it, and *ahead_s says how far ahead it was (else 0).
  std::string Set(const trajectory_msgs::MultiDOFJointTrajectory& msg, double t_odometry_s, double* ahead_s) {
    *ahead_s = 0.0;
    if (msg.points.empty()) return "message has no points";
    std::deque<std::pair<double, TrajectoryPoint>> points;
    for (size_t i = 0; i < msg.points.size(); ++i) {
      const auto& pt = msg.points[i];
      const std::string at = "point " + std::to_string(i);
      if (pt.transforms.empty()) return at + " has no transform";
      const std::string why = CheckUnitQuaternion(pt.transforms[0].rotation);
      if (!why.empty()) return at + ": " + why;
      mav_msgs::EigenTrajectoryPoint eigen_point;
      mav_msgs::eigenTrajectoryPointFromMsg(pt, &eigen_point);
      const TrajectoryPoint p = TrajectoryPointFromEigen(eigen_point);
      if (!p.IsFinite()) return at + " has NaN or inf";
      // time_from_start: >= 0 and not decreasing, within a day
      const double t_s = pt.time_from_start.toSec();
      if (!(t_s >= 0.0 && t_s <= kMaxTimeFromStart_s && (points.empty() || t_s >= points.back().first))) {
        char line[160];
        std::snprintf(line, sizeof(line),
                      " has time_from_start %.3f s; it must be in [0, %.0f] s and not below the point before", t_s,
                      kMaxTimeFromStart_s);
        return at + line;
      }
      points.emplace_back(t_s, p);
    }
    double t0_s = msg.header.stamp.isZero() ? t_odometry_s : msg.header.stamp.toSec();
    if (t0_s - t_odometry_s > kMaxTimeFromStart_s) {
      *ahead_s = t0_s - t_odometry_s;
      t0_s = t_odometry_s;
    }
    for (auto& point : points) point.first += t0_s;  // due times
    pending_ = std::move(points);
    return "";
  }

  /// A pose: "" (the schedule cleared, *point the set point) or why it was ignored.
  std::string FromPose(const geometry_msgs::PoseStamped& msg, TrajectoryPoint* point) {
    const std::string why = CheckUnitQuaternion(msg.pose.orientation);
    const auto& p = msg.pose.position;
    if (!why.empty()) return why;
    if (!std::isfinite(p.x + p.y + p.z)) return "position has NaN or inf";
    pending_.clear();
    point->position_W = {p.x, p.y, p.z};
    point->yaw_rad = mav_msgs::yawFromQuaternion(mav_msgs::quaternionFromMsg(msg.pose.orientation));
    return "";
  }

  /// The latest point due at or before t_s, taken off the schedule with every earlier one; false
  /// when none is due.
  bool ReleaseDue(double t_s, TrajectoryPoint* point) {
    bool released = false;
    while (!pending_.empty() && pending_.front().first <= t_s) {
      *point = pending_.front().second;
      pending_.pop_front();
      released = true;
    }
    return released;
  }

 private:
  std::deque<std::pair<double, TrajectoryPoint>> pending_;  ///< (due sim time [s], point)
};

/// command/trajectory and command/pose for a node that flies to set points (Lee's, the learnt
/// policy's): subscribes both below `nh`, keeps their TrajectorySchedule, warns about what it ignores
/// (one line per kind per second, "[tag] ignoring ..."), and hands each set point to `apply` when it
/// is due: a pose at once, a trajectory's points as Release sees the odometry reach them.
class SetPointInput {
 public:
  SetPointInput(ros::NodeHandle nh, std::string tag, std::function<void(const TrajectoryPoint&)> apply)
      : tag_(std::move(tag)), apply_(std::move(apply)) {
    trajectory_sub_ = nh.subscribe(mav_msgs::default_topics::COMMAND_TRAJECTORY, 1, &SetPointInput::OnTrajectory, this);
    pose_sub_ = nh.subscribe(mav_msgs::default_topics::COMMAND_POSE, 1, &SetPointInput::OnPose, this);
  }
  SetPointInput(const SetPointInput&) = delete;  // the subscriptions call back into this object
  SetPointInput& operator=(const SetPointInput&) = delete;

  /// With each odometry: applies the latest point due at or before its stamp.
  void Release(double t_odometry_s) {
    t_odometry_s_ = t_odometry_s;
    TrajectoryPoint point;
    if (schedule_.ReleaseDue(t_odometry_s_, &point)) apply_(point);
  }

 private:
  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    TrajectoryPoint point;
    const std::string why = schedule_.FromPose(*msg, &point);
    if (!why.empty()) {
      if (warnings_.Due(why)) ROS_WARN("[%s] ignoring command/pose: %s", tag_.c_str(), why.c_str());
      return;
    }
    apply_(point);
  }
  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    double ahead_s = 0.0;
    const std::string why = schedule_.Set(*msg, t_odometry_s_, &ahead_s);
    if (!why.empty()) {
      if (warnings_.Due(why)) ROS_WARN("[%s] ignoring trajectory: %s", tag_.c_str(), why.c_str());
      return;
    }
    if (ahead_s > 0.0)
      ROS_WARN_THROTTLE(1.0,
                        "[%s] trajectory stamped %.0f s ahead of the odometry (a wall-clock stamp?); its points "
                        "count from now",
                        tag_.c_str(), ahead_s);
    Release(t_odometry_s_);
  }

  std::string tag_;
  std::function<void(const TrajectoryPoint&)> apply_;
  TrajectorySchedule schedule_;
  WarningThrottle warnings_{1.0};  ///< set points ignored: one line per kind per second
  double t_odometry_s_ = 0.0;      ///< stamp of the latest odometry
  ros::Subscriber trajectory_sub_, pose_sub_;
};

}  // namespace rotors_control
