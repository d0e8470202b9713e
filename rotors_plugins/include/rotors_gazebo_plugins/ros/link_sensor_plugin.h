// The Load() skeleton the small sensor plugins share. SensorTopic: robotNamespace and the topic
// parameter, for every one of them (pressure, magnetometer, airspeed, optical flow).
// LinkSensorPlugin adds what the link-mounted ones share (pressure, magnetometer, airspeed):
// linkName (required), the link, its world and the vehicle bus, and OnUpdate() after every world
// step, or at <pubRate> [Hz] (ours, PX4's plugins' parameter; 0 or absent: every step, as RotorS),
// which puts the reading on the bus; the reading's message is published from there
// (FeedPublisher). A plugin reads its own parameters between LoadLink() and StartPublishing().
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include <ros/ros.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/feed_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

/// A sensor plugin's topic: where its reading is published.
class SensorTopic {
 public:
  /// The namespace (robotNamespace) and the topic (<topic_param>, default_topic when absent).
  void Read(rotors_sim::SdfParams& params, const std::string& topic_param, const std::string& default_topic) {
    ns_ = ReadRobotNamespace(params);
    topic_ = default_topic;
    ReadParam(params, topic_param, &topic_);
  }
  const std::string& Namespace() const { return ns_; }
  const std::string& Topic() const { return topic_; }
  /// The resolved topic name ("/firefly/air_pressure"): the key of the sensor's feed on the bus.
  std::string Resolved() const { return ResolveTopic(ns_, topic_); }

 private:
  std::string ns_, topic_;
};

/// Reading: the bus' reading type (sensor_feeds.h); Msg: its ROS message (Fill in feed_publisher.h).
template <class Reading, class Msg>
class LinkSensorPlugin : public rotors_sim::ModelPlugin {
 protected:
  /// First in Load(): the namespace and topic (SensorTopic::Read), the link (linkName, required;
  /// also the messages' frame_id, in prototype_).
  void LoadLink(const rotors_sim::physics::ModelPtr& model, const std::string& topic_param,
                const std::string& default_topic) {
    topic_.Read(Params(), topic_param, default_topic);
    std::string link_name;
    RequireParam(Params(), "linkName", &link_name);
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*world_, topic_.Namespace());
    prototype_.header.frame_id = link_name;
    double rate_hz = 0.0;
    ReadParam(Params(), "pubRate", &rate_hz);
    if (!std::isfinite(rate_hz) || rate_hz < 0.0)
      throw rotors_sim::SimError("pubRate = " + std::to_string(rate_hz) +
                                 " Hz must be >= 0 (0: a message every physics step)");
    period_s_ = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  }

  /// Last in Load(): the sensor's feed among the bus' feeds of its kind (e.g. Bus().sensors.barometer),
  /// its messages (prototype_ with each reading) on the topic, and OnUpdate() after each world step
  /// (the bus takes the reading whether or not anyone listens).
  void StartPublishing(SensorFeeds<Reading>& feeds) {
    feed_ = &feeds.Of(topic_.Resolved());
    bus_->Register(this, MeasuringRecord{topic_.Resolved()});
    publisher_.Start(*feed_, *world_, topic_.Namespace(), topic_.Topic(), prototype_);
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] {
      if (Due()) OnUpdate();
    });
  }

  /// Takes the reading and puts it on the bus (Put).
  virtual void OnUpdate() = 0;
  /// The reading, taken now, on the bus (and from there on the topic).
  void Put(const Reading& reading) { feed_->Put(reading, world_->SimTime().Double()); }
  /// robotNamespace, as LoadLink() read it.
  const std::string& Namespace() const { return topic_.Namespace(); }
  VehicleBus& Bus() { return *bus_; }

  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  Msg prototype_;  ///< the message's fixed fields (frame, covariance), set in Load()

 private:
  /// Every step without pubRate; else sample k at the first step at or after k / pubRate, so the
  /// rate is pubRate on any step (100 Hz on 250 Hz steps: 8 and 12 ms apart in turn). PX4's plugins
  /// publish once more than 1 / pubRate has passed since the last, which on 250 Hz steps is 41.7 Hz
  /// for 50 and 83.3 Hz for 100. A reset (sim time going back) starts again.
  bool Due() {
    if (period_s_ <= 0.0) return true;
    const double t = world_->SimTime().Double();
    if (t < last_s_) next_s_ = last_s_ = -1.0;
    constexpr double kEpsilon_s = 1e-9;  // sim time is whole nanoseconds
    if (last_s_ >= 0.0 && t + kEpsilon_s < next_s_) return false;
    next_s_ = (last_s_ >= 0.0 ? next_s_ : t) + period_s_;
    if (next_s_ <= t) next_s_ = t + period_s_;  // no burst after a long step
    last_s_ = t;
    return true;
  }

  SensorTopic topic_;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<Reading>* feed_ = nullptr;
  FeedPublisher<Reading, Msg> publisher_;
  rotors_sim::event::ConnectionPtr connection_;
  double period_s_ = 0.0, last_s_ = -1.0, next_s_ = -1.0;
};

}  // namespace rotors_gazebo_plugins
