#include "rotors_core/ros/nodelet_host.h"

#include <algorithm>

#include "rotors_core/error.h"

namespace rotors_sim {

NodeletHost::NodeletHost(ros::NodeHandle manager_nh, ros::CallbackQueueInterface* queue) : queue_(queue) {
  services_.push_back(manager_nh.advertiseService("load_nodelet", &NodeletHost::OnLoad, this));
  services_.push_back(manager_nh.advertiseService("unload_nodelet", &NodeletHost::OnUnload, this));
  services_.push_back(manager_nh.advertiseService("list", &NodeletHost::OnList, this));
}

NodeletHost::~NodeletHost() {
  services_.clear();
  // the last loaded goes first (it may use what an earlier one offers)
  for (auto it = load_order_.rbegin(); it != load_order_.rend(); ++it) nodelets_.erase(*it);
}

std::string NodeletHost::Load(const std::string& name, const std::string& type, const nodelet::M_string& remappings,
                              const nodelet::V_string& argv) {
  if (name.empty() || name[0] != '/')
    return "the name '" + name + "' is not a full node name (e.g. /firefly/controller)";
  if (nodelets_.count(name)) return "a nodelet named " + name + " is loaded already";
  boost::shared_ptr<nodelet::Nodelet> instance;
  try {
    if (!class_loader_)
      class_loader_ = std::make_unique<pluginlib::ClassLoader<nodelet::Nodelet>>("nodelet", "nodelet::Nodelet");
    instance = class_loader_->createInstance(type);
  } catch (const pluginlib::PluginlibException& e) {
    return "no nodelet type '" + type + "' (" + std::string(e.what()).substr(0, 200) +
           "); `rospack plugins --attrib=plugin nodelet` lists the packages that export some";
  }
  try {
    instance->init(name, remappings, argv, queue_, queue_);  // one thread: the simulation's
  } catch (const std::exception& e) {
    return e.what();
  }
  nodelets_[name] = instance;
  load_order_.push_back(name);
  return "";
}

bool NodeletHost::Unload(const std::string& name) {
  if (!nodelets_.erase(name)) return false;
  load_order_.erase(std::remove(load_order_.begin(), load_order_.end(), name), load_order_.end());
  return true;
}

std::vector<std::string> NodeletHost::Names() const { return load_order_; }

bool NodeletHost::OnLoad(nodelet::NodeletLoad::Request& req, nodelet::NodeletLoad::Response& res) {
  std::string why;
  nodelet::M_string remappings;
  if (req.remap_source_args.size() != req.remap_target_args.size()) {
    why = "remap_source_args has " + std::to_string(req.remap_source_args.size()) + " entries, remap_target_args " +
          std::to_string(req.remap_target_args.size()) + "; they must pair up";
  } else {
    for (size_t i = 0; i < req.remap_source_args.size(); ++i)
      remappings[req.remap_source_args[i]] = req.remap_target_args[i];
    why = Load(req.name, req.type, remappings, req.my_argv);
  }
  res.success = why.empty();
  if (!res.success) {
    ROS_ERROR_THROTTLE(1.0, "[rotors_sim] load_nodelet %s (%s) refused: %s", Abbreviated(req.name).c_str(),
                       Abbreviated(req.type).c_str(), Abbreviated(why, 300).c_str());
    return true;
  }
  ROS_INFO("[rotors_sim] %s (%s) runs in the simulator's process, on its thread%s", req.name.c_str(), req.type.c_str(),
           req.bond_id.empty() ? "" : " (no bond is kept: it stays loaded until unload_nodelet or the end)");
  return true;
}

bool NodeletHost::OnUnload(nodelet::NodeletUnload::Request& req, nodelet::NodeletUnload::Response& res) {
  res.success = Unload(req.name);
  if (!res.success)
    ROS_ERROR_THROTTLE(1.0, "[rotors_sim] unload_nodelet: no nodelet named '%s' is loaded",
                       Abbreviated(req.name).c_str());
  return true;
}

bool NodeletHost::OnList(nodelet::NodeletList::Request&, nodelet::NodeletList::Response& res) {
  res.nodelets = Names();
  return true;
}

}  // namespace rotors_sim
