#include "rotors_core/ros/sim_server.h"

#include <cmath>

#include <ros/callback_queue.h>

#include <csignal>
#include <rosgraph_msgs/Clock.h>

#include "rotors_core/error.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "rotors_core/ros/msg_conversions.h"
#include "rotors_core/ros/world_markers.h"

namespace rotors_sim {
namespace {
volatile std::sig_atomic_t g_stop_requested = 0;
}  // namespace

void SimServer::RequestStop() { g_stop_requested = 1; }

SimServer::SimServer(ros::NodeHandle nh, ros::NodeHandle private_nh, const SimServerOptions& options)
    : nh_(nh), private_nh_(private_nh), user_paused_(options.paused), clock_limit_(options.clock_max_wall_rate_hz) {
  WorldLoadOptions load;
  // RotorS' worlds load its ROS bridge plugin; here every plugin talks ROS itself
  load.skipped_plugins["librotors_gazebo_ros_interface_plugin.so"] = "not needed, plugins publish on ROS directly";
  load.skip_broken_sensors = skip_broken_sensors_ = options.skip_broken_sensors;
  load.shadows = options.shadows;
  world_ = WorldLoader::LoadFile(options.world_file, load);
  if (options.real_time_factor >= 0.0) world_->SetRealTimeFactor(options.real_time_factor);
  if (options.step_size_s > 0.0) world_->SetMaxStepSize(options.step_size_s);
  pacer_.SetRealTimeFactor(world_->Physics().real_time_factor);
  pacer_.Restart(world_->SimTime());
  state_publisher_ =
      std::make_unique<StatePublisher>(nh_, options.state_publish_rate_hz, options.state_max_wall_rate_hz);
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  world_markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("/world/markers", 1, true);
  lockstep_ =
      std::make_unique<Lockstep>(nh_, options.lockstep_participants, options.lockstep, PublishCounts::Of(*world_));
  world_->SetPaused(true, user_paused_ ? "started paused" : "starting");
  services_.push_back(private_nh_.advertiseService("pause_physics", &SimServer::OnPause, this));
  services_.push_back(private_nh_.advertiseService("unpause_physics", &SimServer::OnUnpause, this));
  services_.push_back(private_nh_.advertiseService("reset_world", &SimServer::OnResetWorld, this));
  services_.push_back(private_nh_.advertiseService("reset_simulation", &SimServer::OnResetSimulation, this));
  services_.push_back(private_nh_.advertiseService("spawn_urdf_model", &SimServer::OnSpawn, this));
  services_.push_back(private_nh_.advertiseService("spawn_sdf_model", &SimServer::OnSpawn, this));
  services_.push_back(private_nh_.advertiseService("delete_model", &SimServer::OnDelete, this));
  services_.push_back(private_nh_.advertiseService("get_model_state", &SimServer::OnGetModelState, this));
  services_.push_back(private_nh_.advertiseService("set_model_state", &SimServer::OnSetModelState, this));
  nodelets_ = std::make_unique<NodeletHost>(private_nh_, ros::getGlobalCallbackQueue());
  clock_flush_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
    if (world_->SimTime().Nanoseconds() != clock_published_ns_) PublishClock(true);
  });
  ROS_INFO("[rotors_sim] world '%s' loaded from %s: step %.4f s, real-time factor %g%s, %s", world_->Name().c_str(),
           options.world_file.c_str(), world_->Physics().max_step_size_s, world_->Physics().real_time_factor,
           world_->Physics().real_time_factor == 0.0 ? " (as fast as possible)" : "",
           user_paused_ ? "paused" : "running");
  PublishClock(true);
  PublishWorldMarkers();
}

void SimServer::PublishWorldMarkers() {
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  for (auto& m : WorldMarkers(*world_, "world").markers) markers.markers.push_back(std::move(m));
  world_markers_pub_.publish(markers);
}

SimServer::~SimServer() {
  services_.clear();
  nodelets_.reset();
  if (world_) {
    ROS_INFO("[rotors_sim] stopped at t = %.3f s", world_->SimTime().Double());
    world_->Fini();
  }
}

void SimServer::PublishClock(bool force) {
  rosgraph_msgs::Clock clock;
  clock.clock.fromNSec(world_->SimTime().Nanoseconds());
  if (ros::Time::isSimTime()) ros::Time::setNow(clock.clock);
  if (!force && !clock_limit_.Due()) return;
  clock_pub_.publish(clock);
  clock_published_ns_ = world_->SimTime().Nanoseconds();
}

void SimServer::StepOnce() {
  lockstep_->BeforeStep();
  world_->Step();
  PublishClock();
  state_publisher_->Update(*world_);
  if (lockstep_->Enabled()) {
    ros::Time now;
    now.fromNSec(world_->SimTime().Nanoseconds());
    if (!lockstep_->WaitForAnswers(now, ros::getGlobalCallbackQueue(), [] { return g_stop_requested != 0; }))
      UpdateRunState();
    if (lockstep_->UnwaitedSteps() != world_->UnwaitedSteps())
      world_->SetUnwaitedSteps(lockstep_->UnwaitedSteps(), lockstep_->FirstUnwaitedReason());
  }
  pacer_.WaitUntilDue(world_->SimTime());
}

bool SimServer::UpdateRunState() {
  const std::string held = user_paused_ ? "" : lockstep_->HoldReason(world_->SimTime().Double());
  const bool paused = user_paused_ || !held.empty();
  if (!paused && world_->IsPaused()) pacer_.Restart(world_->SimTime());
  world_->SetPaused(paused, user_paused_ ? "paused by pause_physics" : held);
  return !paused;
}

void SimServer::Run() {
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  while (ros::ok() && !g_stop_requested) {
    queue->callAvailable();
    if (UpdateRunState()) {
      StepOnce();
      continue;
    }
    queue->callAvailable(ros::WallDuration(0.05));
    // late subscribers (rostopic, rviz) still learn the frozen time and poses while paused
    PublishClock(true);
    state_publisher_->Update(*world_, true);
  }
}

bool SimServer::OnPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  user_paused_ = true;
  ROS_INFO("[rotors_sim] physics paused at t = %.3f s", world_->SimTime().Double());
  return true;
}

bool SimServer::OnUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  user_paused_ = false;
  ROS_INFO("[rotors_sim] physics running from t = %.3f s", world_->SimTime().Double());
  return true;
}

bool SimServer::OnResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->ResetWorld();
  state_publisher_->Update(*world_, true);
  return true;
}

bool SimServer::OnResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->ResetSimulation();
  lockstep_->Rewind(ros::Time().fromNSec(world_->SimTime().Nanoseconds()));
  pacer_.Restart(world_->SimTime());
  PublishClock(true);
  state_publisher_->Update(*world_, true);
  return true;
}

bool SimServer::OnSpawn(gazebo_msgs::SpawnModel::Request& req, gazebo_msgs::SpawnModel::Response& res) {
  const auto& p = req.initial_pose;
  std::string refused;
  if (!req.reference_frame.empty() && req.reference_frame != "world" && req.reference_frame != "map")
    refused = "reference_frame '" + Abbreviated(req.reference_frame) + "' is not supported; use 'world'";
  else if (!std::isfinite(p.position.x + p.position.y + p.position.z + p.orientation.w + p.orientation.x +
                          p.orientation.y + p.orientation.z))
    refused = "initial_pose has NaN or inf";
  if (!refused.empty()) {
    res.success = false;
    res.status_message = refused;
    ROS_ERROR_THROTTLE(1.0, "[rotors_sim] spawn '%s': %s", Abbreviated(req.model_name).c_str(), refused.c_str());
    return true;
  }
  SpawnRequest spawn;
  spawn.xml = req.model_xml;
  spawn.model_name = req.model_name;
  spawn.skip_broken_sensors = skip_broken_sensors_;
  // normalised as set_model_state does (a hand-typed 0.707 quaternion is not a unit one); all zeros, as
  // rosservice call's default initial_pose has it, is the identity
  const auto& q = p.orientation;
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  spawn.X_WM = physics::Pose3d(
      physics::Vector3d(p.position.x, p.position.y, p.position.z),
      n > 1e-9 ? physics::Quaterniond(q.w / n, q.x / n, q.y / n, q.z / n) : ignition::math::Quaterniond::Identity);
  try {
    physics::ModelPtr model = ModelBuilder::Spawn(world_, spawn);
    res.success = true;
    res.status_message = "SpawnModel: Successfully spawned entity '" + model->GetName() + "'";
    ROS_INFO("[rotors_sim] %s (%zu links, %zu joints, %zu plugins)", res.status_message.c_str(),
             model->GetLinks().size(), model->GetJoints().size(), model->Plugins().size());
    state_publisher_->Update(*world_, true);
    lockstep_->Resubscribe();
    if (model->IsStatic()) PublishWorldMarkers();
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = Abbreviated(e.what(), 300);
    ROS_ERROR_THROTTLE(1.0, "[rotors_sim] spawn failed: %s", res.status_message.c_str());
  }
  return true;
}

bool SimServer::OnDelete(gazebo_msgs::DeleteModel::Request& req, gazebo_msgs::DeleteModel::Response& res) {
  res.success = world_->RemoveModel(req.model_name);
  if (res.success) PublishWorldMarkers();
  res.status_message = res.success ? "DeleteModel: successfully deleted model '" + req.model_name + "'"
                                   : "DeleteModel: there is no model named '" + req.model_name + "'";
  return true;
}

/// Gazebo's semantics: pose and twist of the model's frame in the relative model's frame (the world
/// frame when relative_entity_name is empty or "world"); the twist is expressed in that frame.
bool SimServer::OnGetModelState(gazebo_msgs::GetModelState::Request& req, gazebo_msgs::GetModelState::Response& res) {
  res.header.stamp.fromNSec(world_->SimTime().Nanoseconds());
  const physics::ModelPtr model = world_->ModelByName(req.model_name);
  if (!model) {
    res.success = false;
    res.status_message = "GetModelState: model '" + req.model_name + "' does not exist";
    return true;
  }
  physics::Pose3d X_WR;  // the relative entity's frame R in the world
  physics::Vector3d v_WR, w_WR;
  const bool in_world = req.relative_entity_name.empty() || req.relative_entity_name == "world";
  if (!in_world) {
    const physics::ModelPtr relative = world_->ModelByName(req.relative_entity_name);
    if (!relative) {
      res.success = false;
      res.status_message = "GetModelState: relative entity '" + req.relative_entity_name +
                           "' is not a model (give a model name, \"world\" or nothing)";
      return true;
    }
    X_WR = relative->WorldPose();
    v_WR = relative->WorldLinearVel();
    w_WR = relative->WorldAngularVel();
  }
  const physics::Pose3d X_WM = model->WorldPose();
  // X_RM = X_WR^-1 X_WM; velocities as differences, rotated into R (as gazebo_ros does)
  const physics::Pose3d X_RM = X_WM - X_WR;
  const physics::Vector3d v_R = X_WR.Rot().RotateVectorReverse(model->WorldLinearVel() - v_WR);
  const physics::Vector3d w_R = X_WR.Rot().RotateVectorReverse(model->WorldAngularVel() - w_WR);
  res.header.frame_id = in_world ? "world" : req.relative_entity_name;
  res.pose = PoseMsg(X_RM);
  res.twist = TwistMsg(v_R, w_R);
  res.success = true;
  res.status_message = "GetModelState: got properties";
  return true;
}

/// Gazebo's set_model_state for poses and twists in the world frame (reference_frame empty, "world"
/// or "map"); the model moves as one rigid body. Another reference frame is refused by name.
bool SimServer::OnSetModelState(gazebo_msgs::SetModelState::Request& req, gazebo_msgs::SetModelState::Response& res) {
  const gazebo_msgs::ModelState& s = req.model_state;
  const physics::ModelPtr model = world_->ModelByName(s.model_name);
  res.success = false;
  if (!model) {
    res.status_message = "SetModelState: model '" + s.model_name + "' does not exist";
    return true;
  }
  if (!(s.reference_frame.empty() || s.reference_frame == "world" || s.reference_frame == "map")) {
    res.status_message = "SetModelState: reference_frame '" + s.reference_frame +
                         "' is not supported (give \"world\", \"map\" or nothing: the world frame)";
    return true;
  }
  const auto& p = s.pose.position;
  const auto& q = s.pose.orientation;
  const auto& v = s.twist.linear;
  const auto& w = s.twist.angular;
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!std::isfinite(p.x + p.y + p.z + v.x + v.y + v.z + w.x + w.y + w.z) || !(n > 1e-9) || !std::isfinite(n)) {
    res.status_message = "SetModelState: the pose and twist must be finite and the quaternion non-zero";
    return true;
  }
  model->SetWorldPose(
      physics::Pose3d(physics::Vector3d(p.x, p.y, p.z), physics::Quaterniond(q.w / n, q.x / n, q.y / n, q.z / n)));
  model->SetWorldTwist(physics::Vector3d(v.x, v.y, v.z), physics::Vector3d(w.x, w.y, w.z));
  res.success = true;
  res.status_message = "SetModelState: set model state";
  return true;
}

}  // namespace rotors_sim
