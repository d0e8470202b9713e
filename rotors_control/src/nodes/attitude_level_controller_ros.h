// The attitude-level controllers' ROS face, the same as a node (roll_pitch_yawrate_thrust_controller_node)
// and as a nodelet in the simulator's process (in_process:=true): odometry + command/roll_pitch_yawrate_thrust |
// command/attitude_thrust | command/rate_thrust -> command/motor_speed. The most recent command
// of any level is tracked. Parameters: attitude_gain, angular_rate_gain and the vehicle yaml.
#pragma once

#include <stdexcept>

#include <boost/make_shared.hpp>

#include <mav_msgs/Actuators.h>
#include <mav_msgs/AttitudeThrust.h>
#include <mav_msgs/RateThrust.h>
#include <mav_msgs/RollPitchYawrateThrust.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "rotors_control/attitude_controllers.h"
#include "rotors_control/parameter_report_ros.h"
#include "ros_conversions.h"

namespace rotors_control {

class AttitudeLevelControllerRos {
 public:
  static constexpr const char* kTag = "roll_pitch_yawrate_thrust_controller";
  static constexpr const char* kNodeletType = "rotors_control/RollPitchYawrateThrustControllerNodelet";

  /// Reads the parameters from `private_nh` (throws std::invalid_argument naming a missing or bad
  /// one) and connects the topics below `nh`.
  AttitudeLevelControllerRos(ros::NodeHandle nh, ros::NodeHandle private_nh) : controller_(LoadParameters(private_nh)) {
    motor_pub_ = nh.advertise<mav_msgs::Actuators>("command/motor_speed", 1);
    subs_.push_back(nh.subscribe("command/roll_pitch_yawrate_thrust", 1, &AttitudeLevelControllerRos::OnRpyt, this));
    subs_.push_back(nh.subscribe("command/attitude_thrust", 1, &AttitudeLevelControllerRos::OnAttitude, this));
    subs_.push_back(nh.subscribe("command/rate_thrust", 1, &AttitudeLevelControllerRos::OnRate, this));
    subs_.push_back(
        nh.subscribe("odometry", 1, &AttitudeLevelControllerRos::OnOdometry, this, ros::TransportHints().tcpNoDelay()));
  }

 private:
  static AttitudeControllerParameters LoadParameters(const ros::NodeHandle& private_nh) {
    AttitudeControllerParameters params;
    ParameterReader reader(private_nh);
    std::string why = LoadAttitudeGains(reader, &params.attitude);
    if (why.empty()) why = LoadVehicleParameters(reader, &params.vehicle);
    if (!why.empty()) throw std::invalid_argument(why);
    ReportParameters(reader, kTag);
    return params;
  }

  static bool Finite(std::initializer_list<double> values) {
    for (double v : values)
      if (!std::isfinite(v)) return false;
    return true;
  }
  void OnRpyt(const mav_msgs::RollPitchYawrateThrustConstPtr& m) {
    if (!Finite({m->roll, m->pitch, m->yaw_rate, m->thrust.z})) {
      ROS_WARN_THROTTLE(1.0, "[roll_pitch_yawrate_thrust_controller] ignoring a command with NaN or inf");
      return;
    }
    controller_.SetRollPitchYawrateThrust(m->roll, m->pitch, m->yaw_rate, m->thrust.z);
  }
  void OnAttitude(const mav_msgs::AttitudeThrustConstPtr& m) {
    const std::string why = CheckUnitQuaternion(m->attitude);
    if (!why.empty() || !std::isfinite(m->thrust.z)) {
      ROS_WARN_THROTTLE(1.0, "[roll_pitch_yawrate_thrust_controller] ignoring command/attitude_thrust: %s",
                        why.empty() ? "thrust is NaN or inf" : why.c_str());
      return;
    }
    const auto& q = m->attitude;
    controller_.SetAttitudeThrust(Eigen::Quaterniond(q.w, q.x, q.y, q.z), m->thrust.z);
  }
  void OnRate(const mav_msgs::RateThrustConstPtr& m) {
    const auto& w = m->angular_rates;
    if (!Finite({w.x, w.y, w.z, m->thrust.z})) {
      ROS_WARN_THROTTLE(1.0, "[roll_pitch_yawrate_thrust_controller] ignoring command/rate_thrust with NaN or inf");
      return;
    }
    controller_.SetRateThrust({w.x, w.y, w.z}, m->thrust.z);
  }
  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[roll_pitch_yawrate_thrust_controller] ignoring odometry: %s (no command sent)",
                        why.c_str());
      return;
    }
    // a shared pointer: in the simulator's process (in_process:=true) it reaches the plugins unserialized
    motor_pub_.publish(boost::make_shared<mav_msgs::Actuators>(
        ActuatorsMsg(controller_.RotorSpeeds(StateFromOdometry(*msg)), msg->header.stamp)));
  }

  AttitudeLevelController controller_;
  ros::Publisher motor_pub_;
  std::vector<ros::Subscriber> subs_;
};

}  // namespace rotors_control
