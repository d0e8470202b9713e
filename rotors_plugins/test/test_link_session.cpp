// LinkSession's table walked as each autopilot's own simulator plugin behaves (link_session.h).
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "rotors_gazebo_plugins/autopilot/link_session.h"

namespace rotors_gazebo_plugins {
namespace {

TEST(LinkSession, Px4LockstepWaitsOnlyWhileArmedAndLateAnswersKeepTheLink) {
  LinkSession px4({/*lockstep=*/true, /*answer_timeout_s=*/0.01, /*only_while_armed=*/true, 1});
  EXPECT_EQ(px4.State(), LinkState::kWaiting);
  EXPECT_FALSE(px4.Waits(true));
  px4.On(LinkEvent::kConnected);  // PX4's TCP client
  EXPECT_EQ(px4.State(), LinkState::kStarting);
  EXPECT_FALSE(px4.Waits(true));
  px4.On(LinkEvent::kAnswered);  // the first HIL_ACTUATOR_CONTROLS
  EXPECT_EQ(px4.State(), LinkState::kLockstep);
  EXPECT_TRUE(px4.Waits(true));
  EXPECT_FALSE(px4.Waits(false));  // disarmed: PX4's Gazebo plugin does not wait
  for (int i = 0; i < 50; ++i) px4.On(LinkEvent::kLate);
  EXPECT_EQ(px4.State(), LinkState::kLockstep);  // silence never ends the session
  EXPECT_EQ(px4.LateAnswers(), 50u);
  px4.On(LinkEvent::kClosed);  // PX4 went away
  EXPECT_EQ(px4.State(), LinkState::kLost);
  EXPECT_FALSE(px4.Waits(true));
  px4.On(LinkEvent::kConnected);  // a restarted PX4
  px4.On(LinkEvent::kAnswered);
  EXPECT_EQ(px4.State(), LinkState::kLockstep);
}

TEST(LinkSession, BetaflightWaitsOnceItAnswersSteadilyAndIsLostWhenSilent) {
  LinkSession bf({true, 0.02, false, /*answers_before_lockstep=*/100});
  for (int i = 0; i < 99; ++i) bf.On(LinkEvent::kAnswered);
  EXPECT_EQ(bf.State(), LinkState::kStarting);
  EXPECT_FALSE(bf.Waits(true));
  bf.On(LinkEvent::kAnswered);
  EXPECT_EQ(bf.State(), LinkState::kLockstep);
  EXPECT_TRUE(bf.Waits(false));
  bf.On(LinkEvent::kSilent);
  EXPECT_EQ(bf.State(), LinkState::kLost);
  bf.On(LinkEvent::kAnswered);  // it answers again: steady after 100 more
  EXPECT_EQ(bf.State(), LinkState::kStarting);
  EXPECT_EQ(bf.AnswersSinceStart(), 1u);
}

TEST(LinkSession, ResetStartsOverAndLockstepOffNeverWaits) {
  LinkSession ap({true, 0.0, false, 1});
  ap.On(LinkEvent::kAnswered);  // ArduPilot's first servo frame
  EXPECT_EQ(ap.State(), LinkState::kLockstep);
  EXPECT_TRUE(ap.Waits(false));
  ap.On(LinkEvent::kReset);
  EXPECT_EQ(ap.State(), LinkState::kWaiting);
  EXPECT_EQ(ap.AnswersSinceStart(), 0u);
  LinkSession free_running({false, 0.0, false, 1});
  free_running.On(LinkEvent::kAnswered);
  EXPECT_EQ(free_running.State(), LinkState::kLockstep);
  EXPECT_FALSE(free_running.Waits(true));
  EXPECT_STREQ(ToString(LinkState::kLost), "lost");
  EXPECT_STREQ(ToString(LinkEvent::kLate), "late");
}

TEST(LinkSession, ATrueLockstepFirmwareIsWaitedForFromTheFirstState) {
  LinkSession bf({true, 2.0, false, /*answers_before_lockstep=*/0});
  EXPECT_EQ(bf.State(), LinkState::kLockstep);
  EXPECT_TRUE(bf.Waits(false));
  bf.On(LinkEvent::kSilent);  // no answer within the limit
  EXPECT_EQ(bf.State(), LinkState::kLost);
  bf.On(LinkEvent::kAnswered);
  EXPECT_EQ(bf.State(), LinkState::kLockstep);
  bf.On(LinkEvent::kSilent);
  bf.On(LinkEvent::kReset);
  EXPECT_EQ(bf.State(), LinkState::kLockstep);
}

// The one deadline loop: it reads until the answer is in, and never longer than the policy's limit.
TEST(LinkSession, AwaitAnswerReadsUntilTheAnswerAndStopsAtTheLimit) {
  const LinkSession px4({true, /*answer_timeout_s=*/0.03, true, 1});
  std::vector<double> reads_s;
  int answered_on = 3;
  auto read = [&](double timeout_s) {
    reads_s.push_back(timeout_s);
    return true;
  };
  auto answered = [&] { return static_cast<int>(reads_s.size()) >= answered_on; };
  EXPECT_EQ(px4.AwaitAnswer(read, answered), AwaitResult::kAnswered);
  EXPECT_EQ(reads_s.size(), 3u);
  for (double t : reads_s) EXPECT_TRUE(t > 0.0 && t <= 0.03) << t;  // never past the limit

  reads_s.clear();
  answered_on = 1 << 30;  // the answer never comes
  auto slow_read = [&](double timeout_s) {
    reads_s.push_back(timeout_s);
    std::this_thread::sleep_for(std::chrono::duration<double>(timeout_s));  // nothing arrives
    return true;
  };
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(px4.AwaitAnswer(slow_read, answered), AwaitResult::kTimedOut);
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.03);
  for (double t : reads_s) EXPECT_LE(t, 0.03);

  // the link closed while waiting
  EXPECT_EQ(px4.AwaitAnswer([](double) { return false; }, [] { return false; }), AwaitResult::kClosed);
}

TEST(LinkSession, AwaitAnswerWithoutALimitReadsInSlices) {
  const LinkSession ardupilot({true, /*answer_timeout_s=*/0.0, false, 1});  // as long as ArduPilot takes
  std::vector<double> reads_s;
  EXPECT_EQ(ardupilot.AwaitAnswer(
                [&](double timeout_s) {
                  reads_s.push_back(timeout_s);
                  return true;
                },
                [&] { return reads_s.size() == 5; }),
            AwaitResult::kAnswered);
  ASSERT_EQ(reads_s.size(), 5u);
  for (double t : reads_s) EXPECT_EQ(t, LinkSession::kReadSlice_s);
}

}  // namespace
}  // namespace rotors_gazebo_plugins
