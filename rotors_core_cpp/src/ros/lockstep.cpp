#include "rotors_core/ros/lockstep.h"

#include <ros/callback_queue.h>

#include <cstring>

namespace rotors_sim {

bool HeaderStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp) {
  std::vector<uint8_t> buffer(msg.size());
  if (buffer.size() < 12) return false;
  ros::serialization::OStream out(buffer.data(), buffer.size());
  msg.write(out);
  uint32_t sec = 0, nsec = 0;  // little-endian, after the uint32 seq
  std::memcpy(&sec, buffer.data() + 4, 4);
  std::memcpy(&nsec, buffer.data() + 8, 4);
  *stamp = ros::Time(sec, nsec);
  return true;
}

Lockstep::Lockstep(ros::NodeHandle nh, const std::vector<std::string>& topics, double timeout_s)
    : nh_(nh), timeout_s_(timeout_s) {
  for (const auto& topic : topics) {
    if (topic.empty()) continue;
    responders_[topic].sub = Subscribe(topic);
    ROS_INFO("[rotors_sim] lockstep: each step waits for an answer on %s", topic.c_str());
  }
}

ros::Subscriber Lockstep::Subscribe(const std::string& topic) {
  return nh_.subscribe<topic_tools::ShapeShifter>(
      topic, 10, [this, topic](const topic_tools::ShapeShifter::ConstPtr& msg) { OnMessage(topic, msg); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
}

void Lockstep::Resubscribe() {
  for (auto& kv : responders_) {
    ros::Subscriber fresh = Subscribe(kv.first);  // appended behind the plugins' subscriptions
    kv.second.sub.shutdown();
    kv.second.sub = fresh;
  }
}

void Lockstep::OnMessage(const std::string& topic, const topic_tools::ShapeShifter::ConstPtr& msg) {
  Responder& r = responders_[topic];
  ros::Time stamp;
  if (!HeaderStamp(*msg, &stamp)) return;
  if (r.muted) ROS_INFO("[rotors_sim] lockstep: %s is answering again", topic.c_str());
  r.muted = false;
  if (stamp > r.last_stamp) r.last_stamp = stamp;
}

bool Lockstep::AllAnswered(const ros::Time& stamp) const {
  for (const auto& kv : responders_)
    if (Awaited(kv.second) && kv.second.last_stamp < stamp) return false;
  return true;
}

void Lockstep::WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s_);
  while (!AllAnswered(stamp) && ros::ok()) {
    queue->callAvailable(ros::WallDuration(0.0005));
    if (ros::WallTime::now() > deadline) {
      for (auto& kv : responders_) {
        if (Awaited(kv.second) && kv.second.last_stamp < stamp) {
          ROS_WARN("[rotors_sim] lockstep: no answer on %s for t = %.3f s within %.1f s; not waiting for it until it "
                   "answers again",
                   kv.first.c_str(), stamp.toSec(), timeout_s_);
          kv.second.muted = true;
        }
      }
    }
  }
  queue->callAvailable();  // deliver the answer to every other subscriber of it too
}

}  // namespace rotors_sim
