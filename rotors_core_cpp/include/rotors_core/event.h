// Signals with scoped connections, mirroring gazebo::event (Events::ConnectWorldUpdateBegin).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "rotors_core/common.h"

namespace rotors_sim {
namespace event {

/// Keeps a callback connected while it lives (gazebo::event::Connection).
class Connection {
 public:
  explicit Connection(std::function<void()> disconnect) : disconnect_(std::move(disconnect)) {}
  ~Connection() {
    if (disconnect_) disconnect_();
  }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

 private:
  std::function<void()> disconnect_;
};
using ConnectionPtr = std::shared_ptr<Connection>;

template <typename... Args>
class EventT {
 public:
  using Callback = std::function<void(Args...)>;

  ConnectionPtr Connect(Callback cb) {
    const int id = next_id_++;
    (*slots_)[id] = std::move(cb);
    std::weak_ptr<std::map<int, Callback>> weak = slots_;
    return std::make_shared<Connection>([weak, id] {
      if (auto slots = weak.lock()) slots->erase(id);
    });
  }

  /// Calls every connected callback; callbacks may connect or disconnect while it runs.
  void operator()(Args... args) {
    ids_.clear();
    for (const auto& kv : *slots_) ids_.push_back(kv.first);
    for (int id : ids_) {
      auto it = slots_->find(id);
      if (it != slots_->end()) it->second(args...);
    }
  }

  size_t ConnectionCount() const { return slots_->size(); }

 private:
  std::shared_ptr<std::map<int, Callback>> slots_ = std::make_shared<std::map<int, Callback>>();
  std::vector<int> ids_;
  int next_id_ = 0;
};

/// The events of one world.
struct WorldEvents {
  EventT<const common::UpdateInfo&> world_update_begin;  ///< before forces are integrated
  EventT<> world_update_end;                             ///< after the physics step
  EventT<> world_reset;
  EventT<bool> pause;  ///< the simulation was paused (true) or resumed (false); see World::SetPaused
  EventT<> stop;       ///< the simulation ends (World::Fini), before any plugin is unloaded
};

/// Gazebo-style static access. It binds to the world whose plugins are loading or stepping in
/// this thread, so several worlds can live in one process.
class Events {
 public:
  static ConnectionPtr ConnectWorldUpdateBegin(std::function<void(const common::UpdateInfo&)> cb);
  static ConnectionPtr ConnectWorldUpdateEnd(std::function<void()> cb);
  static ConnectionPtr ConnectPause(std::function<void(bool)> cb);
  static ConnectionPtr ConnectStop(std::function<void()> cb);

  /// Set by the World while it loads plugins or steps; nullptr otherwise.
  static void SetCurrent(WorldEvents* events);
  static WorldEvents* Current();
};

/// RAII helper that makes a world's events current in this thread.
class ScopedCurrentEvents {
 public:
  explicit ScopedCurrentEvents(WorldEvents* events) : previous_(Events::Current()) { Events::SetCurrent(events); }
  ~ScopedCurrentEvents() { Events::SetCurrent(previous_); }

 private:
  WorldEvents* previous_;
};

}  // namespace event
}  // namespace rotors_sim
