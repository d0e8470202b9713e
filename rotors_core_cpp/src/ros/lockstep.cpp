#include "rotors_core/ros/lockstep.h"

#include <ros/callback_queue.h>
#include <ros/publication.h>
#include <ros/topic_manager.h>

#include <xmlrpcpp/XmlRpcValue.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace rotors_sim {

/// True when the first field of a message definition is a std_msgs/Header (constants, which are
/// not serialized, and comments skipped): only then are bytes 4..12 a stamp.
bool StartsWithHeader(const std::string& definition) {
  std::istringstream lines(definition);
  std::string line;
  while (std::getline(lines, line)) {
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#' || line.find('=') != std::string::npos) continue;
    if (line.rfind("MSG:", first) == first || line.rfind("===", first) == first) return false;
    std::istringstream words(line.substr(first));
    std::string type;
    words >> type;
    return type == "Header" || type == "std_msgs/Header";
  }
  return false;
}

bool SerializedStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp) {
  std::vector<uint8_t> buffer(msg.size());
  if (buffer.size() < 12) return false;
  ros::serialization::OStream out(buffer.data(), buffer.size());
  msg.write(out);
  uint32_t sec = 0, nsec = 0;  // little-endian, after the uint32 seq
  std::memcpy(&sec, buffer.data() + 4, 4);
  std::memcpy(&nsec, buffer.data() + 8, 4);
  *stamp = ros::Time(sec, nsec);
  return true;
}

std::vector<LockstepParticipant> ParseLockstepParticipants(const std::string& spec) {
  std::vector<LockstepParticipant> out;
  std::stringstream entries(spec);
  for (std::string entry; std::getline(entries, entry, ',');) {
    if (entry.empty()) continue;
    LockstepParticipant p;
    const size_t colon = entry.find(':');
    p.answer_topic = entry.substr(0, colon);
    if (colon != std::string::npos) p.input_topic = entry.substr(colon + 1);
    if (p.answer_topic.empty() || (colon != std::string::npos && p.input_topic.empty()) ||
        p.input_topic.find(':') != std::string::npos)
      throw std::invalid_argument("lockstep participant '" + entry +
                                  "' is not ANSWER_TOPIC or ANSWER_TOPIC:INPUT_TOPIC (e.g. "
                                  "/firefly/command/motor_speed:/firefly/odometry_sensor1/odometry)");
    p.answer_topic = ros::names::resolve(p.answer_topic);
    if (!p.input_topic.empty()) p.input_topic = ros::names::resolve(p.input_topic);
    out.push_back(p);
  }
  return out;
}

Lockstep::Lockstep(ros::NodeHandle nh, const std::vector<LockstepParticipant>& participants,
                   const LockstepOptions& options, PublishCounts& counts)
    : nh_(nh), options_(options), counts_(counts), pinger_(options.ping_deadline_s) {
  participants_.resize(participants.size());  // fixed from here on: callbacks hold pointers
  for (size_t i = 0; i < participants.size(); ++i) {
    Participant& p = participants_[i];
    p.topics = participants[i];
    p.input_pub = PublicationCache(p.topics.input_topic);
    p.answer_pub = PublicationCache(p.topics.answer_topic);
    if (!p.topics.input_topic.empty()) p.input_count = counts_.Counter(p.topics.input_topic);
    p.sub = Subscribe(&p);
    ROS_INFO("[rotors_sim] lockstep (%s): each step waits for an answer on %s%s%s",
             options_.mode == LockstepMode::kHold ? "hold" : "lenient", p.topics.answer_topic.c_str(),
             p.topics.input_topic.empty() ? "" : " to ", p.topics.input_topic.c_str());
  }
}

ros::Subscriber Lockstep::Subscribe(Participant* p) {
  return nh_.subscribe<topic_tools::ShapeShifter>(
      p->topics.answer_topic, 10, [this, p](const topic_tools::ShapeShifter::ConstPtr& msg) { OnMessage(p, msg); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
}

void Lockstep::Resubscribe() {
  for (auto& p : participants_) {
    ros::Subscriber fresh = Subscribe(&p);  // appended behind the plugins' subscriptions
    p.sub.shutdown();
    p.sub = fresh;
  }
}

void Lockstep::Answered(Participant* p, const ros::Time& stamp) {
  // an answer stamped after the latest step answers a step from before a rewind
  if (stamp > p->last_stamp && stamp <= latest_step_) p->last_stamp = stamp;
  Apply(p, ParticipantEvent::kAnswered, stamp.toSec());
}

void Lockstep::OnMessage(Participant* p, const topic_tools::ShapeShifter::ConstPtr& msg) {
  if (msg->getMD5Sum() != p->answer_md5) {  // the definition is parsed once per answer type
    p->answer_md5 = msg->getMD5Sum();
    p->answer_stamped = StartsWithHeader(msg->getMessageDefinition());
  }
  ros::Time stamp;
  if (p->answer_stamped && SerializedStamp(*msg, &stamp)) {
    Answered(p, stamp);
    return;
  }
  ROS_ERROR_THROTTLE(5.0,
                     "[rotors_sim] lockstep: %s carries %s, which has no Header: its messages cannot answer a step "
                     "(lockstep needs a stamped type, e.g. mav_msgs/Actuators)",
                     p->topics.answer_topic.c_str(), msg->getDataType().c_str());
}

void Lockstep::Apply(Participant* p, ParticipantEvent event, double sim_time_s) {
  using S = ParticipantState;
  const S before = p->state;
  p->state = Next(before, event, options_.mode);
  if (p->state == before) return;
  const char* topic = p->topics.answer_topic.c_str();
  if (p->state == S::kSettling) p->connected_since = ros::WallTime::now();
  if (before == S::kGone) ROS_INFO("[rotors_sim] lockstep: %s is back; resuming at t = %.3f s", topic, sim_time_s);
  else if (p->state == S::kGone)
    ROS_WARN("[rotors_sim] lockstep: %s went away at t = %.3f s (%s); the simulation is paused until it is back", topic,
             sim_time_s, ToString(event));
  else if (p->state == S::kWarmingUp)
    ROS_WARN(
        "[rotors_sim] lockstep: no first answer on %s to t = %.3f s within %.1f s of wall time; not waiting for it "
        "until it answers (e.g. an estimator not yet initialised): from here the run is not repeatable",
        topic, sim_time_s, options_.first_answer_timeout_s);
  else if (p->state == S::kMuted)
    ROS_WARN(
        "[rotors_sim] lockstep: no answer on %s for t = %.3f s within %.1f s; not waiting for it until it "
        "answers again",
        topic, sim_time_s, options_.silence_timeout_s);
  else if (before == S::kMuted) ROS_INFO("[rotors_sim] lockstep: %s is answering again", topic);
  if (p->state == S::kFirstAnswer && p->input_count && !counts_.Counted(p->topics.input_topic))
    ROS_WARN(
        "[rotors_sim] lockstep: no plugin counts its publications of %s (only sensor plugins' data topics "
        "are counted); %s is never waited for",
        p->topics.input_topic.c_str(), topic);
}

/// Subscribers of one of this node's topics in other nodes (the plugins' own subscriptions, e.g.
/// the bag plugin's, do not make a participant present).
size_t RemoteSubscribers(const ros::PublicationPtr& pub) {
  if (!pub) return 0;
  XmlRpc::XmlRpcValue links;
  links.setSize(0);  // getInfo appends one [id, destination node, ...] per link
  pub->getInfo(links);
  size_t n = 0;
  for (int i = 0; i < links.size(); ++i)
    if (static_cast<std::string>(links[i][1]) != ros::this_node::getName()) ++n;
  return n;
}

void Lockstep::RefreshLocal(Participant* p) {
  // a hosted participant is set up within one callback on this thread: once its answer publication
  // exists here, its input subscription does too
  p->local = static_cast<bool>(p->answer_pub.Get());
}

void Lockstep::FlushAnswer(Participant* p) {
  // roscpp serializes a hosted participant's answer for the watcher (a ShapeShifter) and queues it;
  // sending it now, in this thread, delivers it to the watcher with the next callAvailable
  if (const ros::PublicationPtr& pub = p->answer_pub.Get()) pub->processPublishQueue();
}

bool Lockstep::ConnectedNow(const Participant& p) const {
  if (p.local) return p.answer_pub.Get() != nullptr;
  if (p.sub.getNumPublishers() == 0) return false;
  if (p.topics.input_topic.empty()) return true;
  // once present, a participant leaves through its answer topic; the input is checked on arrival
  const bool present = p.state != ParticipantState::kAbsent && p.state != ParticipantState::kGone;
  return present || RemoteSubscribers(p.input_pub.Get()) > 0;
}

void Lockstep::Observe(Participant* p, double sim_time_s) {
  using S = ParticipantState;
  RefreshLocal(p);
  const bool connected = ConnectedNow(*p);
  if (p->state == S::kGone) {
    // registered again, or still registered: back once its node answers pings (a restarted node)
    if (!connected) return;
    const NodePinger::Answer answer = pinger_.Take(p->topics.answer_topic);
    if (answer == NodePinger::Answer::kAlive) {
      Apply(p, ParticipantEvent::kConnected, sim_time_s);
    } else if (ros::WallTime::now() >= p->next_ping) {
      pinger_.Request(p->topics.answer_topic);
      p->next_ping = ros::WallTime::now() + ros::WallDuration(0.5);
    }
    return;
  }
  if (connected && p->state == S::kAbsent) Apply(p, ParticipantEvent::kConnected, sim_time_s);
  if (!connected && p->state != S::kAbsent) Apply(p, ParticipantEvent::kDisconnected, sim_time_s);
  if (p->state == S::kSettling && ros::WallTime::now() - p->connected_since >= ros::WallDuration(options_.settle_s))
    Apply(p, ParticipantEvent::kSettled, sim_time_s);
}

std::string Lockstep::HoldReason(double sim_time_s) {
  std::string reason;
  for (auto& p : participants_) {
    Observe(&p, sim_time_s);
    if (!HoldsClock(p.state, options_.mode)) continue;
    if (!reason.empty()) reason += "; ";
    if (p.state == ParticipantState::kSettling) reason += "lockstep: " + p.topics.answer_topic + " connected, settling";
    else
      reason += "lockstep: waiting for " + p.topics.answer_topic +
                (p.sub.getNumPublishers() == 0 || p.state == ParticipantState::kGone
                     ? " (no publisher)"
                     : " (nobody subscribes " + p.topics.input_topic + ")");
  }
  if (!reason.empty() && ros::WallTime::now() >= next_report_) {
    ROS_INFO("[rotors_sim] holding the clock at t = %.3f s: %s", sim_time_s, reason.c_str());
    next_report_ = ros::WallTime::now() + ros::WallDuration(options_.report_period_s);
  }
  return reason;
}

void Lockstep::FlushInput(Participant* p) {
  if (p->topics.input_topic.empty()) return;
  if (const ros::PublicationPtr& pub = p->input_pub.Get()) pub->processPublishQueue();
}

void Lockstep::BeforeStep() {
  for (auto& p : participants_)
    if (p.input_count) p.input_count_before = *p.input_count;
}

void Lockstep::CountUnwaited(const ros::Time& stamp) {
  for (const auto& p : participants_) {
    if (!p.input_published || (WaitedFor(p.state) && p.last_stamp >= stamp)) continue;
    if (unwaited_steps_ == 0) {
      char why[512];
      std::snprintf(why, sizeof(why), "lockstep did not wait for %s at t = %.3f s (%s)", p.topics.answer_topic.c_str(),
                    stamp.toSec(), ToString(p.state));
      first_unwaited_reason_ = why;
      ROS_WARN("[rotors_sim] %s: the run is not repeatable", why);
    }
    ++unwaited_steps_;
    return;  // one per step
  }
}

void Lockstep::Rewind(const ros::Time& now) {
  ++rewinds_;
  latest_step_ = now;
  for (auto& p : participants_) p.last_stamp = std::min(p.last_stamp, now);
}

bool Lockstep::WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue, const std::function<bool()>& stop) {
  latest_step_ = stamp;
  for (auto& p : participants_) {
    FlushInput(&p);
    p.input_published = p.topics.input_topic.empty() || *p.input_count != p.input_count_before;
  }
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime next_check = start + ros::WallDuration(options_.silence_timeout_s);
  ros::WallTime next_report = start + ros::WallDuration(options_.report_period_s);
  const bool hold = options_.mode == LockstepMode::kHold;
  const double t_s = stamp.toSec();
  const uint64_t rewinds_before = rewinds_;
  while (ros::ok() && !stop()) {
    if (rewinds_ != rewinds_before) return true;  // reset_simulation was served meanwhile: the step is gone
    bool all = true;
    for (auto& p : participants_) {
      if (p.local) FlushAnswer(&p);
      if (Required(p) && p.last_stamp < stamp) all = false;
    }
    if (all) break;
    queue->callAvailable(ros::WallDuration(0.0005));
    const ros::WallTime now = ros::WallTime::now();
    bool lost = false;
    for (auto& p : participants_) {
      if (!Required(p) || p.last_stamp >= stamp) continue;
      if (p.state == ParticipantState::kFirstAnswer && now - start > ros::WallDuration(options_.first_answer_timeout_s))
        Apply(&p, ParticipantEvent::kFirstAnswerLate, t_s);
      if (now - start > ros::WallDuration(options_.silence_timeout_s)) Apply(&p, ParticipantEvent::kSilent, t_s);
      if (!hold || !Required(p)) continue;
      // one that unregistered is gone at once; a silent one is pinged now and then (on the pinger's thread)
      if (!ConnectedNow(p)) {
        Apply(&p, ParticipantEvent::kDisconnected, t_s);
      } else if (pinger_.Take(p.topics.answer_topic) == NodePinger::Answer::kDead) {
        Apply(&p, ParticipantEvent::kPingFailed, t_s);
      } else if (now >= next_check) {
        pinger_.Request(p.topics.answer_topic);
      } else if (now >= next_report) {
        ROS_WARN("[rotors_sim] lockstep: t = %.3f s: still waiting for an answer on %s (%.0f s)", t_s,
                 p.topics.answer_topic.c_str(), (now - start).toSec());
      }
      lost = lost || p.state == ParticipantState::kGone;
    }
    if (now >= next_check) next_check = now + ros::WallDuration(options_.silence_timeout_s);
    if (now >= next_report) next_report = now + ros::WallDuration(options_.report_period_s);
    if (lost) {
      CountUnwaited(stamp);
      return false;
    }
  }
  if (!ros::ok() || stop()) return true;  // shutting down: the last step's answer does not matter
  queue->callAvailable();                 // deliver the answer to every other subscriber of it too
  CountUnwaited(stamp);
  return true;
}

}  // namespace rotors_sim
