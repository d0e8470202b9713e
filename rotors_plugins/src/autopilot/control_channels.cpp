#include "rotors_gazebo_plugins/autopilot/control_channels.h"

#include <cmath>
#include <sstream>

#include "rotors_core/error.h"

namespace rotors_gazebo_plugins {

std::string ControlChannel::Validate(int input_count) const {
  std::ostringstream why;
  if (input_index < 0 || input_index >= input_count)
    why << "input_index " << input_index << " is outside the autopilot's " << input_count << " outputs (0.."
        << input_count - 1 << ")";
  else if (!std::isfinite(input_offset) || !std::isfinite(input_scaling) || !std::isfinite(zero_position_armed) ||
           !std::isfinite(zero_position_disarmed))
    why << "input_offset, input_scaling, zero_position_armed and zero_position_disarmed must be finite";
  else if (joint_control_type != "velocity" && joint_control_type != "position" && joint_control_type != "normalized")
    why << "joint_control_type '" << joint_control_type
        << "' is not one this simulator drives (velocity: a rotor speed, position: a servo angle, normalized: a "
           "fixed wing's actuator channel)";
  return why.str();
}

ControlChannels::ControlChannels(std::vector<ControlChannel> channels, int input_count)
    : channels_(std::move(channels)) {
  for (size_t i = 0; i < channels_.size(); ++i) {
    const std::string why = channels_[i].Validate(input_count);
    if (!why.empty())
      throw rotors_sim::SimError("<control_channels> channel " + std::to_string(i) + " '" + channels_[i].name +
                                 "': " + why);
  }
}

std::vector<double> ControlChannels::References(const std::vector<double>& u, bool armed) const {
  std::vector<double> reference(channels_.size());
  for (size_t i = 0; i < channels_.size(); ++i) {
    const ControlChannel& c = channels_[i];
    const bool have_input = c.input_index < static_cast<int>(u.size());
    reference[i] = armed && have_input ? (u[c.input_index] + c.input_offset) * c.input_scaling + c.zero_position_armed
                                       : c.zero_position_disarmed;
    // a rotor turns one way: the command the motor models take is a speed >= 0
    if (c.joint_control_type == "velocity" && reference[i] < 0.0) reference[i] = 0.0;
  }
  return reference;
}

}  // namespace rotors_gazebo_plugins
