// The simulator as a nodelet manager: nodes that are nodelets (the controllers, the estimator, or a
// user's own) run inside the simulator's process, exchange messages with the plugins in memory
// (roscpp's intra-process links) and run on the simulation thread, between steps. In lockstep a
// step's odometry is therefore answered before the next step without any wall-clock wait, and a
// run is as repeatable as with separate processes.
//
// Offers nodelet's manager API under the simulator's node (/gazebo/load_nodelet, unload_nodelet,
// list), so `rosrun nodelet nodelet load <pkg>/<Type> /gazebo --no-bond` works, as does a node's
// own `--in-simulator` flag (rotors_control's controllers). Bonds are not kept: a nodelet stays
// loaded until unload_nodelet or the end of the simulation.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <nodelet/NodeletList.h>
#include <nodelet/NodeletLoad.h>
#include <nodelet/NodeletUnload.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_loader.hpp>
#include <ros/ros.h>

namespace rotors_sim {

class NodeletHost {
 public:
  /// Services below `manager_nh` (the simulator's private namespace); callbacks of the hosted
  /// nodelets go to `queue`, which the simulation thread serves.
  NodeletHost(ros::NodeHandle manager_nh, ros::CallbackQueueInterface* queue);
  ~NodeletHost();

  /// Loads `type` as `name` (a full node name); "" or why it failed (one line).
  std::string Load(const std::string& name, const std::string& type, const nodelet::M_string& remappings,
                   const nodelet::V_string& argv);
  bool Unload(const std::string& name);
  std::vector<std::string> Names() const;

 private:
  bool OnLoad(nodelet::NodeletLoad::Request& req, nodelet::NodeletLoad::Response& res);
  bool OnUnload(nodelet::NodeletUnload::Request& req, nodelet::NodeletUnload::Response& res);
  bool OnList(nodelet::NodeletList::Request& req, nodelet::NodeletList::Response& res);

  ros::CallbackQueueInterface* queue_;
  // declared before the nodelets: their libraries stay loaded until the last one is destroyed;
  // made at the first load (it asks rospack for every package's plugins: 0.2 s at start-up)
  std::unique_ptr<pluginlib::ClassLoader<nodelet::Nodelet>> class_loader_;
  std::map<std::string, boost::shared_ptr<nodelet::Nodelet>> nodelets_;
  std::vector<std::string> load_order_;
  std::vector<ros::ServiceServer> services_;
};

}  // namespace rotors_sim
