#include "rotors_gazebo_plugins/vehicle_bus.h"

#include <map>
#include <memory>

namespace rotors_gazebo_plugins {
namespace {
std::map<std::string, std::unique_ptr<VehicleBus>>& Buses() {
  static std::map<std::string, std::unique_ptr<VehicleBus>> buses;
  return buses;
}
}  // namespace

VehicleBus& VehicleBus::For(const std::string& robot_namespace) {
  auto& bus = Buses()[robot_namespace];
  if (!bus) bus = std::make_unique<VehicleBus>();
  return *bus;
}

void VehicleBus::Release(const std::string& robot_namespace) { Buses().erase(robot_namespace); }

void VehicleBus::RegisterRotor(int motor_number) {
  if (motor_number + 1 > rotor_count) rotor_count = motor_number + 1;
  rotor_speed_rad_s.resize(rotor_count, 0.0);
  motor_faults.resize(rotor_count);
}

}  // namespace rotors_gazebo_plugins
