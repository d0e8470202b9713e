// ROS face of the engine (what gazebo_ros is for Gazebo): /clock, the /gazebo/* services,
// TF, joint_states and model_states, and real-time pacing. Runs the world in this thread and
// serves ROS callbacks between steps, so plugin callbacks never race the physics.
#pragma once

#include <memory>
#include <string>

#include <gazebo_msgs/DeleteModel.h>
#include <gazebo_msgs/GetModelState.h>
#include <gazebo_msgs/SetModelState.h>
#include <gazebo_msgs/SpawnModel.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/ros/lockstep.h"
#include "rotors_core/ros/nodelet_host.h"
#include "rotors_core/ros/real_time_pacer.h"
#include "rotors_core/ros/state_publisher.h"

namespace rotors_sim {

struct SimServerOptions {
  std::string world_file;
  bool paused = false;
  double real_time_factor = -1.0;         ///< < 0: the world's own; 0: as fast as possible
  double step_size_s = 0.0;               ///< > 0: replaces the world's max_step_size (--step-size)
  double state_publish_rate_hz = 100.0;   ///< [Hz sim time] TF, joint_states, model_states
  double state_max_wall_rate_hz = 100.0;  ///< [Hz wall] and at most this often (<= 0: no limit)
  /// [Hz wall] /clock to other processes at most this often (<= 0: every step); this process's own
  /// nodes (plugins, nodelets) see every step's time
  double clock_max_wall_rate_hz = 1000.0;
  std::vector<LockstepParticipant> lockstep_participants;  ///< see Lockstep; empty: free running
  LockstepOptions lockstep;
  bool skip_broken_sensors = false;  ///< models load without a sensor that cannot be built (SpawnRequest)
  bool shadows = true;               ///< false: no shadows whatever the world says (WorldLoadOptions)
};

class SimServer {
 public:
  /// Loads the world; throws SimError.
  SimServer(ros::NodeHandle nh, ros::NodeHandle private_nh, const SimServerOptions& options);
  ~SimServer();

  /// Steps and serves callbacks until ROS shuts down or RequestStop() was called.
  void Run();
  /// Async-signal-safe: the simulation takes no further step (call from a SIGINT handler, so
  /// that the world and its bag stop at once instead of stepping on while ROS shuts down).
  static void RequestStop();
  physics::WorldPtr World() const { return world_; }

 private:
  void StepOnce();
  /// Sets this process's time; publishes /clock when `force` or the wall-time limit allows.
  void PublishClock(bool force = false);
  /// Paused by a user (pause_physics, -u) or held by lockstep; tells the world (and its plugins)
  /// on every change. True when the world may step.
  bool UpdateRunState();
  bool OnPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnSpawn(gazebo_msgs::SpawnModel::Request& req, gazebo_msgs::SpawnModel::Response& res);
  bool OnDelete(gazebo_msgs::DeleteModel::Request& req, gazebo_msgs::DeleteModel::Response& res);
  bool OnGetModelState(gazebo_msgs::GetModelState::Request& req, gazebo_msgs::GetModelState::Response& res);
  bool OnSetModelState(gazebo_msgs::SetModelState::Request& req, gazebo_msgs::SetModelState::Response& res);

  ros::NodeHandle nh_, private_nh_;
  physics::WorldPtr world_;
  bool user_paused_;
  bool skip_broken_sensors_ = false;
  RealTimePacer pacer_;
  std::unique_ptr<StatePublisher> state_publisher_;
  std::unique_ptr<Lockstep> lockstep_;
  ros::Publisher clock_pub_;
  WallRateLimit clock_limit_;
  int64_t clock_published_ns_ = -1;  ///< the last time /clock carried
  /// Publishes the time a step left unpublished (the wall-time limit) once the simulation stands
  /// still, e.g. while lockstep waits for a controller: others see where it stopped.
  ros::WallTimer clock_flush_timer_;
  ros::Publisher world_markers_pub_;  ///< latched /world/markers: static models for rviz
  void PublishWorldMarkers();
  std::vector<ros::ServiceServer> services_;
  std::unique_ptr<NodeletHost> nodelets_;  ///< nodes run in this process (in_process:=true)
};

}  // namespace rotors_sim
