// One main for the controller nodes. Without arguments the node runs its controller itself. With
// --in-simulator it asks the simulator (rotors_sim_server, /gazebo) to run the same controller as a
// nodelet in the simulator's process, under this node's name, namespace, parameters and
// remappings, and exits: topics, parameters and behaviour stay the same, the messages stay in
// memory (launch files: in_process:=true).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <ros/ros.h>

namespace rotors_control {

/// Asks /gazebo/load_nodelet to load `nodelet_type` as this node; 0 when it runs there, else 1
/// after one line naming why.
int LoadInSimulator(const std::string& nodelet_type, const std::string& tag);

template <class RosController>
int RunControllerNode(int argc, char** argv, const char* default_name) {
  ros::init(argc, argv, default_name);
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  bool in_simulator = false;
  for (size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--in-simulator") {
      in_simulator = true;
    } else {
      ROS_FATAL("[%s] unknown argument '%s' (the only one is --in-simulator)", RosController::kTag, args[i].c_str());
      return 1;
    }
  }
  if (in_simulator) return LoadInSimulator(RosController::kNodeletType, RosController::kTag);
  ros::NodeHandle nh, private_nh("~");
  try {
    RosController controller(nh, private_nh);
    ros::spin();
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("[%s] %s", RosController::kTag, e.what());
    return 1;
  }
  return 0;
}

}  // namespace rotors_control
