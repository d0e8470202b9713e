// The lockstep state of one participant, as one explicit state and a transition table (ROS-free,
// so that a unit test walks it). Lockstep (lockstep.h) observes the participant (connections,
// answers, pings, wall-time limits), turns what it saw into events and asks Next() for the state.
//
//   state          kHold: clock   waited for   leaves on
//   kAbsent        held           no           kConnected -> kSettling (kLenient: -> kFirstAnswer)
//   kSettling      held           no           kSettled -> kFirstAnswer; kDisconnected -> kAbsent
//   kFirstAnswer   runs           yes          kAnswered -> kAnswering; kFirstAnswerLate -> kWarmingUp (kHold)
//   kAnswering     runs           yes          kDisconnected/kPingFailed -> kGone (kLenient: kSilent -> kMuted)
//   kWarmingUp     runs           no           kAnswered -> kAnswering
//   kMuted         runs           no           kAnswered -> kAnswering (kLenient only)
//   kGone          held           no           kConnected (its node answers pings again) -> kSettling
//
// kLenient (earlier versions' behaviour) never holds the clock: an absent or gone participant is
// simply not waited for. Every step that published a participant's input while it was not waited
// for (or whose answer never came) is an unwaited step: the run then depends on wall-clock timing.
#pragma once

namespace rotors_sim {

enum class LockstepMode { kHold, kLenient };

enum class ParticipantState {
  kAbsent,       ///< not connected (yet)
  kSettling,     ///< connected; its other subscriptions get settle_s of wall time to connect
  kFirstAnswer,  ///< waited for; its first answer since it connected is due
  kAnswering,    ///< waited for after every step that publishes its input
  kWarmingUp,    ///< missed its first answer (e.g. an estimator before initialisation)
  kMuted,        ///< kLenient: silent past the silence timeout
  kGone,         ///< went away after it was present (unregistered, or its node no longer answers pings)
};

enum class ParticipantEvent {
  kConnected,        ///< its answer topic has a publisher (and its input topic a subscriber)
  kDisconnected,     ///< no longer so
  kSettled,          ///< settle_s of wall time passed since it connected
  kAnswered,         ///< an answer arrived
  kFirstAnswerLate,  ///< no first answer within first_answer_timeout_s of wall time
  kSilent,           ///< no answer within silence_timeout_s of wall time
  kPingFailed,       ///< its node does not answer pings (killed with SIGKILL stays registered)
};

/// The transition table; an event a state does not react to leaves it unchanged.
ParticipantState Next(ParticipantState state, ParticipantEvent event, LockstepMode mode);
/// kHold: the simulator does not step while a participant is in this state.
bool HoldsClock(ParticipantState state, LockstepMode mode);
/// The simulator waits for this participant's answer after a step that published its input.
bool WaitedFor(ParticipantState state);
const char* ToString(ParticipantState state);
const char* ToString(ParticipantEvent event);

}  // namespace rotors_sim
