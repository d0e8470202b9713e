#include "rotors_gazebo_plugins/vehicle_bus.h"

#include <map>
#include <memory>

namespace rotors_gazebo_plugins {
namespace {
std::map<std::string, std::weak_ptr<VehicleBus>>& Buses() {
  static std::map<std::string, std::weak_ptr<VehicleBus>> buses;
  return buses;
}
}  // namespace

std::shared_ptr<VehicleBus> VehicleBus::For(const std::string& robot_namespace) {
  std::weak_ptr<VehicleBus>& entry = Buses()[robot_namespace];
  std::shared_ptr<VehicleBus> bus = entry.lock();
  if (!bus) {  // first plugin of this vehicle, or the last holder of the previous one is gone
    bus = std::make_shared<VehicleBus>();
    entry = bus;
  }
  return bus;
}

void VehicleBus::RegisterRotor(int motor_number) {
  if (motor_number + 1 > rotor_count) rotor_count = motor_number + 1;
  rotor_speed_rad_s.resize(rotor_count, 0.0);
  motor_faults.resize(rotor_count);
}

}  // namespace rotors_gazebo_plugins
