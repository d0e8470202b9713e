// The simulator process (gzserver's role): rotors_sim_server <world file> [-u] [--rtf X]
//   -u         start paused (as gzserver -u)
//   --rtf X    real-time factor, 0 = as fast as possible (default: the world's)
//   --lockstep T1,T2   wait each step for a header-stamped answer on these topics
// Private parameters ~world_name, ~paused and ~real_time_factor do the same.
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include <ros/ros.h>

#include "rotors_core/error.h"
#include "rotors_core/ros/sim_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "gazebo");
  rotors_sim::SimServerOptions options;
  ros::NodeHandle nh, private_nh("~");
  private_nh.param("world_name", options.world_file, options.world_file);
  private_nh.param("paused", options.paused, options.paused);
  private_nh.param("real_time_factor", options.real_time_factor, options.real_time_factor);
  private_nh.param("state_publish_rate", options.state_publish_rate_hz, options.state_publish_rate_hz);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-u") {
      options.paused = true;
    } else if (arg == "--rtf" && i + 1 < argc) {
      char* end = nullptr;
      options.real_time_factor = std::strtod(argv[++i], &end);
      if (*end != '\0') {
        std::cerr << "[rotors_sim] error: --rtf '" << argv[i] << "' is not a number\n";
        return 2;
      }
    } else if (arg == "--lockstep" && i + 1 < argc) {
      std::stringstream topics(argv[++i]);
      std::string topic;
      while (std::getline(topics, topic, ',')) if (!topic.empty()) options.lockstep_topics.push_back(topic);
    } else if (!arg.empty() && arg[0] != '-') {
      options.world_file = arg;
    } else {
      std::cerr << "[rotors_sim] error: unknown option '" << arg << "' (usage: rotors_sim_server <world> [-u] [--rtf X] [--lockstep T1,T2])\n";
      return 2;
    }
  }
  if (options.world_file.empty()) {
    std::cerr << "[rotors_sim] error: no world file given (usage: rotors_sim_server <world> [-u] [--rtf X] [--lockstep T1,T2])\n";
    return 2;
  }
  try {
    rotors_sim::SimServer server(nh, private_nh, options);
    server.Run();
  } catch (const std::exception& e) {
    std::cerr << "[rotors_sim] error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
