// msf_updates/pose_sensor: the roscpp shell around PoseEkf with ethzasl_msf's interface
// (reference section 8): topics msf_core/imu_state_input, msf_updates/{pose_with_covariance,pose,
// transform,odometry}_input -> msf_core/{odometry,pose,pose_after_update,state_out,cov_core} and
// TF <msf_output_frame> -> <tf_target_frame>; services ~pose_sensor/initialize_msf_scale and
// ~pose_sensor/initialize_msf_height; parameters under ~core/ and ~pose_sensor/ with MSF's names.
// The same class runs as the node (pose_sensor_node.cpp) and as a nodelet in the simulator's
// process (pose_sensor_nodelet.cpp; in_process:=true).
#pragma once

#include <memory>

#include <ros/ros.h>

namespace msf_updates {

/// Constructed from (nh, private nh); throws std::invalid_argument naming a parameter it refuses.
/// Subscribes, advertises and serves until destroyed (pose_sensor_ros.cpp).
class PoseSensorNode {
 public:
  PoseSensorNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~PoseSensorNode();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace msf_updates
