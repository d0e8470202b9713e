#include "rotors_gazebo_plugins/autopilot/link_session.h"

#include <algorithm>
#include <chrono>

namespace rotors_gazebo_plugins {

LinkState LinkSession::Next(LinkState state, LinkEvent event, bool steady) {
  if (event == LinkEvent::kReset) return LinkState::kWaiting;
  switch (state) {
    case LinkState::kWaiting:
    case LinkState::kLost:
      if (event == LinkEvent::kConnected) return LinkState::kStarting;
      if (event == LinkEvent::kAnswered) return steady ? LinkState::kLockstep : LinkState::kStarting;
      return state;
    case LinkState::kStarting:
      if (event == LinkEvent::kAnswered && steady) return LinkState::kLockstep;
      if (event == LinkEvent::kClosed) return LinkState::kLost;
      return state;
    case LinkState::kLockstep:
      if (event == LinkEvent::kClosed || event == LinkEvent::kSilent) return LinkState::kLost;
      return state;
  }
  return state;
}

bool LinkSession::On(LinkEvent event) {
  const LinkState before = state_;
  const bool starting_over = before == LinkState::kWaiting || before == LinkState::kLost;
  // answers count from the start of a session (a new connection, or the first answer after none)
  if (event == LinkEvent::kReset ||
      (starting_over && (event == LinkEvent::kConnected || event == LinkEvent::kAnswered)))
    answers_ = 0;
  if (event == LinkEvent::kAnswered) ++answers_;
  if (event == LinkEvent::kLate) ++late_;
  state_ = event == LinkEvent::kReset ? Initial() : Next(state_, event, answers_ >= policy_.answers_before_lockstep);
  return state_ != before;
}

bool LinkSession::Waits(bool armed) const {
  return policy_.lockstep && state_ == LinkState::kLockstep && (armed || !policy_.only_while_armed);
}

AwaitResult LinkSession::AwaitAnswer(const std::function<bool(double)>& read,
                                     const std::function<bool()>& answered) const {
  const double limit_s = policy_.answer_timeout_s;
  const auto start = std::chrono::steady_clock::now();
  while (!answered()) {
    const double waited_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (limit_s > 0.0 && waited_s >= limit_s) return AwaitResult::kTimedOut;
    if (!read(limit_s > 0.0 ? std::min(kReadSlice_s, limit_s - waited_s) : kReadSlice_s)) return AwaitResult::kClosed;
  }
  return AwaitResult::kAnswered;
}

const char* ToString(LinkState state) {
  switch (state) {
    case LinkState::kWaiting: return "waiting";
    case LinkState::kStarting: return "starting";
    case LinkState::kLockstep: return "lockstep";
    case LinkState::kLost: return "lost";
  }
  return "?";
}

const char* ToString(LinkEvent event) {
  switch (event) {
    case LinkEvent::kConnected: return "connected";
    case LinkEvent::kAnswered: return "answered";
    case LinkEvent::kLate: return "late";
    case LinkEvent::kSilent: return "silent";
    case LinkEvent::kClosed: return "closed";
    case LinkEvent::kReset: return "reset";
  }
  return "?";
}

}  // namespace rotors_gazebo_plugins
