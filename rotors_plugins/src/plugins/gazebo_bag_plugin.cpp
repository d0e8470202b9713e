// librotors_gazebo_bag_plugin.so (reference section 4.7): writes a bag from inside the simulator,
// stamped with sim time. Every step: <ns>/ground_truth/pose (PoseStamped), <ns>/ground_truth/twist
// (TwistStamped, world frame), <ns>/motor_speed (Actuators, signed real speeds), <ns>/wrench (one
// WrenchStamped per contact of the model). Re-recorded from ROS: imu, odometry, commands, wind,
// and any topics of any type listed in <extraTopics> (ours; e.g. an estimator's output).
// Ours: <ns>/simulation_status (rotors_comm/SimulationStatus) when the simulation is paused, resumes
// or stops, so that the evaluation knows where the flight ended, and at the first step lockstep did
// not wait for (with the count of such steps), so that it knows whether the flight is repeatable.
// Ours: <ns>/robot_description (std_msgs/String), the vehicle's robot description as the parameter
// server holds it, at the bag's start: the calibration, noise figures and sensor parameters of the
// vehicle flown (export_euroc.py reads them).
// File: <ROS_HOME or ~/.ros>/<bagFileName>_YYYY-MM-DD-HH-MM-SS.bag; service record_rosbag.
#include <ctime>
#include <sstream>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <mav_msgs/Actuators.h>
#include <mav_msgs/AttitudeThrust.h>
#include <mav_msgs/RateThrust.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rotors_comm/RecordRosbag.h>
#include <rotors_comm/SimulationStatus.h>
#include <rotors_comm/WindSpeed.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/String.h>
#include <topic_tools/shape_shifter.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/ros/msg_conversions.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboBagPlugin : public rotors_sim::ModelPlugin {
 public:
  ~GazeboBagPlugin() override { Close(); }

  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    ns_ = ReadRobotNamespace(Params());
    std::string link_name = "base_link", service = "record_rosbag";
    bool wait_to_record = false;
    ReadParam(Params(), "bagFileName", &bag_name_);
    ReadParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "frameId", &frame_id_);
    ReadParam(Params(), "poseTopic", &pose_topic_);
    ReadParam(Params(), "twistTopic", &twist_topic_);
    ReadParam(Params(), "motorTopic", &motor_topic_);
    ReadParam(Params(), "wrenchesTopic", &wrench_topic_);
    ReadParam(Params(), "recordingServiceName", &service);
    ReadParam(Params(), "waitToRecordBag", &wait_to_record);
    double slowdown = 10;
    ReadParam(Params(), "rotorVelocitySlowdownSim", &slowdown);  // accepted for compatibility: speeds come unslowed
    link_ = RequireLink(model, link_name);
    model_ = model.get();
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*model->GetWorldRaw(), ns_);
    bus_->Register(this, MeasuringRecord{"bag"});
    node_ = MakeNode(ns_);
    if (!node_) {  // no ROS, no bag: its topics are not needed
      for (const char* name : {"imuTopic", "odometryTopic", "commandAttitudeThrustTopic", "commandMotorSpeedTopic",
                               "commandRateThrustTopic", "windSpeedTopic", "externalForceTopic", "waypointTopic",
                               "commandPoseTopic", "extraTopics"})
        Params().Accept(name, "recorded from ROS, which this process does not run");
      return;
    }
    std::string t;
    auto topic = [&](const char* param, const char* fallback) {
      t = fallback;
      ReadParam(Params(), param, &t);
      return t;
    };
    Record<sensor_msgs::Imu>(topic("imuTopic", "imu"));
    Record<nav_msgs::Odometry>(topic("odometryTopic", "odometry_sensor1/odometry"));
    Record<mav_msgs::AttitudeThrust>(topic("commandAttitudeThrustTopic", "command/attitude_thrust"));
    Record<mav_msgs::Actuators>(topic("commandMotorSpeedTopic", "command/motor_speed"));
    Record<mav_msgs::RateThrust>(topic("commandRateThrustTopic", "command/rate_thrust"));
    Record<rotors_comm::WindSpeed>(topic("windSpeedTopic", "wind_speed"));
    Record<geometry_msgs::WrenchStamped>(topic("externalForceTopic", "external_force"));
    Record<trajectory_msgs::MultiDOFJointTrajectory>(topic("waypointTopic", "command/trajectory"));
    Record<geometry_msgs::PoseStamped>(topic("commandPoseTopic", "command/pose"));
    std::istringstream extra(topic("extraTopics", ""));
    for (std::string name; extra >> name;) Record<topic_tools::ShapeShifter>(name);  // whatever type they carry
    service_ = node_->advertiseService(service, &GazeboBagPlugin::OnRecord, this);
    if (!wait_to_record) Open();
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
    pause_connection_ = rotors_sim::event::Events::ConnectPause([this](bool paused) {
      WriteStatus(paused ? rotors_comm::SimulationStatus::PAUSED : rotors_comm::SimulationStatus::RUNNING);
    });
    stop_connection_ = rotors_sim::event::Events::ConnectStop([this] {
      WriteStatus(rotors_comm::SimulationStatus::STOPPED);
      Close();
    });
  }

 private:
  template <typename MsgT>
  void Record(const std::string& topic) {
    const std::string bag_topic = ns_ + "/" + topic;
    subs_.push_back(node_->subscribe<MsgT>(topic, 100, [this, bag_topic](const boost::shared_ptr<const MsgT>& msg) {
      if (recording_) Write(bag_topic, ToRos(world_->SimTime()), *msg);
    }));
  }

  /// Writes one message; rosbag refuses time 0 (messages received while paused at the start), so
  /// those get the earliest valid time. A failing write is reported and never stops the simulator.
  template <typename MsgT>
  void Write(const std::string& topic, const ros::Time& t, const MsgT& msg) {
    try {
      bag_.write(topic, std::max(t, ros::TIME_MIN), msg);
    } catch (const rosbag::BagException& e) {
      ROS_ERROR_THROTTLE(1.0, "[bag_plugin] cannot write %s to %s: %s", topic.c_str(), path_.c_str(), e.what());
    }
  }

  void Open() {
    if (recording_) return;
    const char* ros_home = std::getenv("ROS_HOME");
    const char* home = std::getenv("HOME");
    const std::string dir = ros_home ? ros_home : std::string(home ? home : ".") + "/.ros";
    std::string base = bag_name_;
    if (base.size() > 4 && base.compare(base.size() - 4, 4, ".bag") == 0) base.resize(base.size() - 4);
    char stamp[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof(stamp), "%Y-%m-%d-%H-%M-%S", std::localtime(&now));
    path_ = base.find('/') == 0 ? base + "_" + stamp + ".bag" : dir + "/" + base + "_" + stamp + ".bag";
    try {
      bag_.open(path_, rosbag::bagmode::Write);
    } catch (const rosbag::BagException& e) {
      throw rotors_sim::SimError("cannot open bag '" + path_ + "': " + e.what());
    }
    recording_ = true;
    ROS_INFO("[bag_plugin] recording %s", path_.c_str());
    std::string key;
    std_msgs::String description;
    if (node_->searchParam("robot_description", key) && node_->getParam(key, description.data))
      Write(ns_ + "/robot_description", ros::TIME_MIN, description);
  }

  void Close() {
    if (!recording_) return;
    recording_ = false;
    bag_.close();
    ROS_INFO("[bag_plugin] closed %s", path_.c_str());
  }

  void WriteStatus(uint8_t state) {
    if (!recording_) return;
    rotors_comm::SimulationStatus status;
    status.header.stamp = ToRos(world_->SimTime());
    status.state = state;
    status.reason = state == rotors_comm::SimulationStatus::STOPPED ? "simulator shut down" : world_->PauseReason();
    status.unwaited_steps = world_->UnwaitedSteps();
    if (status.unwaited_steps > 0)
      status.reason +=
          std::string(status.reason.empty() ? "" : "; ") + "not repeatable: " + world_->FirstUnwaitedReason();
    Write(ns_ + "/simulation_status", status.header.stamp, status);
  }

  bool OnRecord(rotors_comm::RecordRosbag::Request& req, rotors_comm::RecordRosbag::Response& res) {
    try {
      req.record ? Open() : Close();
      res.success = true;
    } catch (const std::exception& e) {
      ROS_ERROR("[bag_plugin] %s", e.what());
      res.success = false;
    }
    return true;
  }

  void OnUpdate() {
    if (!recording_) return;
    // the first step lockstep did not wait for: from here the flight depends on wall-clock timing
    if (world_->UnwaitedSteps() > 0 && !unwaited_reported_) {
      WriteStatus(rotors_comm::SimulationStatus::RUNNING);
      unwaited_reported_ = true;
    }
    const ros::Time stamp = ToRos(world_->SimTime());
    const auto X = link_->WorldPose();
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = stamp;
    pose.header.frame_id = frame_id_;
    pose.pose = rotors_sim::PoseMsg(X);
    Write(ns_ + "/" + pose_topic_, stamp, pose);
    geometry_msgs::TwistStamped twist;
    twist.header = pose.header;
    twist.twist = rotors_sim::TwistMsg(link_->WorldLinearVel(), link_->WorldAngularVel());
    Write(ns_ + "/" + twist_topic_, stamp, twist);
    mav_msgs::Actuators motors;
    motors.header = pose.header;
    motors.angular_velocities = bus_->rotor_speed_rad_s;
    Write(ns_ + "/" + motor_topic_, stamp, motors);
    for (const auto& c : world_->Contacts()) {
      const bool first = c.link1 && c.link1->GetModel() == model_;
      const bool second = c.link2 && c.link2->GetModel() == model_;
      if (!first && !second) continue;
      const auto& f = first ? c.force1_W : c.force2_W;
      const auto& tau = first ? c.torque1_W : c.torque2_W;
      if (f.Length() <= 1e-10) continue;
      geometry_msgs::WrenchStamped wrench;
      wrench.header.stamp = stamp;
      wrench.header.frame_id = c.collision1 + "--" + c.collision2;
      wrench.wrench.force = rotors_sim::Vector3Msg(f);
      wrench.wrench.torque = rotors_sim::Vector3Msg(tau);
      Write(ns_ + "/" + wrench_topic_, stamp, wrench);
    }
  }

  std::string ns_, bag_name_ = "simulator.bag", frame_id_ = "ground_truth_pose", path_;
  std::string pose_topic_ = "ground_truth/pose", twist_topic_ = "ground_truth/twist", motor_topic_ = "motor_speed",
              wrench_topic_ = "wrench";
  bool recording_ = false;
  bool unwaited_reported_ = false;
  rosbag::Bag bag_;
  rotors_sim::physics::Model* model_ = nullptr;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  std::shared_ptr<ros::NodeHandle> node_;
  std::vector<ros::Subscriber> subs_;
  ros::ServiceServer service_;
  rotors_sim::event::ConnectionPtr connection_, pause_connection_, stop_connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboBagPlugin)
