// librotors_gazebo_pressure_plugin.so (rotors_reference.md 4.11): sensor_msgs/FluidPressure on
// <ns>/<pressureTopic> every physics step: the standard atmosphere at referenceAltitude + z_W,
// plus N(0, pressureVariance).
#include <sensor_msgs/FluidPressure.h>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboPressurePlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) override {
    const std::string ns = ReadRobotNamespace(Params());
    std::string link_name, topic = "air_pressure";
    RequireParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "pressureTopic", &topic);
    PressureParams p;
    ReadParam(Params(), "referenceAltitude", &p.reference_altitude_m);
    ReadParam(Params(), "pressureVariance", &p.pressure_variance_pa2);
    ThrowIfInvalid(p.Validate());
    model_.Emplace(p, ReadSeed(Params()));
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    msg_.header.frame_id = link_name;
    msg_.variance = p.pressure_variance_pa2;
    node_ = MakeNode(ns);
    pub_ = Advertise<sensor_msgs::FluidPressure>(node_, ns, topic, *model->GetWorldRaw(), 10);
    if (!pub_) return;  // neither ROS nor in-process taps: nobody to publish to
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() {
    msg_.header.stamp = ToRos(world_->SimTime());
    msg_.fluid_pressure = model_->Measure(link_->WorldPose().Pos().Z());
    pub_.publish(msg_);
  }

  SeededModel<PressureModel> model_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  sensor_msgs::FluidPressure msg_;
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher pub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboPressurePlugin)
