#include "rotors_core/ros/lockstep.h"

#include <ros/callback_queue.h>
#include <ros/publication.h>
#include <ros/topic_manager.h>

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstring>
#include <sstream>
#include <stdexcept>

namespace rotors_sim {

bool HeaderStamp(const topic_tools::ShapeShifter& msg, ros::Time* stamp) {
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
                   const LockstepOptions& options)
    : nh_(nh), options_(options) {
  participants_.resize(participants.size());  // fixed from here on: callbacks hold pointers
  for (size_t i = 0; i < participants.size(); ++i) {
    Participant& p = participants_[i];
    p.topics = participants[i];
    p.input_pub = PublicationCache(p.topics.input_topic);
    p.answer_pub = PublicationCache(p.topics.answer_topic);
    p.sub = Subscribe(&p);
    ROS_INFO("[rotors_sim] lockstep (%s): each step waits for an answer on %s%s%s",
             options_.mode == LockstepOptions::Mode::kHold ? "hold" : "lenient", p.topics.answer_topic.c_str(),
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
    if (p.local) continue;                  // answers are counted, not subscribed
    ros::Subscriber fresh = Subscribe(&p);  // appended behind the plugins' subscriptions
    p.sub.shutdown();
    p.sub = fresh;
  }
}

void Lockstep::OnMessage(Participant* p, const topic_tools::ShapeShifter::ConstPtr& msg) {
  ros::Time stamp;
  if (!HeaderStamp(*msg, &stamp)) return;
  if (p->muted) ROS_INFO("[rotors_sim] lockstep: %s is answering again", p->topics.answer_topic.c_str());
  p->muted = false;
  p->answered = true;
  p->warming_up = false;
  if (stamp > p->last_stamp) p->last_stamp = stamp;
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
  const bool local = static_cast<bool>(p->answer_pub.Get());
  if (local == p->local) return;
  p->local = local;
  if (local) {
    p->sub.shutdown();  // a watcher of another type would make every answer serialized
  } else {
    p->sub = Subscribe(p);  // unloaded: it may come back as a node
  }
}

bool Lockstep::LocalAnswered(Participant* p, const ros::Time& stamp) {
  const ros::PublicationPtr& pub = p->answer_pub.Get();
  if (!pub || pub->getSequence() == p->answer_seq) return false;
  p->answer_seq = pub->getSequence();
  p->answered = true;
  p->warming_up = false;
  if (stamp > p->last_stamp) p->last_stamp = stamp;
  return true;
}

bool Lockstep::ConnectedNow(const Participant& p) const {
  if (p.local) return p.answer_pub.Get() != nullptr;
  if (p.sub.getNumPublishers() == 0) return false;
  if (p.topics.input_topic.empty()) return true;
  // once present, a participant leaves through its answer topic; the input is checked on arrival
  return p.present || RemoteSubscribers(p.input_pub.Get()) > 0;
}

/// Updates p->present; true when it changed. A participant declared gone comes back only when a
/// node publishing its answer topic answers pings again (a restarted node).
bool Lockstep::UpdatePresence(Participant* p, double sim_time_s) {
  bool now = ConnectedNow(*p);
  if (now && p->gone) now = AnyPublisherAlive(p->topics.answer_topic);
  if (now == p->present) return false;
  p->present = now;
  if (now) {
    if (p->ever_present)
      ROS_INFO("[rotors_sim] lockstep: %s is back; resuming at t = %.3f s", p->topics.answer_topic.c_str(), sim_time_s);
    p->gone = false;
    p->ever_present = true;
    p->present_since = ros::WallTime::now();
    p->answered = false;
    p->warming_up = false;
  } else if (p->ever_present) {
    ROS_WARN("[rotors_sim] lockstep: %s went away at t = %.3f s; the simulation is paused until it is back",
             p->topics.answer_topic.c_str(), sim_time_s);
  }
  return true;
}

std::string Lockstep::HoldReason(double sim_time_s) {
  if (options_.mode != LockstepOptions::Mode::kHold) return "";
  // gone participants are pinged at most twice a second
  const bool may_ping = ros::WallTime::now() >= next_ping_;
  std::string reason;
  for (auto& p : participants_) {
    RefreshLocal(&p);
    if (!(p.gone && !may_ping)) UpdatePresence(&p, sim_time_s);
    if (p.present && ros::WallTime::now() - p.present_since >= ros::WallDuration(options_.settle_s)) continue;
    if (p.present) {
      reason += std::string(reason.empty() ? "" : "; ") + "lockstep: " + p.topics.answer_topic + " connected, settling";
      continue;
    }
    if (!reason.empty()) reason += "; ";
    reason += "lockstep: waiting for " + p.topics.answer_topic +
              (p.sub.getNumPublishers() == 0 || p.gone ? " (no publisher)"
                                                       : " (nobody subscribes " + p.topics.input_topic + ")");
  }
  if (may_ping) next_ping_ = ros::WallTime::now() + ros::WallDuration(0.5);
  if (!reason.empty() && ros::WallTime::now() >= next_report_) {
    ROS_INFO("[rotors_sim] holding the clock at t = %.3f s: %s", sim_time_s, reason.c_str());
    next_report_ = ros::WallTime::now() + ros::WallDuration(options_.report_period_s);
  }
  return reason;
}

uint32_t Lockstep::FlushInput(Participant* p) {
  if (p->topics.input_topic.empty()) return 0;
  const ros::PublicationPtr& pub = p->input_pub.Get();
  if (!pub) return 0;
  pub->processPublishQueue();  // numbers and sends queued messages now, in this thread
  return pub->getSequence();
}

void Lockstep::BeforeStep() {
  for (auto& p : participants_) {
    p.input_seq = FlushInput(&p);
    if (!p.local) continue;
    const ros::PublicationPtr& answer = p.answer_pub.Get();
    if (answer) p.answer_seq = answer->getSequence();
  }
}

bool Lockstep::Required(const Participant& p) const {
  if (!p.input_published) return false;
  if (options_.mode == LockstepOptions::Mode::kLenient) return !p.muted && (p.local || p.sub.getNumPublishers() > 0);
  return p.present && !p.warming_up;
}

bool Lockstep::WaitForAnswers(const ros::Time& stamp, ros::CallbackQueue* queue, const std::function<bool()>& stop) {
  for (auto& p : participants_) p.input_published = p.topics.input_topic.empty() || FlushInput(&p) != p.input_seq;
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime next_check = start + ros::WallDuration(options_.silence_timeout_s);
  ros::WallTime next_report = start + ros::WallDuration(options_.report_period_s);
  const bool hold = options_.mode == LockstepOptions::Mode::kHold;
  while (ros::ok() && !stop()) {
    bool all = true;
    for (auto& p : participants_) {
      if (p.local) LocalAnswered(&p, stamp);
      if (Required(p) && p.last_stamp < stamp) all = false;
    }
    if (all) break;
    queue->callAvailable(ros::WallDuration(0.0005));
    const ros::WallTime now = ros::WallTime::now();
    for (auto& p : participants_) {
      if (!Required(p) || p.last_stamp >= stamp) continue;
      if (!p.answered && now - start > ros::WallDuration(options_.first_answer_timeout_s)) {
        ROS_INFO(
            "[rotors_sim] lockstep: no first answer on %s to t = %.3f s within %.1f s; not waiting for it until "
            "it answers (e.g. an estimator not yet initialised)",
            p.topics.answer_topic.c_str(), stamp.toSec(), options_.first_answer_timeout_s);
        p.warming_up = true;
      } else if (!hold && now - start > ros::WallDuration(options_.silence_timeout_s)) {
        ROS_WARN(
            "[rotors_sim] lockstep: no answer on %s for t = %.3f s within %.1f s; not waiting for it until it "
            "answers again",
            p.topics.answer_topic.c_str(), stamp.toSec(), options_.silence_timeout_s);
        p.muted = true;
      }
    }
    if (!hold) continue;
    // a participant that unregistered is gone at once; a silent one is pinged now and then
    bool lost = false;
    for (auto& p : participants_) {
      if (!Required(p) || p.last_stamp >= stamp) continue;
      if (!ConnectedNow(p)) {
        lost = UpdatePresence(&p, stamp.toSec()) || lost;
      } else if (now >= next_check && !AnyPublisherAlive(p.topics.answer_topic)) {
        p.gone = true;
        lost = UpdatePresence(&p, stamp.toSec()) || lost;
      } else if (now >= next_report) {
        ROS_WARN("[rotors_sim] lockstep: t = %.3f s: still waiting for an answer on %s (%.0f s)", stamp.toSec(),
                 p.topics.answer_topic.c_str(), (now - start).toSec());
      }
    }
    if (now >= next_check) next_check = now + ros::WallDuration(options_.silence_timeout_s);
    if (now >= next_report) next_report = now + ros::WallDuration(options_.report_period_s);
    if (lost) return false;
  }
  queue->callAvailable();  // deliver the answer to every other subscriber of it too
  return true;
}

}  // namespace rotors_sim
