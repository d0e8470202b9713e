// The exchange with one autopilot (PX4, ArduPilot or Betaflight) as one explicit state and one
// transition table, engine-, ROS- and socket-free, so that a unit test walks it. Each interface
// plugin observes its link (a connection, answers, wall-time limits), turns what it saw into events
// and asks Next() for the state; Waits() says whether a step waits for the autopilot's answer.
//
//   state        a step waits for the answer   leaves on
//   kWaiting     no                            kConnected -> kStarting; kAnswered -> kStarting (or kLockstep)
//   kStarting    no                            kAnswered -> kLockstep once `answers_before_lockstep` came
//   kLockstep    yes (the policy's limit)      kClosed / kSilent -> kLost; kLate stays (the step goes on)
//   kLost        no                            kConnected / kAnswered -> kStarting; motors disarmed
//   any          -                             kReset -> kWaiting (the world went back)
//
// answers_before_lockstep 0 (a firmware in true lockstep, which answers every state it gets from the
// first on): the session starts in kLockstep and a reset returns there.
//
// kLockstep waits as each autopilot's own simulator plugin does: PX4's Gazebo plugin at most 10 ms
// and only while armed (WaitPolicy::answer_timeout_s, only_while_armed), ArduPilot's as long as it
// takes (answer_timeout_s 0: no limit), Betaflight's at most answer_timeout_s. AwaitAnswer is that
// wait, the one deadline loop of the three links: what a wait that ran out means (a late answer, a
// lost link) is each protocol's to say.
#pragma once

#include <cstdint>
#include <functional>

namespace rotors_gazebo_plugins {

enum class LinkState { kWaiting, kStarting, kLockstep, kLost };

enum class LinkEvent {
  kConnected,  ///< a connection was accepted (TCP), or the first datagram came
  kAnswered,   ///< an answer (outputs) arrived
  kLate,       ///< no answer within the wait limit: the step goes on with the last outputs
  kSilent,     ///< no answer for the link timeout: the link counts as lost
  kClosed,     ///< the autopilot closed the connection (or the serial device went away)
  kReset,      ///< the world went back (reset_world / reset_simulation)
};

/// How a wait for an answer ended.
enum class AwaitResult {
  kAnswered,  ///< the answer came
  kTimedOut,  ///< answer_timeout_s of wall time passed without it
  kClosed,    ///< the link closed while waiting
};

struct WaitPolicy {
  bool lockstep = true;                  ///< enable_lockstep
  double answer_timeout_s = 0.0;         ///< wall time a step waits for its answer; 0: no limit
  bool only_while_armed = false;         ///< PX4: no waiting while the autopilot is disarmed
  uint64_t answers_before_lockstep = 1;  ///< answers in kStarting before the steps wait (0: from the start)
};

class LinkSession {
 public:
  explicit LinkSession(const WaitPolicy& policy) : policy_(policy), state_(Initial()) {}
  /// The transition table; an event a state does not react to leaves it unchanged.
  static LinkState Next(LinkState state, LinkEvent event, bool steady);
  /// Feeds an event; true when the state changed.
  bool On(LinkEvent event);
  /// Whether this step waits for the autopilot's answer (`armed`: the autopilot's last word).
  bool Waits(bool armed) const;
  /// Waits for this step's answer: calls read(timeout_s) (takes what arrives within timeout_s of wall
  /// time; false when the link closed) until answered() is true or the policy's answer_timeout_s has
  /// passed (0: no limit), each read at most kReadSlice_s long.
  AwaitResult AwaitAnswer(const std::function<bool(double)>& read, const std::function<bool()>& answered) const;
  static constexpr double kReadSlice_s = 0.05;
  LinkState State() const { return state_; }
  const WaitPolicy& Policy() const { return policy_; }
  uint64_t AnswersSinceStart() const { return answers_; }
  uint64_t LateAnswers() const { return late_; }

 private:
  LinkState Initial() const {
    return policy_.answers_before_lockstep == 0 ? LinkState::kLockstep : LinkState::kWaiting;
  }
  WaitPolicy policy_;
  LinkState state_;
  uint64_t answers_ = 0, late_ = 0;
};

const char* ToString(LinkState state);
const char* ToString(LinkEvent event);

}  // namespace rotors_gazebo_plugins
