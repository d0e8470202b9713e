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
//   being in this process. Its messages reach the plugins and the nodelet as shared pointers;
//   the watcher gets a serialized copy, sent in this thread as soon as it is published.
// - Whether a step published a participant's input is read from the world's PublishCounts, which
//   every ListenedPublisher adds to (all sensor plugins' data topics).
// - Each participant is in one state of the transition table in lockstep_state.h. A step that
//   published an input whose answer was not waited for is counted (UnwaitedSteps()): the run then
//   depends on wall-clock timing, and the simulator says so once, at WARN.
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
#include "rotors_core/ros/lockstep_state.h"
#include "rotors_core/ros/node_pinger.h"
#include "rotors_core/ros/publish_counts.h"

namespace rotors_sim {

struct LockstepParticipant {
  std::string answer_topic;  ///< e.g. /firefly/command/motor_speed
  std::string input_topic;   ///< published by the simulator, e.g. /firefly/odometry_sensor1/odometry; may be empty
};

/// Parses "ANSWER[:INPUT],ANSWER[:INPUT],..."; throws std::invalid_argument naming a bad entry.
std::vector<LockstepParticipant> ParseLockstepParticipants(const std::string& spec);

struct LockstepOptions {
  using Mode = LockstepMode;
  Mode mode = Mode::kHold;
  double settle_s = 0.5;  ///< [s wall] a participant that (re)connected is given to connect its other topics
  double first_answer_timeout_s = 0.5;  ///< [s wall] waiting for the first answer after (re)connecting
  double silence_timeout_s = 2.0;       ///< [s wall] kLenient: mute; kHold: check whether it is still alive
  double report_period_s = 5.0;         ///< [s wall] between "still waiting" lines
  double ping_deadline_s = 1.0;         ///< [s wall] a node that does not answer a ping within it is gone
};

class Lockstep {
 public:
  /// `counts`: the world's publish counts (PublishCounts::Of(world)), read to tell which inputs a step published.
  Lockstep(ros::NodeHandle nh, const std::vector<LockstepParticipant>& participants, const LockstepOptions& options,
           PublishCounts& counts);
  bool Enabled() const { return !participants_.empty(); }
  /// Re-subscribes the watchers so that they come after every other subscriber of their topics:
  /// roscpp queues a message's callbacks in subscription order, so once the watcher has seen an
  /// answer, the plugins' callbacks for it are queued too. Call after plugins subscribed (spawn).
  void Resubscribe();
  /// Observes who is connected (and settled); kHold: empty when no participant holds the clock,
  /// else why it is held (and a line is logged now and then). kLenient: always empty. Call before each step.
  std::string HoldReason(double sim_time_s);
  /// Call right before the step (to tell which inputs the step publishes).
  void BeforeStep();
  /// Serves callbacks until every participant whose input the step published, and that is waited
  /// for, answered `stamp`. Returns false when a participant went away meanwhile (the caller
  /// pauses; HoldReason says why). Gives up when `stop` returns true (the simulator is shutting down).
  bool WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue, const std::function<bool()>& stop);
  /// The sim time went back to `now` (reset_simulation): answers stamped before the rewind no longer
  /// count, and one that arrives later (stamped after `now`) is not taken for an answer of the new run.
  /// A rewind served while WaitForAnswers serves callbacks ends that wait: the step it waited for is
  /// gone, and its answer (stamped after `now`) would never count.
  void Rewind(const ros::Time& now);
  /// Steps after which a published input's answer was not waited for (see lockstep_state.h).
  uint64_t UnwaitedSteps() const { return unwaited_steps_; }
  /// Why the first of them was not waited for (empty while there was none).
  const std::string& FirstUnwaitedReason() const { return first_unwaited_reason_; }

 private:
  struct Participant {
    LockstepParticipant topics;
    ros::Subscriber sub;
    ParticipantState state = ParticipantState::kAbsent;
    ros::Time last_stamp;                   ///< of its latest answer
    ros::WallTime connected_since;          ///< entered kSettling
    ros::WallTime next_ping;                ///< kGone: when to ask again whether its node is back
    const uint64_t* input_count = nullptr;  ///< the world's count of its input topic
    uint64_t input_count_before = 0;        ///< ... before the step
    bool input_published = false;           ///< the last step published its input
    mutable PublicationCache input_pub;     ///< the simulator's publication of its input
    mutable PublicationCache answer_pub;    ///< its answer's publication in this process (a hosted nodelet)
    bool local = false;                     ///< its answer is published in this process (a hosted nodelet)
    std::string answer_md5;                 ///< the answer type last seen, and whether it starts with a
    bool answer_stamped = false;            ///< Header (read once per type, not per message)
  };
  /// Moves p along the transition table, logging what a user must know (went away, back, ...).
  void Apply(Participant* p, ParticipantEvent event, double sim_time_s);
  /// Connection, settling and (kGone) ping answers become events.
  void Observe(Participant* p, double sim_time_s);
  /// Notices a participant that is (or no longer is) hosted in this process.
  void RefreshLocal(Participant* p);
  /// local: sends its queued answers to the watcher now.
  void FlushAnswer(Participant* p);
  /// Sends what the plugins published in the step now, in this thread (roscpp would do it in its poll thread).
  static void FlushInput(Participant* p);
  void OnMessage(Participant* p, const topic_tools::ShapeShifter::ConstPtr& msg);
  void Answered(Participant* p, const ros::Time& stamp);
  bool ConnectedNow(const Participant& p) const;
  bool Required(const Participant& p) const { return p.input_published && WaitedFor(p.state); }
  void CountUnwaited(const ros::Time& stamp);
  ros::Subscriber Subscribe(Participant* p);

  ros::NodeHandle nh_;
  std::vector<Participant> participants_;
  LockstepOptions options_;
  PublishCounts& counts_;
  NodePinger pinger_;
  ros::Time latest_step_;  ///< the stamp of the latest step waited for: no answer can be later
  uint64_t rewinds_ = 0;   ///< Rewind calls so far (a wait that sees it change ends)
  ros::WallTime next_report_;
  uint64_t unwaited_steps_ = 0;
  std::string first_unwaited_reason_;
};

/// True when the first field of a message definition is a std_msgs/Header.
bool StartsWithHeader(const std::string& definition);
/// Reads bytes 4..12 of a serialized message (uint32 seq, uint32 sec, uint32 nsec of a leading
/// std_msgs/Header); false if it is too short. The caller checks the type (StartsWithHeader).
bool SerializedStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp);

}  // namespace rotors_sim
