// librotors_gazebo_controller_interface.so: takes /<ns>/command/motor_speed (mav_msgs/Actuators,
// rad/s) and hands the latest valid command to the motor models in memory (reference section
// 4.3, without its ROS round trip). /<ns>/gazebo/command/motor_speed, which RotorS users drive
// directly, is accepted the same way. A command of the wrong length or with NaN, inf or negative
// speeds is rejected with a throttled error; the last valid command (or zero) stays in force.
// commandTimeout (ours, default 2 s of sim time; 0 = never): when no valid command came for that
// long while the motors run (the controller died), the motors stop, as an ESC that lost its signal,
// and one line says so; the next valid command starts them again.
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#include <mav_msgs/Actuators.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboControllerInterface : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    namespace_ = ReadRobotNamespace(Params());
    std::string command_topic = "command/motor_speed", direct_topic = "gazebo/command/motor_speed";
    ReadParam(Params(), "commandMotorSpeedSubTopic", &command_topic);
    ReadParam(Params(), "motorSpeedCommandPubTopic", &direct_topic);
    ReadParam(Params(), "commandTimeout", &command_timeout_s_);
    if (!(command_timeout_s_ >= 0.0))
      throw rotors_sim::SimError("commandTimeout = " + std::to_string(command_timeout_s_) +
                                 " must be >= 0 s (0: hold the last command forever)");
    model_name_ = model->GetName();
    bus_ = VehicleBus::For(*model->GetWorldRaw(), namespace_);
    bus_->Register(this, PlumbingRecord{});
    if (command_timeout_s_ > 0.0)
      update_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
          [this](const rotors_sim::common::UpdateInfo& info) { CheckCommandAge(info.simTime.Double()); });
    node_ = MakeNode(namespace_);
    if (!node_) return;
    subs_.push_back(node_->subscribe(command_topic, 1, &GazeboControllerInterface::OnCommand, this,
                                     ros::TransportHints().tcpNoDelay()));
    subs_.push_back(node_->subscribe(direct_topic, 1, &GazeboControllerInterface::OnCommand, this,
                                     ros::TransportHints().tcpNoDelay()));
  }

  void Reset() override {
    bus_->motor_command_rad_s.clear();
    seen_commands_ = bus_->motor_command_count;
    last_command_s_ = now_s_ = 0.0;
    timed_out_ = false;
  }

 private:
  void OnCommand(const mav_msgs::ActuatorsConstPtr& msg) {
    const std::string why = bus_->SetMotorCommand(msg->angular_velocities);
    if (!why.empty()) {
      // at most one line per second of wall time per kind of fault (the reason without its numbers),
      // counting the rejections it did not show
      std::string kind;
      for (char c : why)
        if (!std::isdigit(static_cast<unsigned char>(c))) kind += c;
      Throttle& throttle = throttles_[kind];
      const ros::WallTime now = ros::WallTime::now();
      if ((now - throttle.last_report).toSec() > 1.0) {
        const std::string more = throttle.unreported > 0 ? " (and " + std::to_string(throttle.unreported) +
                                                               " more like it since the last line)"
                                                         : "";
        ROS_ERROR("[controller_interface] model '%s': rejected motor command: %s; keeping the last valid one%s",
                  model_name_.c_str(), why.c_str(), more.c_str());
        throttle.last_report = now;
        throttle.unreported = 0;
      } else {
        ++throttle.unreported;
      }
      return;
    }
  }

  /// Commands come from ROS (OnCommand) or in process (the Python module), both through the bus:
  /// a new one shows as a changed VehicleBus::motor_command_count.
  void CheckCommandAge(double t_s) {
    if (bus_->motor_command_count != seen_commands_) {
      seen_commands_ = bus_->motor_command_count;
      last_command_s_ = now_s_;
      if (timed_out_) {
        ROS_INFO("[controller_interface] model '%s': motor commands again at t = %.3f s", model_name_.c_str(), now_s_);
        timed_out_ = false;
      }
    }
    if (t_s < now_s_) last_command_s_ = t_s;  // the clock went back (reset_simulation)
    now_s_ = t_s;
    if (timed_out_ || bus_->motor_command_rad_s.empty()) return;
    if (t_s - last_command_s_ <= command_timeout_s_) return;
    ROS_ERROR(
        "[controller_interface] model '%s': no motor command for %.2f s (commandTimeout; is the controller "
        "running?): motors stopped at t = %.3f s",
        model_name_.c_str(), t_s - last_command_s_, t_s);
    bus_->motor_command_rad_s.assign(bus_->motor_command_rad_s.size(), 0.0);
    timed_out_ = true;
  }

  std::string namespace_, model_name_;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  std::shared_ptr<ros::NodeHandle> node_;
  std::vector<ros::Subscriber> subs_;
  struct Throttle {
    ros::WallTime last_report;
    int unreported = 0;
  };
  std::map<std::string, Throttle> throttles_;
  double command_timeout_s_ = 2.0;
  double now_s_ = 0.0, last_command_s_ = 0.0;  ///< sim time [s]
  uint64_t seen_commands_ = 0;                 ///< VehicleBus::motor_command_count at the last step
  bool timed_out_ = false;
  rotors_sim::event::ConnectionPtr update_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboControllerInterface)
