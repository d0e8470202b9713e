// Whether the nodes publishing a topic are alive: the master lists publishers until they
// unregister, which a node killed with SIGKILL never does, so each is pinged over XML-RPC.
#include <ros/master.h>
#include <ros/network.h>
#include <ros/this_node.h>
#include <xmlrpcpp/XmlRpcClient.h>
#include <xmlrpcpp/XmlRpcException.h>

#include "rotors_core/ros/node_pinger.h"

namespace rotors_sim {
namespace {

constexpr double kPingTimeoutS = 1.0;  // [s wall] one getPid call

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
  // execute() would wait for ever on a node that accepts the connection and never answers (one
  // stopped in a debugger): the request is sent without blocking and the dispatcher given at most
  // kPingTimeoutS; a node that has not answered by then does not answer
  bool ok = false;
  if (client.executeNonBlock("getPid", args)) {
    client._disp.work(kPingTimeoutS);  // returns when the answer is in, or after the timeout
    ok = client.executeCheckDone(result) && result.valid() && !client.isFault();
  }
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

NodePinger::NodePinger(double deadline_s) : shared_(std::make_shared<Shared>()), deadline_s_(deadline_s) {
  worker_ = std::thread(&NodePinger::Work, shared_);
}

NodePinger::~NodePinger() {
  bool busy = false;
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->stop = true;
    busy = shared_->busy;
  }
  shared_->wake.notify_all();
  // a worker stuck on a node that does not answer must not stop the simulator's shutdown
  if (busy) worker_.detach();
  else worker_.join();
}

void NodePinger::Request(const std::string& topic) {
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    Entry& e = shared_->entries[topic];
    if (e.under_way) return;
    e.under_way = true;
    e.started = false;
    e.overdue_reported = false;
    shared_->queue.push_back(topic);
  }
  shared_->wake.notify_one();
}

NodePinger::Answer NodePinger::Take(const std::string& topic) {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  auto it = shared_->entries.find(topic);
  if (it == shared_->entries.end()) return Answer::kNone;
  Entry& e = it->second;
  if (e.answer != Answer::kNone) {
    const Answer a = e.answer;
    e.answer = Answer::kNone;
    return a;
  }
  if (e.under_way && e.started && !e.overdue_reported &&
      ros::WallTime::now() - e.started_at > ros::WallDuration(deadline_s_)) {
    e.overdue_reported = true;
    return Answer::kDead;
  }
  return Answer::kNone;
}

void NodePinger::Work(const std::shared_ptr<Shared>& shared) {
  std::unique_lock<std::mutex> lock(shared->mutex);
  while (true) {
    shared->wake.wait(lock, [&] { return shared->stop || !shared->queue.empty(); });
    if (shared->stop) return;
    const std::string topic = shared->queue.front();
    shared->queue.pop_front();
    shared->busy = true;
    Entry& started = shared->entries[topic];
    started.started = true;
    started.started_at = ros::WallTime::now();
    lock.unlock();
    const bool alive = AnyPublisherAlive(topic);  // on the network, without the lock
    lock.lock();
    shared->busy = false;
    Entry& e = shared->entries[topic];
    e.under_way = e.started = false;
    // an overdue ping was already reported dead; a late "alive" still counts (the node is back)
    if (!(e.overdue_reported && !alive)) e.answer = alive ? Answer::kAlive : Answer::kDead;
  }
}

}  // namespace rotors_sim
