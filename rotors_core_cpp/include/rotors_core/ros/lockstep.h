// Lockstep: the simulator and its declared participants (controllers, estimators) take turns.
// A participant answers what the simulator publishes on its input topic (e.g. odometry) with a
// header-stamped message on its answer topic (e.g. command/motor_speed stamped with the odometry
// stamp it answered). Any message type that starts with a std_msgs/Header works; the simulator
// stays ignorant of what the messages mean.
//
// Semantics (mode kHold, the default):
// - A participant is present when its answer topic has a publisher and, if an input topic is
//   declared, the simulator's input topic has a subscriber, and it has been so for settle_s of wall
//   time (so that its other subscriptions, e.g. a latched set point, are connected before the first
//   step: runs do not depend on when it started). A participant that is not present holds the clock: the simulator does
//   not step (one line every few seconds names it).
// - After a step that published a participant's input (or every step, when no input topic is
//   declared), the simulator waits until the participant answered with a stamp >= the step's time
//   (inputs carry the step's time as their stamp, as the odometry and IMU plugins write it).
// - A participant that goes away (its publisher unregisters, or its node no longer answers pings,
//   e.g. after kill -9) pauses the simulation with one line; it resumes when the participant is
//   back. Its first input after (re)connecting is waited for briefly: a participant that cannot
//   answer yet (an estimator before initialisation) is not waited for until its first answer.
// - A participant hosted in this process (a nodelet, see NodeletHost) runs on the simulation thread
//   and answers while the simulator serves callbacks; it is recognised by its answer publication
//   being in this process, and its answer by that publication's sequence number, so that nothing
//   but the plugins and the nodelet touch its messages (they travel as shared pointers, unserialized).
// Mode kLenient keeps the behaviour of earlier versions: only connected participants are waited
// for, and one that stays silent past the timeout is not waited for until it answers again.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include "rotors_core/ros/listened_publisher.h"

namespace rotors_sim {

struct LockstepParticipant {
  std::string answer_topic;  ///< e.g. /firefly/command/motor_speed
  std::string input_topic;   ///< published by the simulator, e.g. /firefly/odometry_sensor1/odometry; may be empty
};

/// Parses "ANSWER[:INPUT],ANSWER[:INPUT],..."; throws std::invalid_argument naming a bad entry.
std::vector<LockstepParticipant> ParseLockstepParticipants(const std::string& spec);

struct LockstepOptions {
  enum class Mode { kHold, kLenient };
  Mode mode = Mode::kHold;
  double settle_s = 0.5;  ///< [s wall] a participant that (re)connected is given to connect its other topics
  double first_answer_timeout_s = 0.5;  ///< [s wall] waiting for the first answer after (re)connecting
  double silence_timeout_s = 2.0;       ///< [s wall] kLenient: mute; kHold: check whether it is still alive
  double report_period_s = 5.0;         ///< [s wall] between "still waiting" lines
};

class Lockstep {
 public:
  Lockstep(ros::NodeHandle nh, const std::vector<LockstepParticipant>& participants, const LockstepOptions& options);
  bool Enabled() const { return !participants_.empty(); }
  /// Re-subscribes the watchers so that they come after every other subscriber of their topics:
  /// roscpp queues a message's callbacks in subscription order, so once the watcher has seen an
  /// answer, the plugins' callbacks for it are queued too. Call after plugins subscribed (spawn).
  void Resubscribe();
  /// kHold: empty when every participant is present, else why the clock is held (and a line is
  /// logged now and then). kLenient: always empty. Call before each step.
  std::string HoldReason(double sim_time_s);
  /// Call right before the step (to tell which inputs the step publishes).
  void BeforeStep();
  /// Serves callbacks until every participant whose input the step published answered `stamp`.
  /// Returns false when a participant went away meanwhile (the caller pauses; HoldReason says why).
  /// Gives up when `stop` returns true (the simulator is shutting down).
  bool WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue, const std::function<bool()>& stop);

 private:
  struct Participant {
    LockstepParticipant topics;
    ros::Subscriber sub;
    ros::Time last_stamp;
    bool present = false;  ///< as of the last check
    ros::WallTime present_since;
    bool ever_present = false;
    bool answered = false;                ///< answered since it (re)connected
    bool warming_up = false;              ///< missed its first input; not waited for until it answers
    bool muted = false;                   ///< kLenient: silent past the timeout
    bool gone = false;                    ///< declared gone by a failed ping; present again once its node answers pings
    uint32_t input_seq = 0;               ///< input publication's sequence number before the step
    bool input_published = false;         ///< the last step published its input
    mutable PublicationCache input_pub;   ///< the simulator's publication of its input
    mutable PublicationCache answer_pub;  ///< its answer's publication in this process (a hosted nodelet)
    bool local = false;                   ///< its answer is published in this process (a hosted nodelet)
    uint32_t answer_seq = 0;              ///< local: the answer publication's sequence number before the step
  };
  /// Notices a participant that is (or no longer is) hosted in this process.
  void RefreshLocal(Participant* p);
  /// local: true (and records the answer) when its answer publication counted a message this step.
  bool LocalAnswered(Participant* p, const ros::Time& stamp);
  /// Sends what the plugins published in the step (roscpp would do it in its poll thread) and
  /// returns the input publication's sequence number (0 when it does not exist yet).
  static uint32_t FlushInput(Participant* p);
  void OnMessage(Participant* p, const topic_tools::ShapeShifter::ConstPtr& msg);
  bool ConnectedNow(const Participant& p) const;
  bool UpdatePresence(Participant* p, double sim_time_s);
  bool Required(const Participant& p) const;
  ros::Subscriber Subscribe(Participant* p);

  ros::NodeHandle nh_;
  std::vector<Participant> participants_;
  LockstepOptions options_;
  ros::WallTime next_report_;
  ros::WallTime next_ping_;
};

/// Reads the header stamp of a serialized message that starts with std_msgs/Header
/// (uint32 seq, uint32 sec, uint32 nsec); false if it is too short.
bool HeaderStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp);

/// True when at least one node that publishes `topic` (per the master) answers an XML-RPC ping.
/// A node killed with SIGKILL stays registered, and its TCP link in this process retries.
bool AnyPublisherAlive(const std::string& topic);

}  // namespace rotors_sim
