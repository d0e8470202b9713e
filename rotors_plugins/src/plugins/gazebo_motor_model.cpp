// librotors_gazebo_motor_model.so: one rotor (reference section 4.1). Reads its command from the
// vehicle bus, applies eqs. 1-4 through RotorModel, spins the rotor joint for rviz and publishes
// the real signed rotor speed [rad/s] on motor_speed/<N>. An injected fault (VehicleBus::SpeedFactor)
// scales the command the motor follows.
// With <motorType>position</motorType> (the omav's tilt units) it is a servo instead: its command
// entry is a joint angle [rad], TiltServoModel's PID (<joint_control_pid>) turns the error into a
// joint torque, and it publishes the joint angle [rad] on <motorPositionPubTopic>.
// With <motorType>force</motorType> (RotorS') its command entry is the joint effort [N m or N] itself,
// limited to +-<maxForce> when given. <motorForcePubTopic> (any type) publishes the effort applied to
// the joint each step: 0 for a rotor, whose joint is driven by speed and whose thrust acts on its link.
#include <algorithm>
#include <limits>

#include <std_msgs/Float32.h>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/rotor_model.h"
#include "rotors_gazebo_plugins/models/tilt_servo_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

using rotors_sim::physics::Vector3d;

namespace {
Eigen::Vector3d ToEigen(const Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }
Vector3d FromEigen(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

class GazeboMotorModel : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    namespace_ = ReadRobotNamespace(Params());
    // RotorS' ROS topics between the plugins: here the command and the wind travel in memory (VehicleBus)
    Params().Accept("commandSubTopic", "the motor command comes over the vehicle bus");
    Params().Accept("windSpeedSubTopic", "the wind comes over the vehicle bus");
    std::string joint_name, motor_type = "velocity";
    RequireParam(Params(), "jointName", &joint_name);
    RequireParam(Params(), "motorNumber", &motor_number_);
    ReadParam(Params(), "motorType", &motor_type);
    if (motor_number_ < 0)
      throw rotors_sim::SimError("motorNumber = " + std::to_string(motor_number_) + " must be >= 0");
    joint_ = RequireJoint(model, joint_name);
    dt_s_ = model->GetWorldRaw()->Physics().max_step_size_s;
    bus_ = VehicleBus::For(*model->GetWorldRaw(), namespace_);
    node_ = MakeNode(namespace_);
    if (motor_type == "velocity") {
      LoadRotor(model);
    } else if (motor_type == "position") {
      LoadServo(model);
    } else if (motor_type == "force") {
      LoadEffort(model);
    } else {
      throw rotors_sim::SimError("motorType = '" + motor_type + "' is not known; use 'velocity' (a rotor), " +
                                 "'position' (a servo such as the omav's tilt units) or 'force' (a joint effort)");
    }
    std::string force_topic;
    if (ReadParam(Params(), "motorForcePubTopic", &force_topic))
      force_pub_ = Advertise<std_msgs::Float32>(node_, namespace_, force_topic, *model->GetWorldRaw(), 1);
    connection_ =
        rotors_sim::event::Events::ConnectWorldUpdateBegin([this](const rotors_sim::common::UpdateInfo& info) {
          if (rotor_) {
            OnRotorUpdate(info.simTime.Double());
          } else if (servo_) {
            OnServoUpdate();
          } else {
            OnEffortUpdate();
          }
          PublishEffort();
        });
  }

  void Reset() override {
    if (rotor_) rotor_->Reset();
    if (servo_) servo_->Reset();
    joint_->SetVelocity(0, 0.0);
  }

 private:
  void LoadRotor(const rotors_sim::physics::ModelPtr& model) {
    std::string link_name, speed_topic = "motor_speed";
    RequireParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "motorSpeedPubTopic", &speed_topic);
    const RotorParams p = ReadRotorParams(Params());
    slowdown_ = ReadRotorSlowdown(Params());  // visual only
    rotor_ = std::make_unique<RotorModel>(p);
    link_ = RequireLink(model, link_name);
    parent_link_ = joint_->GetParent();
    bus_->RegisterRotor(motor_number_, p.max_rot_velocity);
    bus_->RegisterRotorMounting(motor_number_,
                                {link_, ToEigen(joint_->LocalAxis(0)), link_->GetInertial().Mass(), p.motor_constant});
    bus_->Register(this, MotorRecord{motor_number_, "velocity", joint_->GetName(), link_name, p, slowdown_});
    speed_pub_ = Advertise<std_msgs::Float32>(node_, namespace_, speed_topic, *model->GetWorldRaw(), 1);
  }

  void LoadServo(const rotors_sim::physics::ModelPtr& model) {
    if (joint_->GetType() != rotors_sim::physics::Joint::Type::kRevolute)
      throw rotors_sim::SimError("motorType 'position' needs a revolute or continuous solver joint; '" +
                                 joint_->GetName() + "' is not one (a <kinematic_joint> cannot take a torque)");
    TiltServoParams p;
    if (!ReadGazeboPid(Params(), "joint_control_pid", true, &p))
      throw rotors_sim::SimError(
          "motorType 'position' needs <joint_control_pid> with p, i, d, iMax, iMin, cmdMax, "
          "cmdMin (Gazebo's PID; the omav uses p 1, i 0, d 0.01, iMax 1, iMin -1, cmdMax 2, "
          "cmdMin -2)");
    ThrowIfInvalid(p.Validate());
    servo_ = std::make_unique<TiltServoModel>(p);
    std::string position_topic = "motor_position/" + std::to_string(motor_number_);
    ReadParam(Params(), "motorPositionPubTopic", &position_topic);
    bus_->RegisterServo(motor_number_);
    bus_->Register(this, MotorRecord{motor_number_, "position", joint_->GetName(), "", {}, 1.0});
    speed_pub_ = Advertise<std_msgs::Float32>(node_, namespace_, position_topic, *model->GetWorldRaw(), 1);
  }

  void LoadEffort(const rotors_sim::physics::ModelPtr& model) {
    if (joint_->GetType() != rotors_sim::physics::Joint::Type::kRevolute &&
        joint_->GetType() != rotors_sim::physics::Joint::Type::kPrismatic)
      throw rotors_sim::SimError("motorType 'force' needs a revolute, continuous or prismatic solver joint; '" +
                                 joint_->GetName() + "' is not one (a <kinematic_joint> cannot take an effort)");
    ReadParam(Params(), "maxForce", &max_force_);
    if (!(max_force_ > 0.0)) throw rotors_sim::SimError("maxForce must be > 0 (the effort limit, N m or N)");
    std::string speed_topic = "motor_speed/" + std::to_string(motor_number_);
    ReadParam(Params(), "motorSpeedPubTopic", &speed_topic);
    bus_->RegisterServo(motor_number_);
    bus_->Register(this, MotorRecord{motor_number_, "force", joint_->GetName(), "", {}, 1.0});
    speed_pub_ = Advertise<std_msgs::Float32>(node_, namespace_, speed_topic, *model->GetWorldRaw(), 1);
  }

  void OnEffortUpdate() {
    const auto& cmd = bus_->motor_command_rad_s;
    const double command = motor_number_ < static_cast<int>(cmd.size()) ? cmd[motor_number_] : 0.0;
    applied_effort_ = std::clamp(command, -max_force_, max_force_);
    joint_->SetForce(0, applied_effort_);
    const double rate = joint_->GetVelocity(0);
    bus_->rotor_speed_rad_s[motor_number_] = rate;
    if (speed_pub_ && speed_pub_.getNumSubscribers() > 0) {
      std_msgs::Float32 msg;
      msg.data = static_cast<float>(rate);
      speed_pub_.publish(msg);
    }
  }

  void PublishEffort() {
    if (!force_pub_ || force_pub_.getNumSubscribers() == 0) return;
    std_msgs::Float32 msg;
    msg.data = static_cast<float>(applied_effort_);
    force_pub_.publish(msg);
  }

  void OnServoUpdate() {
    const auto& cmd = bus_->motor_command_rad_s;
    // before the first command the servo holds its zero angle (as RotorS' zero-filled command)
    const double theta_ref = motor_number_ < static_cast<int>(cmd.size()) ? cmd[motor_number_] : 0.0;
    const double theta = joint_->Position(0);
    applied_effort_ = servo_->Torque(theta, theta_ref, dt_s_);
    joint_->SetForce(0, applied_effort_);
    bus_->rotor_speed_rad_s[motor_number_] = theta;
    if (speed_pub_ && speed_pub_.getNumSubscribers() > 0) {
      std_msgs::Float32 msg;
      msg.data = static_cast<float>(theta);
      speed_pub_.publish(msg);
    }
  }

  void OnRotorUpdate(double t_s) {
    // Forces from the speed reached in the last step (the one-step lag of RotorS, ref. 4.1).
    const auto X_WR = link_->WorldPose();
    const Eigen::Vector3d airspeed_W = ToEigen(link_->WorldLinearVel()) - bus_->wind_velocity_W;
    const Eigen::Vector3d airspeed_R = ToEigen(X_WR.Rot().RotateVectorReverse(FromEigen(airspeed_W)));
    const RotorWrench w = rotor_->ComputeWrench(airspeed_R);
    link_->AddRelativeForce(FromEigen(w.thrust_R + w.drag_R));
    parent_link_->AddTorque(X_WR.Rot().RotateVector(FromEigen(w.reaction_moment_R + w.rolling_moment_R)));

    const auto& cmd = bus_->motor_command_rad_s;
    // an injected fault scales what the motor makes of its command (0: failed)
    const double omega_cmd = (motor_number_ < static_cast<int>(cmd.size()) ? cmd[motor_number_] : 0.0) *
                             bus_->SpeedFactor(motor_number_, t_s);
    rotor_->UpdateSpeed(omega_cmd, dt_s_);
    bus_->rotor_speed_rad_s[motor_number_] = rotor_->SignedOmega();
    // The joint spins slowed down only so that rviz shows it without aliasing; the physics and
    // every published value use the real speed.
    joint_->SetVelocity(0, rotor_->SignedOmega() / slowdown_);

    if (speed_pub_ && speed_pub_.getNumSubscribers() > 0) {
      std_msgs::Float32 msg;
      msg.data = static_cast<float>(rotor_->SignedOmega());
      speed_pub_.publish(msg);
    }
  }

  std::string namespace_;
  int motor_number_ = 0;
  double slowdown_ = 10.0;
  double dt_s_ = 0.001;
  std::unique_ptr<RotorModel> rotor_;      ///< a rotor (motorType velocity), or
  std::unique_ptr<TiltServoModel> servo_;  ///< a servo (motorType position), or neither: an effort motor
  double max_force_ = std::numeric_limits<double>::infinity();
  double applied_effort_ = 0.0;  ///< the joint effort of the last step [N m or N]
  rotors_sim::ListenedPublisher force_pub_;
  rotors_sim::physics::JointPtr joint_;
  rotors_sim::physics::LinkPtr link_, parent_link_;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher speed_pub_;  ///< rotor speed [rad/s] or servo angle [rad]
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMotorModel)
