// Lockstep: after a step to sim time t, the simulator waits until every registered responder
// topic has delivered a message whose header stamp is >= t (a controller stamps its command with
// the sensor stamp it answered). Any message type that starts with a std_msgs/Header works; the
// simulator stays ignorant of what the messages mean. A responder is waited for as soon as a
// publisher of its topic is connected (so its very first answer is in step too); if it stays
// silent longer than the timeout it is warned about and waited for no more until it speaks again.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

namespace rotors_sim {

class Lockstep {
 public:
  Lockstep(ros::NodeHandle nh, const std::vector<std::string>& topics, double timeout_s);
  bool Enabled() const { return !responders_.empty(); }
  /// Re-subscribes the watchers so that they come after every other subscriber of their topics:
  /// roscpp queues a message's callbacks in subscription order, so once the watcher has seen an
  /// answer, the plugins' callbacks for it are queued too. Call after plugins subscribed (spawn).
  void Resubscribe();
  /// Serves callbacks until all active responders answered `stamp` (or timed out).
  void WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue);

 private:
  struct Responder {
    ros::Subscriber sub;
    ros::Time last_stamp;
    bool muted = false;  ///< timed out; waited for again once it answers
  };
  void OnMessage(const std::string& topic, const topic_tools::ShapeShifter::ConstPtr& msg);
  bool AllAnswered(const ros::Time& stamp) const;
  static bool Awaited(const Responder& r) { return !r.muted && r.sub.getNumPublishers() > 0; }

  ros::Subscriber Subscribe(const std::string& topic);
  ros::NodeHandle nh_;
  std::map<std::string, Responder> responders_;
  double timeout_s_;
};

/// Reads the header stamp of a serialized message that starts with std_msgs/Header
/// (uint32 seq, uint32 sec, uint32 nsec); false if it is too short.
bool HeaderStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp);

}  // namespace rotors_sim
