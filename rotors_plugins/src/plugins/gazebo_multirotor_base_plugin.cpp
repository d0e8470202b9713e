// librotors_gazebo_multirotor_base_plugin.so: publishes the real signed speeds of all rotors as one
// mav_msgs/Actuators on motor_speed (reference section 4.2). The rotor joint states are published
// by the simulator for every model on /<model>/joint_states.
#include <mav_msgs/Actuators.h>

#include "rotors_core/event.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboMultirotorBasePlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) override {
    CheckKnownParams(sdf, {"robotNamespace", "linkName", "motorPubTopic", "rotorVelocitySlowdownSim"});
    namespace_ = ReadRobotNamespace(sdf);
    std::string topic = "motor_speed";
    ReadParam(sdf, "linkName", &frame_id_);
    ReadParam(sdf, "motorPubTopic", &topic);
    RequireLink(model, frame_id_);
    world_ = model->GetWorldRaw();
    bus_ = &VehicleBus::For(namespace_);
    node_ = MakeNode(namespace_);
    if (node_) pub_ = node_->advertise<mav_msgs::Actuators>(topic, 1);
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

 private:
  void OnUpdate() {
    if (!node_ || pub_.getNumSubscribers() == 0) return;
    mav_msgs::Actuators msg;
    msg.header.stamp = ToRos(world_->SimTime());
    msg.header.frame_id = frame_id_;
    msg.angular_velocities = bus_->rotor_speed_rad_s;
    pub_.publish(msg);
  }

  std::string namespace_, frame_id_ = "base_link";
  rotors_sim::physics::World* world_ = nullptr;
  VehicleBus* bus_ = nullptr;
  std::shared_ptr<ros::NodeHandle> node_;
  ros::Publisher pub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMultirotorBasePlugin)
