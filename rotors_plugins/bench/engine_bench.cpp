// Engine-only benchmark: a world with N models loaded from a URDF with all their plugins, no ROS
// (plugins skip publishing when ROS is not initialised), motors held at the hover command, in
// free flight (the world file gives the physics settings; no ground, so no contacts).
//   rotors_engine_bench <world.sdf> <model.urdf> <namespace> <step_s> <sim_seconds> <hover_rad_s> [--ros]
// --ros: initialise ROS first (needs a master), so the plugins publish as in the simulator.
// Prints one JSON line: steps, wall seconds, steps per second, real-time factor.
#include <chrono>
#include <string>

#include <ros/ros.h>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "rotors_core/model_builder.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

int main(int argc, char** argv) {
  const bool with_ros = argc == 8 && std::string(argv[7]) == "--ros";
  if (with_ros) {
    int ros_argc = 1;
    ros::init(ros_argc, argv, "rotors_engine_bench",
              ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
    ros::start();
  }
  if (argc != 7 && !with_ros) {
    std::cerr << "usage: rotors_engine_bench <world> <model.urdf> <namespace> <step_s> <sim_seconds> <hover_rad_s>\n";
    return 2;
  }
  try {
    auto world_params = rotors_sim::WorldLoader::LoadFile(argv[1])->Physics();
    world_params.max_step_size_s = std::stod(argv[4]);
    if (const char* solver = std::getenv("ROTORS_BENCH_SOLVER"))
      world_params.quick_solver = std::string(solver) == "quick";
    if (const char* iters = std::getenv("ROTORS_BENCH_ITERS")) world_params.quick_iterations = std::atoi(iters);
    auto world = rotors_sim::physics::World::Create("bench", world_params);
    std::ifstream f(argv[2]);
    std::stringstream xml;
    xml << f.rdbuf();
    rotors_sim::SpawnRequest request{xml.str(), argv[3], rotors_sim::physics::Pose3d(0, 0, 1000, 0, 0, 0)};
    auto model = rotors_sim::ModelBuilder::Spawn(world, request);
    auto bus = rotors_gazebo_plugins::VehicleBus::For(*world, argv[3]);  // the model's plugins hold it
    bus->motor_command_rad_s.assign(bus->rotor_count, std::stod(argv[6]));
    const auto steps = static_cast<long>(std::stod(argv[5]) / world_params.max_step_size_s);
    const auto t0 = std::chrono::steady_clock::now();
    world->Step(static_cast<unsigned>(steps));
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "{\"steps\": " << steps << ", \"wall_s\": " << wall << ", \"steps_per_s\": " << steps / wall
              << ", \"real_time_factor\": " << steps * world_params.max_step_size_s / wall
              << ", \"plugins\": " << model->Plugins().size() << ", \"ros\": " << (with_ros ? "true" : "false") << "}"
              << std::endl;
    world->Fini();
  } catch (const std::exception& e) {
    std::cerr << "rotors_engine_bench: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
