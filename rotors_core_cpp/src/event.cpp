#include "rotors_core/event.h"

#include "rotors_core/error.h"

namespace rotors_sim {
namespace event {
namespace {
thread_local WorldEvents* g_current = nullptr;

WorldEvents& RequireCurrent(const char* what) {
  if (g_current == nullptr) {
    throw SimError(std::string("event::Events::") + what +
                   " called outside a plugin Load() or world update; use world->Events() instead");
  }
  return *g_current;
}
}  // namespace

void Events::SetCurrent(WorldEvents* events) { g_current = events; }
WorldEvents* Events::Current() { return g_current; }

ConnectionPtr Events::ConnectWorldUpdateBegin(std::function<void(const common::UpdateInfo&)> cb) {
  return RequireCurrent("ConnectWorldUpdateBegin").world_update_begin.Connect(std::move(cb));
}

ConnectionPtr Events::ConnectWorldUpdateEnd(std::function<void()> cb) {
  return RequireCurrent("ConnectWorldUpdateEnd").world_update_end.Connect(std::move(cb));
}

ConnectionPtr Events::ConnectPause(std::function<void(bool)> cb) {
  return RequireCurrent("ConnectPause").pause.Connect(std::move(cb));
}

ConnectionPtr Events::ConnectStop(std::function<void()> cb) {
  return RequireCurrent("ConnectStop").stop.Connect(std::move(cb));
}

}  // namespace event
}  // namespace rotors_sim
