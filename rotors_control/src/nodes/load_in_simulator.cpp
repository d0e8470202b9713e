#include <nodelet/NodeletLoad.h>

#include "controller_main.h"

namespace rotors_control {

int LoadInSimulator(const std::string& nodelet_type, const std::string& tag) {
  const std::string service = "/gazebo/load_nodelet";
  const double wait_s = 60.0;
  if (!ros::service::waitForService(service, ros::Duration(wait_s))) {
    ROS_FATAL("[%s] --in-simulator: %s is not offered after %.0f s (is rotors_sim_server running as /gazebo?)",
              tag.c_str(), service.c_str(), wait_s);
    return 1;
  }
  nodelet::NodeletLoad load;
  load.request.name = ros::this_node::getName();
  load.request.type = nodelet_type;
  for (const auto& remap : ros::names::getRemappings()) {
    load.request.remap_source_args.push_back(remap.first);
    load.request.remap_target_args.push_back(remap.second);
  }
  if (!ros::service::call(service, load)) {
    ROS_FATAL("[%s] --in-simulator: the call to %s failed", tag.c_str(), service.c_str());
    return 1;
  }
  if (!load.response.success) {
    ROS_FATAL("[%s] --in-simulator: the simulator refused to load %s (its log says why)", tag.c_str(),
              nodelet_type.c_str());
    return 1;
  }
  ROS_INFO("[%s] runs in the simulator's process as %s", tag.c_str(), load.request.name.c_str());
  return 0;
}

}  // namespace rotors_control
