// The Load() skeleton the small sensor plugins share. SensorTopic: robotNamespace, the topic
// parameter and one advertised message type (ROS, or the in-process taps), for every one of them
// (pressure, magnetometer, airspeed, optical flow). LinkSensorPlugin adds what the link-mounted
// ones share (pressure, magnetometer, airspeed): linkName (required), the link and its world, and
// OnUpdate() after every world step while someone listens. A plugin reads its own parameters
// between LoadLink() and StartPublishing().
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>

#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

/// A sensor plugin's topic: where it publishes and how.
template <class Msg>
class SensorTopic {
 public:
  /// The namespace (robotNamespace) and the topic (<topic_param>, default_topic when absent).
  void Read(rotors_sim::SdfParams& params, const std::string& topic_param, const std::string& default_topic) {
    ns_ = ReadRobotNamespace(params);
    topic_ = default_topic;
    ReadParam(params, topic_param, &topic_);
  }
  /// Advertises the topic; false when nobody can listen (neither ROS nor the world's taps).
  bool Advertise(rotors_sim::physics::World& world) {
    node_ = MakeNode(ns_);
    pub_ = rotors_gazebo_plugins::Advertise<Msg>(node_, ns_, topic_, world, 10);
    return static_cast<bool>(pub_);
  }
  void Publish(const Msg& msg) { pub_.publish(msg); }
  const std::string& Namespace() const { return ns_; }

 private:
  std::string ns_, topic_;
  std::shared_ptr<ros::NodeHandle> node_;
  rotors_sim::ListenedPublisher pub_;  // no search through every topic per step
};

template <class Msg>
class LinkSensorPlugin : public rotors_sim::ModelPlugin {
 protected:
  /// First in Load(): the namespace and topic (SensorTopic::Read), the link (linkName, required;
  /// also the messages' frame_id).
  void LoadLink(const rotors_sim::physics::ModelPtr& model, const std::string& topic_param,
                const std::string& default_topic) {
    topic_.Read(Params(), topic_param, default_topic);
    std::string link_name;
    RequireParam(Params(), "linkName", &link_name);
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    msg_.header.frame_id = link_name;
  }

  /// Last in Load(): advertises the topic and calls OnUpdate() after each world step (not at all
  /// when nobody can listen).
  void StartPublishing() {
    if (!topic_.Advertise(*world_)) return;
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  /// Fills msg_ (its stamp too) and publishes it with Publish().
  virtual void OnUpdate() = 0;
  void Publish() { topic_.Publish(msg_); }
  /// robotNamespace, as LoadLink() read it.
  const std::string& Namespace() const { return topic_.Namespace(); }

  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  Msg msg_;

 private:
  SensorTopic<Msg> topic_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins
