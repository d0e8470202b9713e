// RotorS' <control_channels> (gazebo_mavlink_interface): how an autopilot's actuator outputs become
// the vehicle's motor command. Channel i of the list drives motor i of the vehicle (the order of the
// motor command, as RotorS' plugin publishes its references):
//   armed:     reference_i = (u[input_index_i] + input_offset_i) input_scaling_i + zero_position_armed_i
//   disarmed:  reference_i = zero_position_disarmed_i
// A rotor's reference is a speed [rad/s], a servo's (joint_control_type position) an angle [rad];
// ours, joint_control_type normalized: a fixed wing's normalized actuator channel (a control
// surface or the throttle, RotorS' mav_msgs/Actuators.normalized), in the order of the channels.
#pragma once

#include <string>
#include <vector>

namespace rotors_gazebo_plugins {

struct ControlChannel {
  std::string name;  ///< the <channel name="..."> attribute (for messages)
  int input_index = 0;
  double input_offset = 0.0;
  double input_scaling = 1.0;
  double zero_position_disarmed = 0.0;
  double zero_position_armed = 0.0;
  std::string joint_control_type = "velocity";  ///< velocity (a rotor), position (a servo), normalized (a fixed wing)
  std::string joint_name;                       ///< RotorS' field, kept for the record
  std::string gztopic;                          ///< RotorS' field, kept for the record
  /// "" or why the channel cannot work with `input_count` autopilot outputs.
  std::string Validate(int input_count) const;
};

class ControlChannels {
 public:
  ControlChannels() = default;
  /// Throws SimError naming the first bad channel.
  ControlChannels(std::vector<ControlChannel> channels, int input_count);
  /// The motor command for the autopilot's outputs `u` (size >= the highest input_index + 1), or for
  /// no outputs at all when disarmed.
  std::vector<double> References(const std::vector<double>& u, bool armed) const;
  std::vector<double> Disarmed() const { return References({}, false); }
  const std::vector<ControlChannel>& Channels() const { return channels_; }
  size_t size() const { return channels_.size(); }

 private:
  std::vector<ControlChannel> channels_;
};

}  // namespace rotors_gazebo_plugins
