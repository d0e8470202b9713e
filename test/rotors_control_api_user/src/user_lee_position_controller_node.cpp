// A RotorS user's controller node: everything it knows of the controller comes from RotorS'
// rotors_control library API (rotors_control/common.h, parameters_ros.h, lee_position_controller.h)
// and mav_msgs. It reads the gains and the vehicle as RotorS' node does (GetRosParameter,
// GetVehicleParameters), takes command/pose and command/trajectory (the first point) as references,
// and answers each odometry message with command/motor_speed stamped like it.
#include <string>
#include <utility>

#include <geometry_msgs/PoseStamped.h>
#include <mav_msgs/Actuators.h>
#include <mav_msgs/conversions.h>
#include <mav_msgs/default_topics.h>
#include <mav_msgs/eigen_mav_msgs.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_control/common.h"
#include "rotors_control/lee_position_controller.h"
#include "rotors_control/parameters_ros.h"

namespace user {

class LeeNode {
 public:
  LeeNode(ros::NodeHandle nh, const ros::NodeHandle& private_nh) {
    rotors_control::LeePositionControllerParameters& gains = controller_.controller_parameters_;
    const std::pair<const char*, Eigen::Vector3d*> vectors[] = {{"position_gain", &gains.position_gain_},
                                                                {"velocity_gain", &gains.velocity_gain_},
                                                                {"attitude_gain", &gains.attitude_gain_},
                                                                {"angular_rate_gain", &gains.angular_rate_gain_}};
    for (const auto& [name, gain] : vectors) {
      const std::string key(name);
      rotors_control::GetRosParameter(private_nh, key + "/x", gain->x(), &gain->x());
      rotors_control::GetRosParameter(private_nh, key + "/y", gain->y(), &gain->y());
      rotors_control::GetRosParameter(private_nh, key + "/z", gain->z(), &gain->z());
    }
    rotors_control::GetVehicleParameters(private_nh, &controller_.vehicle_parameters_);
    controller_.InitializeParameters();

    pose_sub_ = nh.subscribe(mav_msgs::default_topics::COMMAND_POSE, 1, &LeeNode::OnPose, this);
    trajectory_sub_ =
        nh.subscribe(rotors_control::kDefaultCommandMultiDofJointTrajectoryTopic, 1, &LeeNode::OnTrajectory, this);
    odometry_sub_ = nh.subscribe(rotors_control::kDefaultOdometryTopic, 1, &LeeNode::OnOdometry, this);
    motor_pub_ = nh.advertise<mav_msgs::Actuators>(rotors_control::kDefaultCommandMotorSpeedTopic, 1);
  }

 private:
  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    mav_msgs::EigenTrajectoryPoint reference;
    mav_msgs::eigenTrajectoryPointFromPoseMsg(*msg, &reference);
    controller_.SetTrajectoryPoint(reference);
  }

  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    if (msg->points.empty()) {
      ROS_WARN("command/trajectory without points: ignored");
      return;
    }
    mav_msgs::EigenTrajectoryPoint reference;
    mav_msgs::eigenTrajectoryPointFromMsg(msg->points.front(), &reference);
    controller_.SetTrajectoryPoint(reference);
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    rotors_control::EigenOdometry odometry;
    rotors_control::eigenOdometryFromMsg(msg, &odometry);
    controller_.SetOdometry(odometry);
    Eigen::VectorXd rotor_velocities;
    controller_.CalculateRotorVelocities(&rotor_velocities);
    mav_msgs::ActuatorsPtr command(new mav_msgs::Actuators);
    command->angular_velocities.assign(rotor_velocities.data(), rotor_velocities.data() + rotor_velocities.size());
    command->header.stamp = msg->header.stamp;
    motor_pub_.publish(command);
  }

  rotors_control::LeePositionController controller_;
  ros::Subscriber pose_sub_, trajectory_sub_, odometry_sub_;
  ros::Publisher motor_pub_;
};

}  // namespace user

int main(int argc, char** argv) {
  ros::init(argc, argv, "user_lee_position_controller_node");
  user::LeeNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
