#include "rotors_core/ros/lockstep_state.h"

namespace rotors_sim {

using S = ParticipantState;
using E = ParticipantEvent;

ParticipantState Next(ParticipantState state, ParticipantEvent event, LockstepMode mode) {
  const bool hold = mode == LockstepMode::kHold;
  switch (state) {
    case S::kAbsent:
      if (event == E::kConnected) return hold ? S::kSettling : S::kFirstAnswer;
      return state;
    case S::kSettling:
      if (event == E::kSettled) return S::kFirstAnswer;
      if (event == E::kDisconnected) return S::kAbsent;
      return state;
    case S::kFirstAnswer:
    case S::kAnswering:
    case S::kWarmingUp:
    case S::kMuted:
      if (event == E::kAnswered) return S::kAnswering;
      if (event == E::kDisconnected) return hold ? S::kGone : S::kAbsent;
      if (event == E::kPingFailed && hold) return S::kGone;
      if (event == E::kFirstAnswerLate && hold && state == S::kFirstAnswer) return S::kWarmingUp;
      if (event == E::kSilent && !hold && (state == S::kFirstAnswer || state == S::kAnswering)) return S::kMuted;
      return state;
    case S::kGone:
      if (event == E::kConnected) return hold ? S::kSettling : S::kFirstAnswer;
      return state;
  }
  return state;
}

bool HoldsClock(ParticipantState state, LockstepMode mode) {
  return mode == LockstepMode::kHold && (state == S::kAbsent || state == S::kSettling || state == S::kGone);
}

bool WaitedFor(ParticipantState state) { return state == S::kFirstAnswer || state == S::kAnswering; }

const char* ToString(ParticipantState state) {
  switch (state) {
    case S::kAbsent: return "absent";
    case S::kSettling: return "settling";
    case S::kFirstAnswer: return "first answer due";
    case S::kAnswering: return "answering";
    case S::kWarmingUp: return "warming up";
    case S::kMuted: return "muted";
    case S::kGone: return "gone";
  }
  return "?";
}

const char* ToString(ParticipantEvent event) {
  switch (event) {
    case E::kConnected: return "connected";
    case E::kDisconnected: return "disconnected";
    case E::kSettled: return "settled";
    case E::kAnswered: return "answered";
    case E::kFirstAnswerLate: return "first answer late";
    case E::kSilent: return "silent";
    case E::kPingFailed: return "ping failed";
  }
  return "?";
}

}  // namespace rotors_sim
