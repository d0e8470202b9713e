#include "rotors_gazebo_plugins/vehicle_bus.h"

#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "rotors_core/physics/world.h"

namespace rotors_gazebo_plugins {
namespace {
using Buses = std::map<std::string, std::weak_ptr<VehicleBus>>;

/// The world's buses by namespace, kept in the world.
Buses& BusesOf(rotors_sim::physics::World& world) {
  std::shared_ptr<void>& state = world.PluginState("rotors_gazebo_plugins/vehicle_buses");
  if (!state) state = std::make_shared<Buses>();
  return *std::static_pointer_cast<Buses>(state);
}
}  // namespace

std::shared_ptr<VehicleBus> VehicleBus::For(rotors_sim::physics::World& world, const std::string& robot_namespace) {
  std::weak_ptr<VehicleBus>& entry = BusesOf(world)[robot_namespace];
  std::shared_ptr<VehicleBus> bus = entry.lock();
  if (!bus) {  // first plugin of this vehicle, or the last holder of the previous one is gone
    bus = std::make_shared<VehicleBus>();
    VehicleBus* raw = bus.get();
    bus->reset_connection_ = world.Events().world_reset.Connect([raw] { raw->sensors.Forget(); });
    entry = bus;
  }
  return bus;
}

void VehicleBus::RegisterRotor(int motor_number, double max_rot_velocity) {
  if (motor_number + 1 > rotor_count) rotor_count = motor_number + 1;
  rotor_speed_rad_s.resize(rotor_count, 0.0);
  motor_faults.resize(rotor_count);
  is_servo.resize(rotor_count, false);
  max_rot_velocity_rad_s.resize(rotor_count, 0.0);
  max_rot_velocity_rad_s[motor_number] = max_rot_velocity;
  rotor_mountings.resize(rotor_count);
}

void VehicleBus::RegisterRotorMounting(int motor_number, const RotorMounting& mounting) {
  if (motor_number >= rotor_count) RegisterRotor(motor_number);
  rotor_mountings[motor_number] = mounting;
}

std::string VehicleBus::SetRcChannels(const std::vector<int>& channels_us) {
  std::ostringstream why;
  if (channels_us.size() > 16) {
    why << "has " << channels_us.size() << " RC channels; at most 16 are forwarded";
    return why.str();
  }
  for (size_t i = 0; i < channels_us.size(); ++i)
    if (channels_us[i] < 800 || channels_us[i] > 2200) {
      why << "RC channel " << i + 1 << " = " << channels_us[i] << " us is outside 800..2200 us";
      return why.str();
    }
  rc_channels_us = channels_us;
  ++rc_count;
  return {};
}

void VehicleBus::RegisterServo(int motor_number) {
  RegisterRotor(motor_number);
  is_servo[motor_number] = true;
}

std::string VehicleBus::SetMotorCommand(const std::vector<double>& speeds_rad_s) {
  std::ostringstream why;
  if (static_cast<int>(speeds_rad_s.size()) != rotor_count) {
    why << "has " << speeds_rad_s.size() << " angular_velocities, the vehicle has " << rotor_count << " motors";
    return why.str();
  }
  for (size_t i = 0; i < speeds_rad_s.size(); ++i) {
    if (is_servo[i]) {
      if (!std::isfinite(speeds_rad_s[i])) {
        why << "angular_velocities[" << i << "] = " << speeds_rad_s[i] << " must be a finite servo angle [rad]";
        return why.str();
      }
    } else if (!std::isfinite(speeds_rad_s[i]) || speeds_rad_s[i] < 0.0) {
      why << "angular_velocities[" << i << "] = " << speeds_rad_s[i] << " must be a finite speed >= 0 rad/s";
      return why.str();
    }
  }
  motor_command_rad_s = speeds_rad_s;
  ++motor_command_count;
  return {};
}

std::string VehicleBus::SetNormalizedCommand(const std::vector<double>& normalized) {
  std::ostringstream why;
  if (normalized_channels == 0) return "is for a fixed wing; this vehicle has no fixed-wing plugin";
  if (static_cast<int>(normalized.size()) < normalized_channels) {
    why << "has " << normalized.size() << " normalized values, the vehicle reads " << normalized_channels
        << " channels";
    return why.str();
  }
  for (size_t i = 0; i < normalized.size(); ++i)
    if (!std::isfinite(normalized[i])) {
      why << "normalized[" << i << "] = " << normalized[i] << " must be finite";
      return why.str();
    }
  if (normalized_check) {
    const std::string why_not = normalized_check(normalized);
    if (!why_not.empty()) return why_not;
  }
  normalized_command = normalized;
  ++normalized_command_count;
  return {};
}

}  // namespace rotors_gazebo_plugins
