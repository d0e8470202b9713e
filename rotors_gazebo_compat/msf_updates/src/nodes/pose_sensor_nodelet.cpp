// The pose sensor estimator as a nodelet (in the simulator's process with in_process:=true, or in
// any nodelet manager): the node's class under the nodelet's name, parameters and remappings.
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "pose_sensor_node.h"

namespace msf_updates {

class PoseSensorNodelet : public nodelet::Nodelet {
 private:
  /// A bad parameter throws: the manager refuses the load with its line.
  void onInit() override { node_ = std::make_unique<PoseSensorNode>(getNodeHandle(), getPrivateNodeHandle()); }
  std::unique_ptr<PoseSensorNode> node_;
};

}  // namespace msf_updates

PLUGINLIB_EXPORT_CLASS(msf_updates::PoseSensorNodelet, nodelet::Nodelet)
