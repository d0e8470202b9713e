// Walks the lockstep transition table (lockstep_state.h) through the lives a participant has:
// it arrives and settles, answers, goes away and comes back, warms up, and (kLenient) goes mute.
#include <gtest/gtest.h>

#include "rotors_core/ros/lockstep_state.h"

namespace rotors_sim {
namespace {

using S = ParticipantState;
using E = ParticipantEvent;

struct Walk {
  LockstepMode mode;
  S state = S::kAbsent;
  /// Applies `event` and checks the state it leads to, and whether that state holds the clock and is waited for.
  void Expect(E event, S next, bool holds, bool waited) {
    const S before = state;
    state = Next(state, event, mode);
    SCOPED_TRACE(std::string(ToString(before)) + " --" + ToString(event) + "-> " + ToString(state));
    EXPECT_EQ(state, next);
    EXPECT_EQ(HoldsClock(state, mode), holds);
    EXPECT_EQ(WaitedFor(state), waited);
  }
};

TEST(LockstepState, HoldWaitAnswerGoAwayAndComeBack) {
  Walk w{LockstepMode::kHold};
  EXPECT_TRUE(HoldsClock(w.state, w.mode));             // nobody there: the clock is held
  w.Expect(E::kAnswered, S::kAbsent, true, false);      // a stray answer changes nothing
  w.Expect(E::kConnected, S::kSettling, true, false);   // connected: its other topics get time
  w.Expect(E::kDisconnected, S::kAbsent, true, false);  // left while settling
  w.Expect(E::kConnected, S::kSettling, true, false);
  w.Expect(E::kSettled, S::kFirstAnswer, false, true);  // the clock runs, each step waits for it
  w.Expect(E::kSilent, S::kFirstAnswer, false, true);   // kHold never mutes: it pings instead
  w.Expect(E::kAnswered, S::kAnswering, false, true);
  w.Expect(E::kFirstAnswerLate, S::kAnswering, false, true);  // only a first answer can be late
  w.Expect(E::kPingFailed, S::kGone, true, false);            // killed with SIGKILL: paused
  w.Expect(E::kAnswered, S::kGone, true, false);
  w.Expect(E::kConnected, S::kSettling, true, false);  // back (a restarted node)
  w.Expect(E::kSettled, S::kFirstAnswer, false, true);
  w.Expect(E::kDisconnected, S::kGone, true, false);  // unregistered
}

TEST(LockstepState, HoldWarmUpIsNotWaitedForUntilTheFirstAnswer) {
  Walk w{LockstepMode::kHold};
  w.Expect(E::kConnected, S::kSettling, true, false);
  w.Expect(E::kSettled, S::kFirstAnswer, false, true);
  w.Expect(E::kFirstAnswerLate, S::kWarmingUp, false, false);  // an estimator before initialisation
  w.Expect(E::kSilent, S::kWarmingUp, false, false);
  w.Expect(E::kAnswered, S::kAnswering, false, true);
}

TEST(LockstepState, LenientNeverHoldsAndMutesTheSilent) {
  Walk w{LockstepMode::kLenient};
  EXPECT_FALSE(HoldsClock(w.state, w.mode));
  w.Expect(E::kConnected, S::kFirstAnswer, false, true);  // no settling
  w.Expect(E::kFirstAnswerLate, S::kFirstAnswer, false, true);
  w.Expect(E::kSilent, S::kMuted, false, false);
  w.Expect(E::kAnswered, S::kAnswering, false, true);
  w.Expect(E::kPingFailed, S::kAnswering, false, true);  // kLenient does not ping
  w.Expect(E::kSilent, S::kMuted, false, false);
  w.Expect(E::kDisconnected, S::kAbsent, false, false);
}

TEST(LockstepState, EveryStateHasAName) {
  for (S s : {S::kAbsent, S::kSettling, S::kFirstAnswer, S::kAnswering, S::kWarmingUp, S::kMuted, S::kGone})
    EXPECT_STRNE(ToString(s), "?");
}

}  // namespace
}  // namespace rotors_sim
