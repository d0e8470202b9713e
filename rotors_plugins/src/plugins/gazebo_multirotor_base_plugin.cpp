// librotors_gazebo_multirotor_base_plugin.so: publishes the real signed speeds of all rotors as one
// mav_msgs/Actuators on motor_speed (reference section 4.2). The rotor joint states are published
// by the simulator for every model on /<model>/joint_states.
// Ours (RotorS issue 511): motor failure injection. The service <ns>/set_motor_failure
// (rotors_comm/SetMotorFailure) fails or derates motor N from sim time t; detection_delay after it
// takes effect it is announced latched on <ns>/motor_failure (rotors_comm/MotorFailure), which a
// controller that knows about faults listens to.
#include <cmath>
#include <sstream>

#include <mav_msgs/Actuators.h>
#include <rotors_comm/MotorFailure.h>
#include <rotors_comm/SetMotorFailure.h>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
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
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    namespace_ = ReadRobotNamespace(Params());
    // RotorS scales the joint speeds it publishes by this; the bus holds the real speeds already
    Params().Accept("rotorVelocitySlowdownSim", "the published speeds are the real ones");
    std::string topic = "motor_speed";
    ReadParam(Params(), "linkName", &frame_id_);
    ReadParam(Params(), "motorPubTopic", &topic);
    RequireLink(model, frame_id_);
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*model->GetWorldRaw(), namespace_);
    bus_->Register(this, PlumbingRecord{});
    node_ = MakeNode(namespace_);
    pub_ = Advertise<mav_msgs::Actuators>(node_, namespace_, topic, *model->GetWorldRaw(), 1);
    failure_pub_ =
        Advertise<rotors_comm::MotorFailure>(node_, namespace_, "motor_failure", *model->GetWorldRaw(), 10, true);
    if (node_) {
      failure_srv_ = node_->advertiseService("set_motor_failure", &GazeboMultirotorBasePlugin::OnSetFailure, this);
    }
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  void Reset() override {
    for (MotorFault& f : bus_->motor_faults) f = MotorFault();
    pending_.clear();
  }

 private:
  bool OnSetFailure(rotors_comm::SetMotorFailure::Request& req, rotors_comm::SetMotorFailure::Response& res) {
    std::ostringstream why;
    if (req.motor_number < 0 || req.motor_number >= bus_->rotor_count)
      why << "motor_number " << req.motor_number << " is not a motor of " << namespace_ << " (0.."
          << bus_->rotor_count - 1 << ")";
    else if (!(req.speed_factor >= 0.0 && req.speed_factor <= 1.0))
      why << "speed_factor " << req.speed_factor << " must be in [0, 1] (0: failed, 1: healthy)";
    else if (!std::isfinite(req.start_time)) why << "start_time " << req.start_time << " must be a finite sim time [s]";
    else if (!(req.detection_delay >= 0.0 && std::isfinite(req.detection_delay)))
      why << "detection_delay " << req.detection_delay << " must be a finite time >= 0 [s]";
    res.success = why.str().empty();
    if (!res.success) {
      res.message = why.str();
      ROS_ERROR_THROTTLE(1.0, "[multirotor_base] set_motor_failure refused: %s", res.message.c_str());
      return true;
    }
    const double now_s = world_->SimTime().Double();
    const double start_s = std::max(req.start_time, now_s);
    bus_->motor_faults[req.motor_number] = {req.speed_factor, start_s};
    pending_.push_back({req.motor_number, start_s + req.detection_delay});
    std::ostringstream what;
    what << namespace_ << " motor " << req.motor_number << " at " << req.speed_factor << " of its command from "
         << start_s << " s, announced " << req.detection_delay << " s later";
    res.message = what.str();
    ROS_WARN("[multirotor_base] fault injected: %s", res.message.c_str());
    return true;
  }

  void OnUpdate() {
    if (!pub_) return;
    const double now_s = world_->SimTime().Double();
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (now_s < it->announce_at_s) {
        ++it;
        continue;
      }
      const MotorFault& f = bus_->motor_faults[it->motor_number];
      rotors_comm::MotorFailure msg;
      msg.header.stamp = ToRos(world_->SimTime());
      msg.header.frame_id = frame_id_;
      msg.motor_number = it->motor_number;
      msg.speed_factor = f.speed_factor;
      failure_pub_.publish(msg);
      it = pending_.erase(it);
    }
    if (pub_.getNumSubscribers() == 0) return;
    mav_msgs::Actuators msg;
    msg.header.stamp = ToRos(world_->SimTime());
    msg.header.frame_id = frame_id_;
    msg.angular_velocities = bus_->rotor_speed_rad_s;
    pub_.publish(msg);
  }

  std::string namespace_, frame_id_ = "base_link";
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  struct Announcement {
    int motor_number;
    double announce_at_s;  ///< [s] sim time
  };
  std::vector<Announcement> pending_;  ///< faults set but not yet announced
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher pub_, failure_pub_;
  ros::ServiceServer failure_srv_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMultirotorBasePlugin)
