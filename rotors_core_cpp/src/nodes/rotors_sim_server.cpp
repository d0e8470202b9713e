// The simulator process (gzserver's role): rotors_sim_server <world file> [-u] [--rtf X]
//   -u         start paused (as gzserver -u)
//   --rtf X    real-time factor, 0 = as fast as possible (default: the world's)
//   --lockstep A1[:I1],A2[:I2]   lockstep participants: answer topic A (header-stamped), answering
//              the simulator's input topic I (see rotors_core/ros/lockstep.h)
//   --skip-broken-sensors  a camera that cannot be built is left out (one line says why) instead
//                          of failing its model
//   --lockstep-lenient   wait only for connected participants, mute silent ones (earlier versions)
// Private parameters ~world_name, ~paused and ~real_time_factor do the same. Further parameters:
//   ~state_publish_rate   [Hz sim] TF, joint_states, model_states (100)
//   ~state_max_wall_rate  [Hz wall] and at most this often (100; <= 0: no limit)
//   ~clock_max_wall_rate  [Hz wall] /clock to other processes at most this often (1000; <= 0: every step)
// The simulator also hosts nodelets (/gazebo/load_nodelet; see rotors_core/ros/nodelet_host.h).
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include <ros/package.h>
#include <ros/ros.h>

#include "rotors_core/error.h"
#include "rotors_core/geometry/uri_resolver.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/ros/sim_server.h"

namespace {
/// SIGINT/SIGTERM stop the stepping at once; ROS shuts down after the world and its bag closed.
void OnStopSignal(int) { rotors_sim::SimServer::RequestStop(); }

/// The whole of `text` as a finite number.
bool ParseNumber(const char* text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(*value);
}
}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // console lines reach a launch's log as they happen
  ros::init(argc, argv, "gazebo", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
  // model:// folders exported by packages (<gazebo_ros gazebo_model_path="${prefix}/models"/>), as gazebo_ros does
  std::vector<std::pair<std::string, std::string>> exports;
  ros::package::getPlugins("gazebo_ros", "gazebo_model_path", exports);
  for (const auto& e : exports) rotors_sim::geometry::UriResolver::AddModelPath(e.second);
  rotors_sim::SimServerOptions options;
  ros::NodeHandle nh, private_nh("~");
  private_nh.param("world_name", options.world_file, options.world_file);
  private_nh.param("paused", options.paused, options.paused);
  private_nh.param("real_time_factor", options.real_time_factor, options.real_time_factor);
  private_nh.param("state_publish_rate", options.state_publish_rate_hz, options.state_publish_rate_hz);
  private_nh.param("state_max_wall_rate", options.state_max_wall_rate_hz, options.state_max_wall_rate_hz);
  private_nh.param("clock_max_wall_rate", options.clock_max_wall_rate_hz, options.clock_max_wall_rate_hz);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-u") {
      options.paused = true;
    } else if (arg == "--rtf" && i + 1 < argc) {
      // -1: the world's own pacing (the launch files' default); 0: as fast as possible
      if (!ParseNumber(argv[++i], &options.real_time_factor) ||
          !(options.real_time_factor >= 0.0 || options.real_time_factor == -1.0)) {
        std::cerr << "[rotors_sim] error: --rtf '" << argv[i]
                  << "' must be a finite number >= 0 (0: as fast as possible) or -1 (the world's own)\n";
        return 2;
      }
    } else if (arg == "--step-size" && i + 1 < argc) {
      if (!ParseNumber(argv[++i], &options.step_size_s) || !(options.step_size_s > 0.0 && options.step_size_s <= 0.1)) {
        std::cerr << "[rotors_sim] error: --step-size '" << argv[i] << "' must be a physics step in (0, 0.1] s\n";
        return 2;
      }
    } else if (arg == "--lockstep" && i + 1 < argc) {
      try {
        options.lockstep_participants = rotors_sim::ParseLockstepParticipants(argv[++i]);
      } catch (const std::invalid_argument& e) {
        std::cerr << "[rotors_sim] error: " << e.what() << "\n";
        return 2;
      }
    } else if (arg == "--skip-broken-sensors") {
      options.skip_broken_sensors = true;
    } else if (arg == "--no-shadows") {
      options.shadows = false;
    } else if (arg == "--lockstep-lenient") {
      options.lockstep.mode = rotors_sim::LockstepOptions::Mode::kLenient;
    } else if (!arg.empty() && arg[0] != '-') {
      options.world_file = arg;
    } else {
      std::cerr << "[rotors_sim] error: unknown option '" << arg
                << "' (usage: rotors_sim_server <world> [-u] [--rtf X] [--step-size S] [--lockstep A1[:I1],A2[:I2]] "
                   "[--lockstep-lenient] [--skip-broken-sensors] [--no-shadows])\n";
      return 2;
    }
  }
  if (options.world_file.empty()) {
    std::cerr << "[rotors_sim] error: no world file given (usage: rotors_sim_server <world> [-u] [--rtf X] "
                 "[--step-size S] [--lockstep "
                 "A1[:I1],A2[:I2]] [--lockstep-lenient] [--skip-broken-sensors] [--no-shadows])\n";
    return 2;
  }
  try {
    rotors_sim::SimServer server(nh, private_nh, options);
    server.Run();
  } catch (const std::exception& e) {
    std::cerr << "[rotors_sim] error: " << e.what() << std::endl;
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
