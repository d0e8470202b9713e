// Whether the nodes publishing a topic are alive: the master lists publishers until they
// unregister, which a node killed with SIGKILL never does, so each is pinged over XML-RPC.
#include <ros/master.h>
#include <ros/network.h>
#include <ros/this_node.h>
#include <xmlrpcpp/XmlRpcClient.h>
#include <xmlrpcpp/XmlRpcException.h>

#include "rotors_core/ros/lockstep.h"

namespace rotors_sim {
namespace {

std::vector<std::string> PublisherNodes(const std::string& topic) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  std::vector<std::string> nodes;
  if (!ros::master::execute("getSystemState", request, response, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeArray)
    return nodes;
  XmlRpc::XmlRpcValue& publishers = payload[0];
  for (int i = 0; i < publishers.size(); ++i) {
    if (static_cast<std::string>(publishers[i][0]) != topic) continue;
    for (int j = 0; j < publishers[i][1].size(); ++j) nodes.push_back(publishers[i][1][j]);
  }
  return nodes;
}

bool NodeAnswersPing(const std::string& node) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  request[1] = node;
  if (!ros::master::execute("lookupNode", request, response, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeString)
    return false;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue args, result;
  args[0] = ros::this_node::getName();
  const bool ok = client.execute("getPid", args, result) && !client.isFault();
  client.close();
  return ok;
}

}  // namespace

bool AnyPublisherAlive(const std::string& topic) {
  try {
    for (const auto& node : PublisherNodes(topic))
      if (NodeAnswersPing(node)) return true;
  } catch (const XmlRpc::XmlRpcException& e) {  // a malformed reply: treat as not answering
    ROS_WARN_THROTTLE(5.0, "[rotors_sim] lockstep: pinging the publishers of %s failed: %s", topic.c_str(),
                      e.getMessage().c_str());
  }
  return false;
}

}  // namespace rotors_sim
