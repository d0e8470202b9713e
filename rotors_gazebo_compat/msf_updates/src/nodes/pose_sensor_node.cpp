// msf_updates/pose_sensor: see pose_sensor_node.h.
#include "pose_sensor_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "msf_pose_sensor");
  ros::NodeHandle nh, pnh("~");  // outlive a failing constructor: ROS_FATAL needs ROS up
  try {
    msf_updates::PoseSensorNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("[msf] %s", e.what());
    return 1;
  }
  return 0;
}
