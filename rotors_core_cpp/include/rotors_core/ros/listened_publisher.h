// roscpp finds a topic's publication by comparing its name with every topic the process advertises,
// in ros::Publisher::getNumSubscribers() and publish() alike. With 20 vehicles in one simulator
// (several hundred topics) asked several times per step, that search took a third of the
// simulator's time. PublicationCache keeps the publication itself (looked up again only when roscpp
// drops it); ListenedPublisher is a ros::Publisher whose subscriber count costs no search and whose
// publish() does nothing, without a search, when nobody listens (unless it latches).
//
// ListenedPublisher also publishes a shared copy of the message: roscpp hands a shared pointer to
// subscribers in this process at once (the bag plugin, a controller nodelet), while a message
// given by value reaches them only when roscpp's poll thread gets to it, i.e. some steps later when
// the simulation runs fast: what they receive, and when, would depend on thread timing.
//
// Every publish() is counted in the world's PublishCounts, heard or not: lockstep tells from the
// count whether a step published a participant's input. With the world's MessageTaps enabled (the
// Python module), publish() also keeps the message for in-process readers; such a publisher may
// have no ROS publisher at all (ROS not initialised).
#pragma once

#include <string>
#include <utility>

#include <boost/make_shared.hpp>
#include <ros/publication.h>
#include <ros/ros.h>
#include <ros/topic_manager.h>

#include "rotors_core/ros/message_taps.h"
#include "rotors_core/ros/publish_counts.h"

namespace rotors_sim {

class PublicationCache {
 public:
  explicit PublicationCache(std::string topic = "") : topic_(std::move(topic)) {}
  /// This process's publication of the topic (nullptr when it is not advertised here).
  const ros::PublicationPtr& Get() {
    if ((!publication_ || publication_->isDropped()) && !topic_.empty() && ros::isStarted())
      publication_ = ros::TopicManager::instance()->lookupPublication(topic_);
    return publication_;
  }
  const std::string& Topic() const { return topic_; }

 private:
  std::string topic_;
  ros::PublicationPtr publication_;
};

class ListenedPublisher {
 public:
  ListenedPublisher() = default;
  /// `counts`: the world's publish counts, which this publisher's publish() calls add to.
  ListenedPublisher(const ros::Publisher& publisher, PublishCounts& counts)
      : publisher_(publisher),
        cache_(publisher ? publisher.getTopic() : std::string()),
        published_(publisher ? counts.Register(publisher.getTopic()) : nullptr) {}
  /// `publisher` may be empty (no ROS); `topic` is the resolved name; `tap` may be nullptr.
  ListenedPublisher(const ros::Publisher& publisher, const std::string& topic, PublishCounts& counts,
                    TappedMessage* tap)
      : publisher_(publisher),
        cache_(publisher ? topic : std::string()),
        published_(counts.Register(topic)),
        tap_(tap),
        topic_(topic) {}

  /// ROS subscribers, plus one for an in-process tap.
  uint32_t getNumSubscribers() {
    const ros::PublicationPtr& p = cache_.Get();
    return (p ? p->getNumSubscribers() : 0) + (Tapped() ? 1 : 0);
  }
  template <class M>
  void publish(const M& message) {
    if (published_) ++*published_;
    const bool listened = Listened();
    if (!listened && !Tapped()) return;
    auto shared = boost::make_shared<M>(message);
    if (Tapped()) tap_->Put(boost::shared_ptr<const M>(shared));
    if (listened) publisher_.publish(shared);
  }
  template <class M>
  void publish(const boost::shared_ptr<M>& message) {
    if (published_) ++*published_;
    if (Tapped()) tap_->Put(boost::shared_ptr<const M>(message));
    if (Listened()) publisher_.publish(message);
  }
  std::string getTopic() const { return publisher_ ? publisher_.getTopic() : topic_; }

  /// A ROS publisher or a tap: publish() reaches somebody (now or once they subscribe).
  explicit operator bool() const { return static_cast<bool>(publisher_) || tap_ != nullptr; }

 private:
  bool Tapped() const { return tap_ != nullptr && tap_->wanted; }
  /// True when publish() must go through roscpp.
  bool Listened() {
    if (!publisher_) return false;
    const ros::PublicationPtr& p = cache_.Get();
    return publisher_.isLatched() || (p && p->getNumSubscribers() > 0);
  }

  ros::Publisher publisher_;
  PublicationCache cache_;
  uint64_t* published_ = nullptr;  ///< this topic's count in the world's PublishCounts
  TappedMessage* tap_ = nullptr;   ///< the world's MessageTaps slot of this topic (taps enabled)
  std::string topic_;
};

}  // namespace rotors_sim
