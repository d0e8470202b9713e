// librotors_gazebo_gimbal_controller_plugin.so: RotorS' gimbal controller (its source was never
// compiled upstream; this one is). Holds the camera (the pitch joint's child link) at the commanded
// yaw, roll and pitch in the world, Z-X-Y Euler angles, whatever the MAV does: GimbalController's
// PID per axis gives each joint's torque. The attitude is the link's own, what an ideal IMU on it
// (RotorS' <imu>) measures.
// Parameters: <joint_yaw>, <joint_roll>, <joint_pitch> (RotorS' defaults cgo3_vertical_arm_joint,
// cgo3_horizontal_arm_joint, cgo3_camera_joint); optional <yaw_pid>, <roll_pid>, <pitch_pid> with
// Gazebo's PID elements (p, i, d, iMax, iMin, cmdMax, cmdMin). Commands [rad] (std_msgs/Float64,
// clamped to the joint's limits as RotorS does): gimbal_{yaw,roll,pitch}_cmd; the joint angles
// [rad] at 10 Hz on gimbal_{yaw,roll,pitch}_status. The commands start at <initial_yaw>,
// <initial_roll>, <initial_pitch> (ours; default 0: camera level, looking along the world's x axis).
#include <algorithm>
#include <array>

#include <Eigen/Geometry>
#include <std_msgs/Float64.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_gazebo_plugins/models/gimbal_controller.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

namespace {
/// Gazebo's PID elements below <name>, each optional over `defaults`.
TiltServoParams ReadPid(SdfParams& params, const std::string& name, TiltServoParams pid) {
  ReadGazeboPid(params, name, false, &pid);
  return pid;
}

TiltServoParams Pid(double p, double d, double max_torque) {
  TiltServoParams pid;
  pid.p = p;
  pid.d = d;
  pid.cmd_max = max_torque;
  pid.cmd_min = -max_torque;
  return pid;
}
}  // namespace

class GazeboGimbalControllerPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    const std::string ns = ReadRobotNamespace(Params());
    std::array<std::string, 3> joint_names = {"cgo3_vertical_arm_joint", "cgo3_horizontal_arm_joint",
                                              "cgo3_camera_joint"};
    ReadParam(Params(), "joint_yaw", &joint_names[0]);
    ReadParam(Params(), "joint_roll", &joint_names[1]);
    ReadParam(Params(), "joint_pitch", &joint_names[2]);
    const char* initial[3] = {"initial_yaw", "initial_roll", "initial_pitch"};
    for (int i = 0; i < 3; ++i) ReadParam(Params(), initial[i], &initial_ypr_[i]);
    Params().Accept("imu", "the camera's attitude is its link's, what an ideal IMU on it measures");
    // RotorS' gains by default (P 5, limit 0.3 N m for roll and pitch; P 1, limit 1 N m for yaw;
    // no D: they rely on the cgo3 model's joint damping). A frictionless gimbal needs a D term:
    // gimbal_camera_macro sets all three PIDs for its inertias.
    GimbalParams p;
    p.yaw = ReadPid(Params(), "yaw_pid", Pid(1.0, 0.0, 1.0));
    p.roll = ReadPid(Params(), "roll_pid", Pid(5.0, 0.0, 0.3));
    p.pitch = ReadPid(Params(), "pitch_pid", Pid(5.0, 0.0, 0.3));
    ThrowIfInvalid(p.Validate());
    controller_ = std::make_unique<GimbalController>(p);
    const char* params[3] = {"joint_yaw", "joint_roll", "joint_pitch"};
    for (int i = 0; i < 3; ++i) {
      joints_[i] = RequireJoint(model, joint_names[i], params[i]);
      if (joints_[i]->GetType() != rotors_sim::physics::Joint::Type::kRevolute)
        throw rotors_sim::SimError(std::string(params[i]) + " '" + joint_names[i] +
                                   "' must be a revolute or continuous joint");
    }
    camera_link_ = joints_[2]->GetChild();
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(initial_ypr_[i])) throw rotors_sim::SimError(std::string(initial[i]) + " must be finite");
      OnCommand(i, initial_ypr_[i]);
    }
    dt_s_ = model->GetWorldRaw()->Physics().max_step_size_s;
    world_ = model->GetWorldRaw();
    node_ = MakeNode(ns);
    const char* axes[3] = {"yaw", "roll", "pitch"};
    for (int i = 0; i < 3; ++i) {
      status_pubs_[i] =
          Advertise<std_msgs::Float64>(node_, ns, std::string("gimbal_") + axes[i] + "_status", *world_, 1);
      if (node_)
        subs_[i] = node_->subscribe<std_msgs::Float64>(
            std::string("gimbal_") + axes[i] + "_cmd", 1,
            [this, i](const std_msgs::Float64ConstPtr& msg) { OnCommand(i, msg->data); });
    }
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
        [this](const rotors_sim::common::UpdateInfo& info) { OnUpdate(info.simTime.Double()); });
  }

  void Reset() override {
    controller_->Reset();
    for (int i = 0; i < 3; ++i) OnCommand(i, initial_ypr_[i]);
  }

 private:
  void OnCommand(int axis, double angle_rad) {
    if (!std::isfinite(angle_rad)) {
      ROS_WARN_THROTTLE(1.0, "[gimbal_controller] ignoring a gimbal command of %f rad: it must be finite", angle_rad);
      return;
    }
    // clamped to the joint's limits, as RotorS does
    command_ypr_[axis] = std::clamp(angle_rad, joints_[axis]->LowerLimit(), joints_[axis]->UpperLimit());
  }

  void OnUpdate(double t_s) {
    const auto q = camera_link_->WorldPose().Rot();
    const Eigen::Matrix3d R_WC = Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()).toRotationMatrix();
    const Eigen::Vector3d torques = controller_->Torques(R_WC, command_ypr_, dt_s_);
    for (int i = 0; i < 3; ++i) joints_[i]->SetForce(0, torques[i]);
    if (t_s + 1e-9 < next_status_s_) return;
    next_status_s_ = t_s + kStatusPeriod_s;
    for (int i = 0; i < 3; ++i) {
      if (!status_pubs_[i] || status_pubs_[i].getNumSubscribers() == 0) continue;
      std_msgs::Float64 msg;
      msg.data = joints_[i]->Position(0);
      status_pubs_[i].publish(msg);
    }
  }

  static constexpr double kStatusPeriod_s = 0.1;
  std::unique_ptr<GimbalController> controller_;
  std::array<rotors_sim::physics::JointPtr, 3> joints_;  ///< yaw, roll, pitch
  rotors_sim::physics::LinkPtr camera_link_;
  Eigen::Vector3d command_ypr_ = Eigen::Vector3d::Zero();  ///< [rad]
  Eigen::Vector3d initial_ypr_ = Eigen::Vector3d::Zero();  ///< [rad]
  double dt_s_ = 0.001;
  double next_status_s_ = 0.0;
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<ros::NodeHandle> node_;
  std::array<ros::Subscriber, 3> subs_;
  std::array<rotors_sim::ListenedPublisher, 3> status_pubs_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboGimbalControllerPlugin)
