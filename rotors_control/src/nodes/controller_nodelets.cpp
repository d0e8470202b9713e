// The controllers as nodelets (loaded into the simulator with in_process:=true, or into any
// nodelet manager): the same ROS classes as the nodes, with the nodelet's name, namespace,
// parameters and remappings.
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "attitude_level_controller_ros.h"
#include "hover_policy_ros.h"
#include "lee_position_controller_ros.h"

namespace rotors_control {

template <class RosController>
class ControllerNodelet : public nodelet::Nodelet {
 private:
  /// A missing parameter throws std::invalid_argument: the manager refuses the load with its line.
  void onInit() override { controller_ = std::make_unique<RosController>(getNodeHandle(), getPrivateNodeHandle()); }
  std::unique_ptr<RosController> controller_;
};

using LeePositionControllerNodelet = ControllerNodelet<LeePositionControllerRos>;
using RollPitchYawrateThrustControllerNodelet = ControllerNodelet<AttitudeLevelControllerRos>;
using RlPolicyNodelet = ControllerNodelet<HoverPolicyRos>;

}  // namespace rotors_control

PLUGINLIB_EXPORT_CLASS(rotors_control::LeePositionControllerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(rotors_control::RollPitchYawrateThrustControllerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(rotors_control::RlPolicyNodelet, nodelet::Nodelet)
