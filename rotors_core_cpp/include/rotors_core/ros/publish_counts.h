// How many messages the plugins of a world published, per topic: ListenedPublisher counts every
// publish() (whether or not anybody listens), and lockstep reads the count before and after a step
// to tell whether the step published a participant's input. The counts live in the world.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "rotors_core/physics/world.h"

namespace rotors_sim {

class PublishCounts {
 public:
  /// The world's counts (created on first use).
  static PublishCounts& Of(physics::World& world) {
    std::shared_ptr<void>& state = world.PluginState("rotors_sim/publish_counts");
    if (!state) state = std::make_shared<PublishCounts>();
    return *std::static_pointer_cast<PublishCounts>(state);
  }
  /// The counter of a resolved topic name; the pointer stays valid as long as the world.
  uint64_t* Counter(const std::string& topic) { return &counts_[topic]; }
  /// True when some publisher counts this topic (it was advertised through ListenedPublisher).
  bool Counted(const std::string& topic) const { return counted_.count(topic) > 0; }
  uint64_t* Register(const std::string& topic) {
    counted_[topic] = true;
    return Counter(topic);
  }

 private:
  std::map<std::string, uint64_t> counts_;  // std::map: pointers to its values stay valid
  std::map<std::string, bool> counted_;
};

}  // namespace rotors_sim
