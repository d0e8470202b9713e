// roll_pitch_yawrate_thrust_controller_node: odometry + command/roll_pitch_yawrate_thrust |
// command/attitude_thrust | command/rate_thrust -> command/motor_speed. The most recent command
// of any level is tracked. Parameters: attitude_gain, angular_rate_gain and the vehicle yaml.
#include <mav_msgs/Actuators.h>
#include <mav_msgs/AttitudeThrust.h>
#include <mav_msgs/RateThrust.h>
#include <mav_msgs/RollPitchYawrateThrust.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "rotors_control/attitude_controllers.h"
#include "rotors_control/parameters_ros.h"
#include "ros_conversions.h"

namespace rotors_control {

class AttitudeLevelControllerNode {
 public:
  AttitudeLevelControllerNode(ros::NodeHandle nh, const AttitudeControllerParameters& params) : controller_(params) {
    motor_pub_ = nh.advertise<mav_msgs::Actuators>("command/motor_speed", 1);
    subs_.push_back(nh.subscribe("command/roll_pitch_yawrate_thrust", 1, &AttitudeLevelControllerNode::OnRpyt, this));
    subs_.push_back(nh.subscribe("command/attitude_thrust", 1, &AttitudeLevelControllerNode::OnAttitude, this));
    subs_.push_back(nh.subscribe("command/rate_thrust", 1, &AttitudeLevelControllerNode::OnRate, this));
    subs_.push_back(nh.subscribe("odometry", 1, &AttitudeLevelControllerNode::OnOdometry, this,
                                 ros::TransportHints().tcpNoDelay()));
  }

 private:
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
    motor_pub_.publish(ActuatorsMsg(controller_.RotorSpeeds(StateFromOdometry(*msg)), msg->header.stamp));
  }

  AttitudeLevelController controller_;
  ros::Publisher motor_pub_;
  std::vector<ros::Subscriber> subs_;
};

}  // namespace rotors_control

int main(int argc, char** argv) {
  ros::init(argc, argv, "roll_pitch_yawrate_thrust_controller_node");
  ros::NodeHandle nh, private_nh("~");
  rotors_control::AttitudeControllerParameters params;
  rotors_control::ParameterReader reader(private_nh);
  std::string why = rotors_control::LoadAttitudeGains(reader, &params.attitude);
  if (why.empty()) why = rotors_control::LoadVehicleParameters(reader, &params.vehicle);
  if (!why.empty()) {
    ROS_FATAL("[roll_pitch_yawrate_thrust_controller] %s", why.c_str());
    return 1;
  }
  rotors_control::ReportParameters(reader, "roll_pitch_yawrate_thrust_controller");
  try {
    rotors_control::AttitudeLevelControllerNode node(nh, params);
    ros::spin();
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("[roll_pitch_yawrate_thrust_controller] %s", e.what());
    return 1;
  }
  return 0;
}
