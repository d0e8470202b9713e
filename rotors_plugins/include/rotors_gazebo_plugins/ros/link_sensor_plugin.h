// The Load() skeleton the link-mounted sensor plugins share (pressure, magnetometer, airspeed):
// robotNamespace, linkName (required) and the topic parameter; the link and its world; one
// advertised message type; OnUpdate() after every world step while someone listens (ROS or the
// in-process taps). A plugin reads its own parameters between LoadLink() and StartPublishing().
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

template <class Msg>
class LinkSensorPlugin : public rotors_sim::ModelPlugin {
 protected:
  /// First in Load(): the namespace, the link (linkName, required; also the messages' frame_id) and
  /// the topic (<topic_param>, default_topic when absent).
  void LoadLink(const rotors_sim::physics::ModelPtr& model, const std::string& topic_param,
                const std::string& default_topic) {
    ns_ = ReadRobotNamespace(Params());
    std::string link_name;
    RequireParam(Params(), "linkName", &link_name);
    topic_ = default_topic;
    ReadParam(Params(), topic_param, &topic_);
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    msg_.header.frame_id = link_name;
  }

  /// Last in Load(): advertises the topic and calls OnUpdate() after each world step (not at all
  /// when nobody can listen).
  void StartPublishing() {
    node_ = MakeNode(ns_);
    pub_ = Advertise<Msg>(node_, ns_, topic_, *world_, 10);
    if (!pub_) return;
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  /// Fills msg_ (its stamp too) and publishes it with pub_.
  virtual void OnUpdate() = 0;

  std::string ns_, topic_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  Msg msg_;
  rotors_sim::ListenedPublisher pub_;  // no search through every topic per step

 private:
  std::shared_ptr<ros::NodeHandle> node_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins
