// The Lee position controller's ROS face, the same as a node (lee_position_controller_node) and as a
// nodelet in the simulator's process (in_process:=true): odometry + command/trajectory |
// command/pose -> command/motor_speed.
// Ours: motor_failure (rotors_comm/MotorFailure) re-allocates without (or with a derated) rotor.
// Parameters from the private namespace (lee_controller_<mav>.yaml and <mav>.yaml). Set points as
// SetPointInput releases them (trajectory_schedule.h). The motor command is stamped with the
// odometry stamp it answers (lockstep keys on this).
#pragma once

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
#include "trajectory_schedule.h"

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

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[lee_position_controller] ignoring odometry: %s (no command sent)", why.c_str());
      return;
    }
    set_points_.Release(msg->header.stamp.toSec());
    // a shared pointer: in the simulator's process (in_process:=true) it reaches the plugins unserialized
    motor_pub_.publish(boost::make_shared<mav_msgs::Actuators>(
        ActuatorsMsg(controller_.RotorSpeeds(StateFromOdometry(*msg)), msg->header.stamp)));
  }

  ros::NodeHandle nh_;
  LeeController controller_;
  SetPointInput set_points_{nh_, kTag, [this](const TrajectoryPoint& p) { controller_.SetTrajectoryPoint(p); }};
  ros::Publisher motor_pub_;
  ros::Subscriber odometry_sub_, failure_sub_;
};

}  // namespace rotors_control
