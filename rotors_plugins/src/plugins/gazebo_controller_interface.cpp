// librotors_gazebo_controller_interface.so: takes /<ns>/command/motor_speed (mav_msgs/Actuators,
// rad/s) and hands the latest valid command to the motor models in memory (reference section
// 4.3, without its ROS round trip). /<ns>/gazebo/command/motor_speed, which RotorS users drive
// directly, is accepted the same way. A command of the wrong length or with NaN, inf or negative
// speeds is rejected with a throttled error; the last valid command (or zero) stays in force.
#include <cmath>
#include <sstream>

#include <mav_msgs/Actuators.h>

#include "rotors_core/physics/model.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

/// Empty if `speeds` is a valid command for `rotor_count` rotors, else the reason.
std::string CheckMotorCommand(const std::vector<double>& speeds, int rotor_count) {
  std::ostringstream why;
  if (static_cast<int>(speeds.size()) != rotor_count) {
    why << "has " << speeds.size() << " angular_velocities, the vehicle has " << rotor_count << " rotors";
    return why.str();
  }
  for (size_t i = 0; i < speeds.size(); ++i) {
    if (!std::isfinite(speeds[i]) || speeds[i] < 0.0) {
      why << "angular_velocities[" << i << "] = " << speeds[i] << " must be a finite speed >= 0 rad/s";
      return why.str();
    }
  }
  return {};
}

class GazeboControllerInterface : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) override {
    CheckKnownParams(sdf, {"robotNamespace", "commandMotorSpeedSubTopic", "motorSpeedCommandPubTopic"});
    namespace_ = ReadRobotNamespace(sdf);
    std::string command_topic = "command/motor_speed", direct_topic = "gazebo/command/motor_speed";
    ReadParam(sdf, "commandMotorSpeedSubTopic", &command_topic);
    ReadParam(sdf, "motorSpeedCommandPubTopic", &direct_topic);
    model_name_ = model->GetName();
    bus_ = VehicleBus::For(namespace_);
    node_ = MakeNode(namespace_);
    if (!node_) return;
    subs_.push_back(node_->subscribe(command_topic, 1, &GazeboControllerInterface::OnCommand, this,
                                     ros::TransportHints().tcpNoDelay()));
    subs_.push_back(node_->subscribe(direct_topic, 1, &GazeboControllerInterface::OnCommand, this,
                                     ros::TransportHints().tcpNoDelay()));
  }

  void Reset() override { bus_->motor_command_rad_s.clear(); }

 private:
  void OnCommand(const mav_msgs::ActuatorsConstPtr& msg) {
    const std::string why = CheckMotorCommand(msg->angular_velocities, bus_->rotor_count);
    if (!why.empty()) {
      // throttled per reason: a new kind of bad command is always reported
      const ros::WallTime now = ros::WallTime::now();
      if (why != last_reason_ || (now - last_report_).toSec() > 1.0) {
        ROS_ERROR("[controller_interface] model '%s': rejected motor command: %s; keeping the last valid one",
                  model_name_.c_str(), why.c_str());
        last_reason_ = why;
        last_report_ = now;
      }
      return;
    }
    bus_->motor_command_rad_s = msg->angular_velocities;
  }

  std::string namespace_, model_name_;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  std::shared_ptr<ros::NodeHandle> node_;
  std::vector<ros::Subscriber> subs_;
  std::string last_reason_;
  ros::WallTime last_report_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboControllerInterface)
