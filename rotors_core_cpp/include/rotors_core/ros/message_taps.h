// In-process readers of what plugins publish, without a ROS master (the Python module): when a
// world's taps are enabled before its models load, every ListenedPublisher of its plugins keeps
// the last message of its topic here (a shared copy, serialized only when somebody reads it), so
// that the same plugin code serves ROS subscribers and Python. The taps live in the world.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <ros/message_traits.h>
#include <ros/serialization.h>

#include "rotors_core/event.h"
#include "rotors_core/physics/world.h"

namespace rotors_sim {

/// The last message of one topic.
struct TappedMessage {
  std::string datatype;  ///< e.g. "sensor_msgs/Imu"
  std::string md5sum;
  uint64_t count = 0;       ///< messages so far
  bool wanted = true;       ///< false: MessageTaps::Restrict left this topic out (its plugin skips it)
  bool pinned = false;      ///< an in-process reader (MessageTaps::Pin) keeps it whatever the taps' state
  bool advertised = false;  ///< a plugin publishes it (MessageTaps::Slot was asked for it)
  bool on_request = false;  ///< kept only when a reader names it (MessageTaps::Restrict) or pins it: images
  boost::shared_ptr<const void> message;
  std::function<std::string(const void*)> serialize;  ///< ROS wire format of `message`

  /// The message in ROS' wire format ("" before the first one).
  std::string Serialized() const { return message ? serialize(message.get()) : std::string(); }

  template <class M>
  void Put(const boost::shared_ptr<const M>& m) {
    if (!serialize) {
      datatype = ros::message_traits::DataType<M>::value();
      md5sum = ros::message_traits::MD5Sum<M>::value();
      serialize = [](const void* p) {
        const M& msg = *static_cast<const M*>(p);
        std::string bytes(ros::serialization::serializationLength(msg), '\0');
        ros::serialization::OStream stream(reinterpret_cast<uint8_t*>(&bytes[0]), static_cast<uint32_t>(bytes.size()));
        ros::serialization::serialize(stream, msg);
        return bytes;
      };
    }
    message = m;
    ++count;
  }

  /// The last message as M, nullptr before the first one or when the topic carries another type.
  template <class M>
  const M* As() const {
    if (!message || datatype != ros::message_traits::DataType<M>::value()) return nullptr;
    return static_cast<const M*>(message.get());
  }
};

class MessageTaps {
 public:
  /// The world's taps (created on first use, disabled). A reset of the world forgets the last
  /// messages (as after load, no reader sees one from before the reset); the counts run on.
  static MessageTaps& Of(physics::World& world) {
    std::shared_ptr<void>& state = world.PluginState("rotors_sim/message_taps");
    if (!state) {
      auto taps = std::make_shared<MessageTaps>();
      MessageTaps* raw = taps.get();
      taps->reset_connection_ = world.Events().world_reset.Connect([raw] { raw->ForgetMessages(); });
      state = taps;
    }
    return *std::static_pointer_cast<MessageTaps>(state);
  }
  /// Drops every topic's last message; the counts (messages since load) stay.
  void ForgetMessages() {
    for (auto& slot : slots_) slot.second.message.reset();
  }
  /// From now on, publishers made for this world keep their messages here.
  void Enable() { enabled_ = true; }
  bool Enabled() const { return enabled_; }
  /// The slot of a resolved topic name, nullptr when the taps are disabled and nobody pinned the
  /// topic. Valid as long as the world. `on_request`: a topic whose messages cost much to build
  /// (a camera's images), kept only once a reader names it in Restrict (or pins it).
  TappedMessage* Slot(const std::string& topic, bool on_request = false) {
    TappedMessage* slot = nullptr;
    if (enabled_) {
      const bool fresh = slots_.find(topic) == slots_.end();
      slot = &slots_[topic];
      if (on_request) {
        slot->on_request = true;
        if (fresh) slot->wanted = false;  // named before the plugin loaded: kept as named
      }
    } else {
      auto it = slots_.find(topic);
      if (it != slots_.end() && it->second.pinned) slot = &it->second;
    }
    if (slot) slot->advertised = true;
    return slot;
  }
  /// An in-process reader in the engine (an autopilot interface plugin reading the vehicle's
  /// sensors) keeps `topic` whether or not the taps are enabled or restricted. The topic's
  /// publisher must be made after this call (its plugin loaded later).
  const TappedMessage* Pin(const std::string& topic) {
    TappedMessage& slot = slots_[topic];
    slot.pinned = slot.wanted = true;
    return &slot;
  }
  const TappedMessage* Find(const std::string& topic) const {
    auto it = slots_.find(topic);
    return it == slots_.end() ? nullptr : &it->second;
  }
  /// Only these topics are kept from now on (the others' plugins need not even build their
  /// messages: a speed-up when a learning loop reads one or two topics); empty: all again, but for
  /// the topics kept only on request.
  void Restrict(const std::vector<std::string>& topics) {
    for (auto& slot : slots_) slot.second.wanted = (topics.empty() && !slot.second.on_request) || slot.second.pinned;
    for (const std::string& topic : topics) slots_[topic].wanted = true;
  }
  /// The topics some plugin publishes (not those only pinned by a reader).
  std::vector<std::string> Topics() const {
    std::vector<std::string> names;
    for (const auto& slot : slots_)
      if (slot.second.advertised) names.push_back(slot.first);
    return names;
  }

 private:
  bool enabled_ = false;
  event::ConnectionPtr reset_connection_;
  std::map<std::string, TappedMessage> slots_;  // std::map: pointers to its values stay valid
};

}  // namespace rotors_sim
