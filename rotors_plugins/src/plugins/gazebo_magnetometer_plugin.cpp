// librotors_gazebo_magnetometer_plugin.so (rotors_reference.md 4.10): sensor_msgs/MagneticField
// on <ns>/<magnetometerTopic> every physics step, B_B = R_WB^T m_W + b_B + n with covariance
// diag(sigma^2). The reference field is given as north, east, down [T] and placed in the ENU
// world correctly (RotorS used N, E, D as x, y, z).
#include <sensor_msgs/MagneticField.h>

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

class GazeboMagnetometerPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) override {
    const std::string ns = ReadRobotNamespace(Params());
    std::string link_name, topic = "magnetic_field";
    RequireParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "magnetometerTopic", &topic);
    MagnetometerParams p;
    ReadParam(Params(), "refMagNorth", &p.reference_NED_T.x());
    ReadParam(Params(), "refMagEast", &p.reference_NED_T.y());
    ReadParam(Params(), "refMagDown", &p.reference_NED_T.z());
    ReadVector(Params(), "noiseNormal", &p.noise_normal_T);
    ReadVector(Params(), "noiseUniformInitialBias", &p.noise_uniform_initial_bias_T);
    ThrowIfInvalid(p.Validate());
    model_.Emplace(p, ReadSeed(Params()));
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    msg_.header.frame_id = link_name;
    for (int i = 0; i < 3; ++i) msg_.magnetic_field_covariance[i * 4] = p.noise_normal_T[i] * p.noise_normal_T[i];
    node_ = MakeNode(ns);
    pub_ = Advertise<sensor_msgs::MagneticField>(node_, ns, topic, *model->GetWorldRaw(), 10);
    if (!pub_) return;  // neither ROS nor in-process taps: nobody to publish to
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() {
    const auto q = link_->WorldPose().Rot();
    msg_.header.stamp = ToRos(world_->SimTime());
    msg_.magnetic_field = ToVector3Msg(model_->Measure(Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z())));
    pub_.publish(msg_);
  }

  SeededModel<MagnetometerModel> model_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  sensor_msgs::MagneticField msg_;
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher pub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMagnetometerPlugin)
