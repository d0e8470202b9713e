// omav_pose_controller_node (ours): the omav's 6-DoF pose controller (tilt_rotor_controller.h).
// odometry + command/pose (position AND attitude: roll and pitch are held too) |
// command/trajectory (first point: position, velocity, acceleration, attitude) ->
// command/motor_speed (RotorS' 18 entries: 12 rotor speeds, 6 tilt angles), stamped with the
// odometry it answers. Parameters: resource/omav.yaml and resource/omav_pose_controller.yaml.
#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <mav_msgs/Actuators.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_control/parameter_report_ros.h"
#include "rotors_control/tilt_rotor_controller.h"
#include "ros_conversions.h"

namespace rotors_control {

class OmavPoseControllerRos {
 public:
  static constexpr const char* kTag = "omav_pose_controller";

  OmavPoseControllerRos(ros::NodeHandle nh, const ros::NodeHandle& private_nh)
      : nh_(nh), controller_(LoadParameters(private_nh)) {
    motor_pub_ = nh_.advertise<mav_msgs::Actuators>(mav_msgs::default_topics::COMMAND_ACTUATORS, 1);
    pose_sub_ = nh_.subscribe(mav_msgs::default_topics::COMMAND_POSE, 1, &OmavPoseControllerRos::OnPose, this);
    trajectory_sub_ =
        nh_.subscribe(mav_msgs::default_topics::COMMAND_TRAJECTORY, 1, &OmavPoseControllerRos::OnTrajectory, this);
    odometry_sub_ = nh_.subscribe(mav_msgs::default_topics::ODOMETRY, 1, &OmavPoseControllerRos::OnOdometry, this,
                                  ros::TransportHints().tcpNoDelay());
  }

 private:
  static TiltRotorControllerParameters LoadParameters(const ros::NodeHandle& private_nh) {
    TiltRotorControllerParameters params;
    ParameterReader reader(private_nh);
    const std::string why = LoadTiltRotorParameters(reader, &params);
    if (!why.empty()) throw std::invalid_argument(why);
    ReportParameters(reader, kTag);
    return params;
  }

  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    const std::string why = CheckUnitQuaternion(msg->pose.orientation);
    const auto& p = msg->pose.position;
    if (!why.empty() || !std::isfinite(p.x + p.y + p.z)) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring command/pose: %s", kTag,
                        why.empty() ? "position has NaN or inf" : why.c_str());
      return;
    }
    PoseReference reference;
    reference.position_W = {p.x, p.y, p.z};
    const auto& q = msg->pose.orientation;
    reference.orientation_W_D = Eigen::Quaterniond(q.w, q.x, q.y, q.z);
    controller_.SetReference(reference);
  }

  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    if (msg->points.empty() || msg->points[0].transforms.empty()) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring command/trajectory: it has no point with a transform", kTag);
      return;
    }
    const auto& point = msg->points[0];
    const std::string why = CheckUnitQuaternion(point.transforms[0].rotation);
    const auto& t = point.transforms[0].translation;
    PoseReference reference;
    reference.position_W = {t.x, t.y, t.z};
    if (!point.velocities.empty())
      reference.velocity_W = {point.velocities[0].linear.x, point.velocities[0].linear.y, point.velocities[0].linear.z};
    if (!point.accelerations.empty())
      reference.acceleration_W = {point.accelerations[0].linear.x, point.accelerations[0].linear.y,
                                  point.accelerations[0].linear.z};
    if (!why.empty() || !reference.position_W.allFinite() || !reference.velocity_W.allFinite() ||
        !reference.acceleration_W.allFinite()) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring command/trajectory: %s", kTag,
                        why.empty() ? "NaN or inf in the first point" : why.c_str());
      return;
    }
    const auto& q = point.transforms[0].rotation;
    reference.orientation_W_D = Eigen::Quaterniond(q.w, q.x, q.y, q.z);
    controller_.SetReference(reference);
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const std::string why = CheckOdometry(*msg);
    if (!why.empty()) {
      ROS_WARN_THROTTLE(1.0, "[%s] ignoring odometry: %s (no command sent)", kTag, why.c_str());
      return;
    }
    motor_pub_.publish(boost::make_shared<mav_msgs::Actuators>(
        ActuatorsMsg(controller_.Command(StateFromOdometry(*msg)), msg->header.stamp)));
  }

  ros::NodeHandle nh_;
  TiltRotorController controller_;
  ros::Publisher motor_pub_;
  ros::Subscriber pose_sub_, trajectory_sub_, odometry_sub_;
};

}  // namespace rotors_control

int main(int argc, char** argv) {
  ros::init(argc, argv, "omav_pose_controller_node");
  ros::NodeHandle nh, private_nh("~");
  try {
    rotors_control::OmavPoseControllerRos controller(nh, private_nh);
    ros::spin();
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("[%s] %s", rotors_control::OmavPoseControllerRos::kTag, e.what());
    return 1;
  }
  return 0;
}
